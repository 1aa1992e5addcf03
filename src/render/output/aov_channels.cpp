#include "render/output/aov_channels.h"

#include <cmath>
#include <sstream>

#include "spectral/error.h"

namespace rimu {

AovSelection parse_aov_list(const std::string& text, const std::string& where) {
  AovSelection s;
  if (text == "all") return AovSelection::all();
  std::stringstream in(text);
  std::string name;
  int count = 0;
  while (std::getline(in, name, ',')) {
    bool* flag = name == "albedo"     ? &s.albedo
                 : name == "normal"   ? &s.normal
                 : name == "depth"    ? &s.depth
                 : name == "variance" ? &s.variance
                 : name == "halves"   ? &s.halves
                                      : nullptr;
    if (!flag)
      throw InputError({"", 0, where}, "unknown feature layer '" + name +
                                           "': give a comma-separated list of albedo, normal, depth, variance, halves, "
                                           "or all");
    if (*flag) throw InputError({"", 0, where}, "the feature layer '" + name + "' is named twice");
    *flag = true;
    ++count;
  }
  if (count == 0)
    throw InputError({"", 0, where}, "an empty list: give albedo, normal, depth, variance, halves, or all");
  return s;
}

std::string aov_list_text(const AovSelection& s) {
  std::string out;
  const auto add = [&](bool on, const char* name) {
    if (on) out += (out.empty() ? "" : ",") + std::string(name);
  };
  add(s.albedo, "albedo");
  add(s.normal, "normal");
  add(s.depth, "depth");
  add(s.variance, "variance");
  add(s.halves, "halves");
  return out;
}

namespace {
float finite(double v) { return std::isfinite(v) && std::fabs(v) < 3e38 ? float(v) : 0.0f; }
}  // namespace

std::vector<std::pair<std::string, std::vector<float>>> aov_channels(const FeatureBuffers& features, const Film& film,
                                                                      const AovSelection& selection) {
  std::vector<std::pair<std::string, std::vector<float>>> out;
  const PixelBounds& b = film.pixel_bounds();
  const std::array<std::string, 3>& names = film.response().channel_names();
  const FilmOutputTransform& transform = film.output_transform();
  const auto layer = [&](const std::string& name) -> std::vector<float>& {
    out.emplace_back(name, std::vector<float>());
    out.back().second.reserve(size_t(b.area()));
    return out.back().second;
  };
  const auto each_pixel = [&](auto&& f) {
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x) f(x, y);
  };
  if (selection.albedo) {
    for (int k = 0; k < 3; ++k) {
      std::vector<float>& v = layer("albedo." + names[size_t(k)]);
      each_pixel([&](int x, int y) { v.push_back(finite(features.albedo(x, y)[size_t(k)])); });
    }
    std::vector<float>& v = layer("albedo_variance");
    each_pixel([&](int x, int y) { v.push_back(finite(features.albedo_variance(x, y))); });
  }
  if (selection.normal) {
    static const char* axes[3] = {"N.X", "N.Y", "N.Z"};
    for (int k = 0; k < 3; ++k) {
      std::vector<float>& v = layer(axes[k]);
      each_pixel([&](int x, int y) {
        const Vec3 n = features.normal(x, y);
        v.push_back(finite(k == 0 ? n.x : k == 1 ? n.y : n.z));
      });
    }
    std::vector<float>& v = layer("N_variance");
    each_pixel([&](int x, int y) { v.push_back(finite(features.normal_variance(x, y))); });
  }
  if (selection.depth) {
    std::vector<float>& z = layer("depth.Z");
    each_pixel([&](int x, int y) { z.push_back(finite(features.depth(x, y))); });
    std::vector<float>& v = layer("depth_variance");
    each_pixel([&](int x, int y) { v.push_back(finite(features.depth_variance(x, y))); });
  }
  if (selection.variance) {
    // The written beauty is s·M·v: channel k's variance is s² Σ_j M_kj² Var_j (the channels' covariances, which
    // a white balance would mix in, are not kept).
    const Matrix3& m = transform.channel_matrix;
    const double s2 = transform.scale * transform.scale;
    std::vector<float>& v = layer("variance");
    each_pixel([&](int x, int y) {
      const std::array<double, 3> var = features.beauty_variance(x, y);
      double total = 0.0;
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) total += m.m[size_t(k)][size_t(j)] * m.m[size_t(k)][size_t(j)] * var[size_t(j)];
      v.push_back(finite(s2 * total / 3.0));
    });
  }
  if (selection.halves) {
    for (int half = 0; half < 2; ++half)
      for (int k = 0; k < 3; ++k) {
        std::vector<float>& v = layer(std::string(half == 0 ? "half_even." : "half_odd.") + names[size_t(k)]);
        each_pixel([&](int x, int y) { v.push_back(finite(transform.apply(features.half_value(half, x, y))[size_t(k)])); });
      }
  }
  return out;
}

}  // namespace rimu
