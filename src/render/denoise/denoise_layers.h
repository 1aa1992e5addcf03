// The EXR layers the denoiser reads, by name, and what it writes back: shared by `rimu --denoise` (from the render's
// memory) and `rimu denoise in.exr` (from a file).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "render/denoise/nfor_denoiser.h"

namespace rimu {

/// The layer names the denoiser needs besides the beauty, for a film whose channels are `channels` (X, Y, Z or
/// R, G, B): the halves, the variance, albedo, N and Z with their variances (render/output/aov_channels.h).
std::vector<std::string> denoise_layer_names(const std::array<std::string, 3>& channels);

/// Builds the denoiser's input from named single-channel images of width × height pixels; `layer` returns nullptr
/// for a layer that is missing. InputError naming `file` and listing every missing layer otherwise, with how to
/// render them (`--aov all`).
DenoiseInput denoise_input_from_layers(int width, int height, const std::array<std::string, 3>& channels,
                                       const std::function<const std::vector<float>*(const std::string&)>& layer,
                                       const std::string& file);

}  // namespace rimu
