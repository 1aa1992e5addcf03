#include "render/output/png_file.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <memory>

#include "spectral/error.h"

namespace rimu {
namespace {

// libpng reports an error through a callback that must not return: it keeps the message and jumps back to the
// setjmp in write_png_rgb8 (libpng's documented way; no C++ exception crosses libpng's C frames).
void on_error(png_structp png, png_const_charp message) {
  *static_cast<std::string*>(png_get_error_ptr(png)) = message ? message : "libpng error";
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}

// The part of the write libpng may jump out of: only plain values here, so the jump leaves nothing half-made
// (false: libpng failed, its message in the error pointer's string).
bool write_image(png_structp png, png_infop info, std::FILE* file, int width, int height, const uint8_t* pixels,
                 png_text* text, int text_count, bool srgb_encoded) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (srgb_encoded) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
  if (text_count > 0) png_set_text(png, info, text, text_count);
  png_write_info(png, info);
  const size_t row_bytes = size_t(width) * 3;
  for (int y = 0; y < height; ++y) png_write_row(png, pixels + size_t(y) * row_bytes);
  png_write_end(png, nullptr);
  return true;
}

}  // namespace

void write_png_rgb8(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& pixels,
                    const PngMetadata& metadata) {
  const auto fail = [&path](const std::string& what) {
    throw RenderError("cannot write the PNG " + path.string() + ": " + what);
  };
  if (width <= 0 || height <= 0 || pixels.size() != size_t(width) * size_t(height) * 3)
    fail("the image is " + std::to_string(width) + " x " + std::to_string(height) + " pixels but holds " +
         std::to_string(pixels.size()) + " bytes");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!file) fail("cannot open it for writing");
  std::string error;
  std::vector<png_text> text(metadata.text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    text[i].compression = PNG_TEXT_COMPRESSION_NONE;
    text[i].key = const_cast<char*>(metadata.text[i].first.c_str());
    text[i].text = const_cast<char*>(metadata.text[i].second.c_str());
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, on_error, on_warning);
  if (!png) fail("libpng cannot allocate its writer");
  png_infop info = png_create_info_struct(png);
  const bool written = info && write_image(png, info, file.get(), width, height, pixels.data(), text.data(),
                                           int(text.size()), metadata.srgb_encoded);
  png_destroy_write_struct(&png, info ? &info : nullptr);
  if (!written) fail(info ? error : "libpng cannot allocate its header");
  if (std::fflush(file.get()) != 0 || std::ferror(file.get())) fail("the write failed (is the disk full?)");
}

}  // namespace rimu
