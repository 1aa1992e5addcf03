#include "render/denoise/denoise_layers.h"

#include "spectral/error.h"

namespace rimu {

std::vector<std::string> denoise_layer_names(const std::array<std::string, 3>& c) {
  std::vector<std::string> names;
  for (const char* half : {"half_even.", "half_odd."})
    for (const std::string& channel : c) names.push_back(half + channel);
  names.push_back("variance");
  for (const std::string& channel : c) names.push_back("albedo." + channel);
  names.push_back("albedo_variance");
  for (const char* n : {"N.X", "N.Y", "N.Z", "N_variance", "depth.Z", "depth_variance"}) names.push_back(n);
  return names;
}

DenoiseInput denoise_input_from_layers(int width, int height, const std::array<std::string, 3>& c,
                                       const std::function<const std::vector<float>*(const std::string&)>& layer,
                                       const std::string& file) {
  std::string missing;
  for (const std::string& name : denoise_layer_names(c))
    if (!layer(name)) missing += (missing.empty() ? "" : ", ") + name;
  if (!missing.empty())
    throw InputError({file, 0, ""},
                     "the denoiser needs the render's feature layers and half buffers, and this image lacks " + missing +
                         ": render it with `rimu scene.json --aov all` (or --aov albedo,normal,depth,variance,halves)");
  DenoiseInput in;
  in.width = width;
  in.height = height;
  const size_t n = size_t(width) * size_t(height);
  const auto interleave = [&](const std::string& prefix, const std::array<std::string, 3>& channels) {
    std::vector<float> out(3 * n);
    for (int k = 0; k < 3; ++k) {
      const std::vector<float>& v = *layer(prefix + channels[size_t(k)]);
      if (v.size() != n) throw InputError({file, 0, prefix + channels[size_t(k)]}, "the layer has the wrong size");
      for (size_t i = 0; i < n; ++i) out[3 * i + size_t(k)] = v[i];
    }
    return out;
  };
  const auto single = [&](const std::string& name) {
    const std::vector<float>& v = *layer(name);
    if (v.size() != n) throw InputError({file, 0, name}, "the layer has the wrong size");
    return v;
  };
  in.halves[0] = interleave("half_even.", c);
  in.halves[1] = interleave("half_odd.", c);
  in.variance = single("variance");
  in.albedo = interleave("albedo.", c);
  in.normal = interleave("N.", {"X", "Y", "Z"});
  in.depth = single("depth.Z");
  in.albedo_variance = single("albedo_variance");
  in.normal_variance = single("N_variance");
  in.depth_variance = single("depth_variance");
  return in;
}

}  // namespace rimu
