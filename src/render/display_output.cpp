#include "render/display_output.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/output_file.h"
#include "render/version.h"

namespace rimu {

std::vector<uint8_t> display_pixels(const Film& film, const DisplayOptions& options) {
  const DisplayTransform transform(film.response().kind(), options);
  const PixelBounds& b = film.pixel_bounds();
  const size_t pixel_count = size_t(b.area());
  std::vector<float> rgb;
  rgb.reserve(pixel_count * 3);
  for (int y = b.y0; y < b.y1; ++y) {
    for (int x = b.x0; x < b.x1; ++x) {
      const auto v = film.output_value(x, y);
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

void write_display_png(const std::filesystem::path& path, const Film& film, const DisplayOptions& options) {
  const std::vector<uint8_t> pixels = display_pixels(film, options);  // InputErrors before touching the disk
  const PixelBounds& b = film.pixel_bounds();
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    // OpenImageIO reports failure through return values and geterror(); turn each into an exception here.
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create("png");
    if (!out) throw std::runtime_error("OpenImageIO has no PNG writer: " + OIIO::geterror());
    OIIO::ImageSpec spec(b.width(), b.height(), 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Software", std::string("Rimu ") + rimu_version());
    spec.attribute("rimu:view", options.view);
    if (!out->open(temporary.string(), spec)) throw std::runtime_error(out->geterror());
    if (!out->write_image(OIIO::TypeDesc::UINT8, pixels.data())) {
      const std::string error = out->geterror();
      out->close();
      throw std::runtime_error(error);
    }
    if (!out->close()) throw std::runtime_error(out->geterror());
  });
}

}  // namespace rimu
