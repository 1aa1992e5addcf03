// `rimu denoise in.exr -o out.exr`: denoising a render written with its feature layers (`rimu --aov all`).
#pragma once

#include <filesystem>
#include <iosfwd>

#include "render/denoise/nfor_denoiser.h"

namespace rimu {

/// Reads `input` (a render with the layers denoise_layer_names() lists: `rimu scene.json --aov all`), denoises its
/// beauty and writes `output` atomically: every channel and attribute of the input, the beauty replaced by the
/// denoised image, the noisy beauty kept as "noisy.c0" … "noisy.c2", and "rimu:denoised" saying how. The beauty's
/// channels are X, Y, Z (XYZ films) or R, G, B (camera films). InputError naming the file, and nothing written, when
/// the input is no OpenEXR file, lacks a layer (all missing ones are named), is a partial render (its exact sums
/// cannot be denoised: merge it with `rimu merge --final` first) or when output names the input. A line on `log`
/// says what was done and how long it took.
void denoise_exr_file(const std::filesystem::path& input, const std::filesystem::path& output,
                      const DenoiseSettings& settings, std::ostream& log);

}  // namespace rimu
