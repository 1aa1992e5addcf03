#include "render/output/display_output.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/image/image_library.h"
#include "render/output/output_file.h"
#include "render/output/png_file.h"
#include "spectral/version.h"
#include "spectral/error.h"

namespace rimu {
namespace {

// A camera film with a camera-to-XYZ matrix is shown as the XYZ it stands for.
bool converts_camera_to_xyz(const Film& film, const DisplayOptions& options) {
  return film.response().kind() == ResponseKind::camera_rgb && options.camera_to_xyz.has_value();
}

std::array<double, 3> display_input(const Film& film, const DisplayOptions& options, int x, int y) {
  const std::array<double, 3> v = film.output_value(x, y);
  return converts_camera_to_xyz(film, options) ? options.camera_to_xyz->apply(v) : v;
}

}  // namespace

std::vector<uint8_t> display_pixels(const Film& film, const DisplayOptions& options) {
  const ResponseKind space = converts_camera_to_xyz(film, options) ? ResponseKind::cie_xyz : film.response().kind();
  const DisplayTransform transform(space, options);
  const PixelBounds& b = film.pixel_bounds();
  const size_t pixel_count = size_t(b.area());
  std::vector<float> rgb;
  rgb.reserve(pixel_count * 3);
  for (int y = b.y0; y < b.y1; ++y) {
    for (int x = b.x0; x < b.x1; ++x) {
      const auto v = display_input(film, options, x, y);
      rgb.insert(rgb.end(), {float(v[0]), float(v[1]), float(v[2])});
    }
  }
  transform.apply(rgb, pixel_count);
  std::vector<uint8_t> out(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    const float v = std::isnan(rgb[i]) ? 0.0f : std::clamp(rgb[i], 0.0f, 1.0f);
    out[i] = uint8_t(std::lround(v * 255.0f));
  }
  return out;
}

double mean_display_luminance(const Film& film, const DisplayOptions& options) {
  if (film.response().kind() != ResponseKind::cie_xyz && !converts_camera_to_xyz(film, options)) return 0.0;
  const PixelBounds& b = film.pixel_bounds();
  double sum = 0.0;
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x) sum += display_input(film, options, x, y)[1];
  return b.area() > 0 ? sum / double(b.area()) : 0.0;
}

DisplayLevels display_levels(const std::vector<uint8_t>& rgb) {
  DisplayLevels levels;
  const size_t pixel_count = rgb.size() / 3;
  if (pixel_count == 0) return levels;
  size_t black = 0, clipped = 0;
  double sum = 0.0;
  for (size_t p = 0; p < pixel_count; ++p) {
    const uint8_t* v = &rgb[p * 3];
    black += (v[0] <= kNearlyBlackCode && v[1] <= kNearlyBlackCode && v[2] <= kNearlyBlackCode);
    clipped += (v[0] == 255 || v[1] == 255 || v[2] == 255);
    sum += double(v[0]) + double(v[1]) + double(v[2]);
  }
  levels.black_fraction = double(black) / double(pixel_count);
  levels.clipped_fraction = double(clipped) / double(pixel_count);
  levels.mean_code = sum / double(rgb.size());
  return levels;
}

std::string display_image_format(const std::filesystem::path& path, const std::string& option) {
  const std::string extension = lower_case_extension(path);
  std::string format;
  if (extension == "png") format = "png";
  if (extension == "jpg" || extension == "jpeg") format = "jpeg";
  if (extension == "tif" || extension == "tiff") format = "tiff";
  if (format.empty()) {
    const std::string hint = extension == "exr" ? " (the scene-referred OpenEXR image is written by -o)" : "";
    throw InputError({path.string(), 0, option},
                     "a display image is written as 8-bit sRGB PNG, JPEG or TIFF, chosen by the extension: expected "
                     ".png, .jpg, .jpeg, .tif or .tiff, got '" +
                         path.extension().string() + "'" + hint);
  }
  // PNG is written in-process (png_file.h); JPEG and TIFF by OpenImageIO, whose build is asked before rendering.
  if (std::string error; format != "png" && !image_library().can_write(format, error))
    throw InputError({path.string(), 0, option}, "this OpenImageIO build cannot write " + format + ": " + error);
  return format;
}

DisplayLevels write_display_image(const std::filesystem::path& path, const Film& film, const DisplayOptions& options) {
  const std::string format = display_image_format(path);
  const std::vector<uint8_t> pixels = display_pixels(film, options);  // InputErrors before touching the disk
  const PixelBounds& b = film.pixel_bounds();
  const std::string software = std::string("Rimu ") + rimu_version();
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    // The views other than Raw end in the sRGB display encoding (data/ocio/config.ocio): say so in the file.
    if (format == "png") {
      write_png_rgb8(temporary, b.width(), b.height(), pixels,
                     PngMetadata{{{"Software", software}, {"rimu:view", options.view}}, options.view != "Raw"});
      return;
    }
    std::string error;
    if (!image_library().write_rgb8(temporary.string(), format, b.width(), b.height(), pixels,
                                    software, options.view, options.view != "Raw", error))
      throw std::runtime_error(error);
  });
  return display_levels(pixels);
}

}  // namespace rimu
