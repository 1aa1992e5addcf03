// Shared by the light-group tests (light_groups_test.cpp, light_groups_relight_test.cpp,
// light_groups_resume_test.cpp): a tiny job on the example scene, an EXR's channels by name, the layers-sum-to-the-
// beauty check, the `--group x=0` exactness check, and a copy of an EXR with its header edited (to make the file an
// interrupted render or an older Rimu would have written).
#pragma once

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "render/output/exr_display_source.h"
#include "render/output/exr_relight.h"
#include "render/render_job.h"
#include "test_support.h"

namespace rimu::test {

inline std::filesystem::path light_groups_example() {
  return library().root() / "scenes" / "examples" / "light_groups.json";
}
inline const std::vector<std::string> kExampleGroups{"sky", "sun", "lamps", "ungrouped"};

inline RenderJob tiny_job(const std::filesystem::path& scene, const std::filesystem::path& out,
                          std::optional<SampleRange> samples = std::nullopt) {
  RenderJob job;
  job.scene = scene;
  job.width = 24;
  job.height = 16;
  job.samples_per_pixel = 8;
  job.threads = 2;
  job.quiet = true;
  job.samples = samples;
  job.exr_output = out;
  return job;
}

inline void render(const RenderJob& job) {
  std::ostringstream log;
  run_render_job(job, log);
}

/// An EXR's float channels by name, and its header's light groups ("" when it has none).
struct ExrChannels {
  std::map<std::string, std::vector<float>> channels;
  std::string light_groups;
  bool has_layer = false;  ///< some channel name holds a '.' (a layer)
};

inline ExrChannels read_channels(const std::filesystem::path& path) {
  Imf::InputFile file(path.c_str());
  const Imf::Header& h = file.header();
  ExrChannels out;
  if (const auto* a = h.findTypedAttribute<Imf::StringAttribute>("rimu:lightGroups")) out.light_groups = a->value();
  const Imath::Box2i dw = h.dataWindow();
  const int width = dw.max.x - dw.min.x + 1, height = dw.max.y - dw.min.y + 1;
  Imf::FrameBuffer frame;
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it) {
    const std::string name = it.name();
    if (it.channel().type == Imf::UINT) continue;  // a partial's exact sums
    out.has_layer = out.has_layer || name.find('.') != std::string::npos;
    auto& values = out.channels[name];
    values.resize(size_t(width) * size_t(height));
    char* origin = reinterpret_cast<char*>(values.data()) - (ptrdiff_t(dw.min.y) * width + dw.min.x) * ptrdiff_t(sizeof(float));
    frame.insert(name, Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * size_t(width)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(dw.min.y, dw.max.y);
  return out;
}

/// The relative bound on |Σ layers − beauty| for one written value. Each camera sample's beauty is a float sum of
/// at most n emitted contributions (NEE and an emitter hit per vertex, every light at infinity on escape:
/// n ≤ 2·(max_depth + 1) + 2 = 16 in the example), each group's the float sum of its share, so they differ by
/// ≤ (n − 1)·2⁻²⁴ of the sum of contributions; the film's estimator rounds each layer ~5 more times in float (÷ pdf,
/// × filter weight, × response, the 4-lane sum), the double sums add nothing visible, and the EXR's float32 rounds
/// each of the 1 + G written values once more. With G = 4: (15 + 5 + 5)·2⁻²⁴ relative to beauty + Σ layers;
/// 32·2⁻²⁴ covers it. A spectral bin's estimate has fewer roundings (no response, no lane sum): the same bound.
inline constexpr double kLayerSumBound = 32.0 * 0x1p-24;

/// Σ_g `<g>.<channel>` against `<channel>` over every pixel, for each of `channels` (the beauty's X, Y, Z when
/// empty); and every group lit something (the test then sees every kind of light).
inline void check_layers_sum_to_beauty(const ExrChannels& exr, const std::vector<std::string>& groups,
                                       std::vector<std::string> channels = {}) {
  if (channels.empty()) channels = {"X", "Y", "Z"};
  for (const std::string& c : channels) {
    const auto& beauty = exr.channels.at(c);
    double worst = 0.0;
    for (size_t i = 0; i < beauty.size(); ++i) {
      double sum = 0.0, magnitude = double(beauty[i]);
      for (const std::string& g : groups) {
        const float v = exr.channels.at(g + "." + c)[i];
        REQUIRE(v >= 0.0f);
        sum += double(v);
        magnitude += double(v);
      }
      if (magnitude > 0.0) worst = std::max(worst, std::abs(sum - double(beauty[i])) / magnitude);
    }
    CAPTURE(c);
    CHECK(worst <= kLayerSumBound);
  }
  size_t nonzero_layers = 0;
  for (const std::string& g : groups) {
    double total = 0.0;
    for (float v : exr.channels.at(g + ".Y")) total += double(v);
    if (total > 0.0) ++nonzero_layers;
  }
  CHECK(nonzero_layers == groups.size());
}

/// Every written channel of `b` against `a`'s of the same name, relative to a's value: what two renders of the same
/// samples, summed in another grouping of the double sums, agree to (one float32 rounding each: 2⁻²³).
inline void check_same_image(const ExrChannels& a, const ExrChannels& b) {
  for (const auto& [name, values] : a.channels) {
    CAPTURE(name);
    REQUIRE(b.channels.count(name) == 1);
    const auto& other = b.channels.at(name);
    double worst = 0.0;
    for (size_t i = 0; i < values.size(); ++i)
      if (values[i] != 0.0f) worst = std::max(worst, std::abs(double(other[i]) - values[i]) / std::abs(double(values[i])));
    CHECK(worst <= 0x1p-23);
  }
}

/// `rimu display FILE --group <group>=0` on `path` (through read_exr_for_display, as the tool does) removes that
/// group's light exactly: every pixel is the file's beauty minus the group's layer (in double: the rebalance's
/// subtraction, the division by the weight and the exposure scale against the reference's two divisions, two scales
/// and a subtraction, ≤ 6·2⁻⁵³ of the two), the group's layer is exactly 0, and what is left is the other layers' sum (within the render's own float
/// rounding, kLayerSumBound).
inline void check_group_removed_exactly(const std::filesystem::path& path, const std::string& group) {
  const ExrDisplaySource plain = read_exr_for_display(path, library());
  const ExrDisplaySource relit = read_exr_for_display(path, library());
  rebalance_light_groups(*relit.film, {{group, 0.0}}, path.string());
  const std::vector<std::string>& groups = plain.film->light_groups();
  const int removed = int(std::find(groups.begin(), groups.end(), group) - groups.begin());
  REQUIRE(removed < int(groups.size()));
  const PixelBounds& b = plain.film->pixel_bounds();
  double worst_exact = 0.0, worst_rest = 0.0, lit = 0.0;
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x) {
      const auto beauty = plain.film->output_value(x, y), layer = plain.film->group_output_value(x, y, removed);
      const auto shown = relit.film->output_value(x, y);
      for (size_t c = 0; c < 3; ++c) {
        lit += layer[c];
        const double magnitude = std::abs(beauty[c]) + std::abs(layer[c]);
        if (magnitude > 0.0) worst_exact = std::max(worst_exact, std::abs(shown[c] - (beauty[c] - layer[c])) / magnitude);
        CHECK(relit.film->group_output_value(x, y, removed)[c] == 0.0);
        double rest = 0.0, rest_magnitude = std::abs(beauty[c]);
        for (int g = 0; g < int(groups.size()); ++g) {
          const double v = plain.film->group_output_value(x, y, g)[c];
          rest_magnitude += std::abs(v);
          if (g != removed) rest += v;
        }
        if (rest_magnitude > 0.0) worst_rest = std::max(worst_rest, std::abs(shown[c] - rest) / rest_magnitude);
      }
    }
  CAPTURE(path.string());
  CAPTURE(group);
  CHECK(lit > 0.0);  // the group had light to remove
  CHECK(worst_exact <= 6 * 0x1p-53);
  CHECK(worst_rest <= kLayerSumBound);
}

/// Copies the EXR at `from` to `to` with every channel as it is and the header changed by `edit` (attributes set,
/// replaced or erased), as another writer would have written the same pixels.
inline void copy_exr_with_header(const std::filesystem::path& from, const std::filesystem::path& to,
                                 const std::function<void(Imf::Header&)>& edit) {
  Imf::InputFile in(from.c_str());
  Imf::Header header = in.header();
  edit(header);
  const Imath::Box2i dw = header.dataWindow();
  const size_t width = size_t(dw.max.x - dw.min.x + 1), height = size_t(dw.max.y - dw.min.y + 1);
  std::vector<std::vector<uint32_t>> buffers;  // 4 bytes per value: FLOAT and UINT (a half fits too)
  Imf::FrameBuffer frame;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    buffers.emplace_back(width * height);
    char* origin = reinterpret_cast<char*>(buffers.back().data()) -
                   (ptrdiff_t(dw.min.y) * ptrdiff_t(width) + dw.min.x) * ptrdiff_t(sizeof(uint32_t));
    frame.insert(it.name(), Imf::Slice(it.channel().type, origin, sizeof(uint32_t), sizeof(uint32_t) * width));
  }
  in.setFrameBuffer(frame);
  in.readPixels(dw.min.y, dw.max.y);
  Imf::OutputFile out(to.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(int(height));
}

}  // namespace rimu::test
