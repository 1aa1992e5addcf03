// A render's two outputs, the scene-referred OpenEXR image (-o) and the optional display image (--png): checked
// before anything slow happens, and the EXR written with the warnings its values call for.
#pragma once

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <vector>

#include "render/output/exr_output.h"

namespace rimu {

/// -o is OpenEXR and must say so, --png picks its format by its extension, the two are different files, and a
/// file can be created in each folder. InputError naming the option otherwise.
void check_render_outputs(const std::filesystem::path& exr, const std::optional<std::filesystem::path>& png);

/// --preview (the display image rewritten while rendering): a display format by its extension, neither -o nor
/// --png, a file that can be created. InputError naming --preview otherwise.
void check_preview_output(const std::filesystem::path& preview, const std::filesystem::path& exr,
                          const std::optional<std::filesystem::path>& png);

/// --preview-error (the adaptive render's error heat map): a PNG gnuplot can draw, none of -o, --png, --preview.
/// InputError naming --preview-error otherwise.
void check_preview_error_output(const std::filesystem::path& heat_map, const std::filesystem::path& exr,
                                const std::optional<std::filesystem::path>& png,
                                const std::optional<std::filesystem::path>& preview);

/// No output may be a file the render reads (`files_read`: the scene and every file loading it read, also through
/// a link). Checkpoints are written to -o, so they are covered too.
void check_render_outputs_not_inputs(const std::filesystem::path& exr,
                                     const std::optional<std::filesystem::path>& png,
                                     const std::vector<std::filesystem::path>& files_read,
                                     const std::optional<std::filesystem::path>& preview = std::nullopt,
                                     const std::optional<std::filesystem::path>& preview_error = std::nullopt);

/// write_exr(), with a warning to `log` when half floats lose values and when non-finite or overflowing values
/// were replaced.
void write_render_exr(const std::filesystem::path& path, const Film& film, const ExrOptions& options, std::ostream& log);

}  // namespace rimu
