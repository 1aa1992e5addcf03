#include "render/output/render_outputs.h"

#include <ostream>
#include <string>

#include "render/output/display_output.h"
#include "render/output/plot_output.h"
#include "spectral/error.h"
#include "spectral/io/output_file.h"

namespace rimu {

void check_render_outputs(const std::filesystem::path& exr, const std::optional<std::filesystem::path>& png) {
  if (lower_case_extension(exr) != "exr")
    throw InputError({exr.string(), 0, "-o"},
                     "the scene-referred OpenEXR image needs a name ending in .exr (got '" +
                         exr.extension().string() + "'); a display image (.png, .jpg, .tif) is --png");
  if (png) {
    if (same_output_file(exr, *png))
      throw InputError({png->string(), 0, "--png"},
                       "-o and --png name the same file; the display image would replace the OpenEXR image");
    display_image_format(*png, "--png");
  }
  check_output_path(exr);
  if (png) check_output_path(*png);
}

void check_preview_output(const std::filesystem::path& preview, const std::filesystem::path& exr,
                          const std::optional<std::filesystem::path>& png) {
  if (same_output_file(exr, preview) || (png && same_output_file(*png, preview)))
    throw InputError({preview.string(), 0, "--preview"},
                     std::string("names the same file as ") + (same_output_file(exr, preview) ? "-o" : "--png") +
                         "; the preview is rewritten while rendering, so it needs a file of its own");
  display_image_format(preview, "--preview");
  check_output_path(preview);
}

void check_preview_error_output(const std::filesystem::path& heat_map, const std::filesystem::path& exr,
                                const std::optional<std::filesystem::path>& png,
                                const std::optional<std::filesystem::path>& preview) {
  const SourceLocation where{heat_map.string(), 0, "--preview-error"};
  check_plot_png(heat_map, where);
  for (const auto& [other, option] : {std::pair{std::optional<std::filesystem::path>(exr), "-o"},
                                      std::pair{png, "--png"}, std::pair{preview, "--preview"}})
    if (other && same_output_file(*other, heat_map))
      throw InputError(where, std::string("names the same file as ") + option +
                                  "; the heat map is rewritten while rendering, so it needs a file of its own");
}

// The list is the readers' own (InputFileLog), not a guess from the scene's text.
void check_render_outputs_not_inputs(const std::filesystem::path& exr,
                                     const std::optional<std::filesystem::path>& png,
                                     const std::vector<std::filesystem::path>& files_read,
                                     const std::optional<std::filesystem::path>& preview,
                                     const std::optional<std::filesystem::path>& preview_error) {
  std::vector<InputFile> inputs;
  for (const std::filesystem::path& file : files_read) inputs.push_back({file, "read by the scene"});
  check_output_not_input(exr, "-o", inputs);
  if (png) check_output_not_input(*png, "--png", inputs);
  if (preview) check_output_not_input(*preview, "--preview", inputs);
  if (preview_error) check_output_not_input(*preview_error, "--preview-error", inputs);
}

void write_render_exr(const std::filesystem::path& path, const Film& film, const ExrOptions& options, std::ostream& log) {
  if (options.pixel_type == ExrPixelType::half) {
    const std::string warning = half_range_warning(half_range_counts(film), path.string());
    if (!warning.empty()) log << warning << "\n";
  }
  const size_t replaced = write_exr(path, film, options);
  if (replaced > 0)
    log << "rimu: warning: " << replaced << " values of " << path.string()
        << " were NaN or beyond the largest float and were written as 0 or the largest value (see "
           "rimu:nonFiniteValuesReplaced); lower the exposure\n";
}

}  // namespace rimu
