// libFuzzer target: image files (PNG, JPEG, TGA, BMP, OpenEXR, PFM/PPM, Radiance HDR) read as the renderer reads
// image textures, environment maps and alpha masks: RgbImage::read and AlphaMask::read, i.e. Rimu's header checks
// (render/image/image_file.h) and then stb_image (PNG, JPEG, TGA, BMP: render/image/stb_image_decoder.h), FreeImage
// (PFM, in librimu_freeimage.so) or OpenImageIO's decoder in the module the renderer loads (librimu_oiio.so; both
// modules built beside this target). Debian's libstb, FreeImage and OpenImageIO are not instrumented: the fuzzer sees Rimu's side of each call (the header checks, the
// truncation check, the conversions), and a decoder's own overflow shows only if it corrupts Rimu's memory.
#include <cstring>

#include "fuzz_support.h"
#include "render/image/alpha_mask.h"
#include "render/image/rgb_image.h"

namespace {

// OpenImageIO picks its reader by the file's extension (and tries the others when that one fails), and Rimu sends a
// TGA to stb_image by its extension: name the input after its signature, so each mutation reaches the decoder of
// the format it looks like.
const char* extension_of(const uint8_t* data, size_t size) {
  const auto starts = [&](const char* magic) { return size >= std::strlen(magic) && std::memcmp(data, magic, std::strlen(magic)) == 0; };
  if (starts("\x89PNG")) return ".png";
  if (starts("\x76\x2f\x31\x01")) return ".exr";
  if (starts("PF") || starts("Pf")) return ".pfm";
  if (starts("P")) return ".ppm";
  if (starts("#?")) return ".hdr";
  if (starts("\xff\xd8\xff")) return ".jpg";
  if (starts("BM")) return ".bmp";
  // TGA has no signature: no colour map and an image type of true colour or grey, raw or RLE (byte 2).
  if (size >= 18 && data[1] == 0 && (data[2] == 2 || data[2] == 3 || data[2] == 10 || data[2] == 11)) return ".tga";
  return ".png";
}

}  // namespace

// OpenImageIO keeps an ImageInput's error text in its own per-thread table (ImageInput::geterror), which the
// library frees at thread exit rather than with the reader: LeakSanitizer reports those strings (62 bytes in the
// first run) as leaks of Debian's uninstrumented libOpenImageIO. They are the library's, not Rimu's: suppressed
// for that library only, so a leak in Rimu's own code or in the module still stops the target.
extern "C" const char* __lsan_default_suppressions() { return "leak:libOpenImageIO.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rimu::fuzz::run_reader("fuzz_image", [&] {
    const std::filesystem::path file = rimu::fuzz::write_private_file(data, size, extension_of(data, size));
    // As an image texture or environment map (the encoding the loader would choose), then as an alpha mask.
    const rimu::RgbImage image = rimu::RgbImage::read(file, rimu::default_encoding_for(file));
    (void)image.bilinear({0.5f, 0.5f});
    const rimu::AlphaMask mask = rimu::AlphaMask::read(file, 0, false, false, true);
    (void)mask.evaluate({0.25f, 0.75f});
  });
}
