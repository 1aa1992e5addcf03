#include "render/image/image_file.h"

#include <algorithm>
#include <optional>

#include "render/image/exr_header_check.h"
#include "render/image/exr_image_decoder.h"
#include "render/image/image_library.h"
#include "render/image/stb_image_decoder.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {

void check_image_header(const DecodedImage& header, std::uintmax_t file_bytes, const std::string& file) {
  const auto fail = [&file](const std::string& what) { throw InputError({file, 0, ""}, what); };
  if (header.width <= 0 || header.height <= 0 || header.channels <= 0)
    fail("the image is empty (its header says " + std::to_string(header.width) + " x " +
         std::to_string(header.height) + " pixels, " + std::to_string(header.channels) + " channels)");
  const std::uint64_t w = std::uint64_t(header.width), h = std::uint64_t(header.height);
  const std::uint64_t pixels = w * h;  // both < 2^31: no overflow
  const std::string size = std::to_string(w) + " x " + std::to_string(h) + " pixels";
  if (pixels > kMaxImagePixels)
    fail("the image has " + size + ", more than the limit of " + std::to_string(kMaxImagePixels) +
         " pixels (16384 x 8192): as a texture it would need about " + format_bytes(100 * pixels) +
         " of memory; reduce its resolution");
  if (header.format_name == "pnm") {
    // PPM, PGM, PBM and PFM store their samples uncompressed (binary: bits_per_sample each, rows padded to a
    // byte; ascii: at least two characters each), so the pixel data alone must fit in the file.
    const std::uint64_t bits = std::uint64_t(std::max(header.bits_per_sample, 1));
    const std::uint64_t row_bytes = (w * std::uint64_t(header.channels) * bits + 7) / 8;
    if (row_bytes * h > file_bytes)
      fail("the header says " + size + " of " + std::to_string(header.channels) + " channels (" +
           format_bytes(row_bytes * h) + " of pixel data), but the file has only " + format_bytes(file_bytes) +
           " (is it truncated?)");
  } else if (pixels > kMaxPixelsPerFileByte * file_bytes) {
    fail("the header says " + size + ", more than a file of " + format_bytes(file_bytes) +
         " can hold (at most " + std::to_string(kMaxPixelsPerFileByte) +
         " pixels per byte, beyond any image codec's compression): the header is corrupt");
  }
}

namespace {

// The file was read twice (header, then pixels): one that changed in between is refused rather than read past its
// pixels.
void check_same_image(const DecodedImage& image, const DecodedImage& header, const std::filesystem::path& path) {
  if (image.width != header.width || image.height != header.height || image.channels != header.channels ||
      image.pixels.size() + image.bytes.size() + image.halves.size() !=
          std::size_t(image.width) * std::size_t(image.height) * std::size_t(image.channels))
    throw InputError({path.string(), 0, ""}, "the image changed while it was read");
}

}  // namespace

DecodedImage read_image_file(const std::filesystem::path& path, bool as_stored, bool compact) {
  const std::uintmax_t file_bytes = check_input_file(path, kMaxBinaryFileBytes);  // a FIFO would block the library
  // PNG, JPEG, TGA and BMP in-process, without loading OpenImageIO (stb_image_decoder.h).
  if (const std::optional<DecodedImage> header = stb_image_header(path, as_stored)) {
    check_image_header(*header, file_bytes, path.string());
    DecodedImage image = stb_image_pixels(path, *header, compact);
    check_same_image(image, *header, path);
    return image;
  }
  // OpenEXR images of R, G, B (A) or Y (A) with OpenEXR itself, which Rimu links anyway (exr_image_decoder.h).
  if (const std::optional<DecodedImage> header = exr_image_header(path)) {
    check_image_header(*header, file_bytes, path.string());
    DecodedImage image = exr_image_pixels(path, *header, compact);
    check_same_image(image, *header, path);
    return image;
  }
  const ImageModuleApi& library = image_reader_for(path);
  // OpenEXR allocates header attributes at their claimed size inside the library: check them first.
  check_exr_header_sizes(path, file_bytes);
  DecodedImage image;
  image.as_stored = as_stored;
  image.bytes_if_8bit = compact;
  if (std::string error; !library.read_header(path.string(), image, error))
    throw InputError({path.string(), 0, ""}, "cannot read the image: " + error);
  check_image_header(image, file_bytes, path.string());
  const DecodedImage header = image;
  if (std::string error; !library.read_pixels(path.string(), image, error))
    throw InputError({path.string(), 0, ""}, error);
  check_same_image(image, header, path);
  return image;
}

ImageSize read_image_size(const std::filesystem::path& path) {
  const std::uintmax_t file_bytes = check_input_file(path, kMaxBinaryFileBytes);
  std::optional<DecodedImage> header = stb_image_header(path, false);
  if (!header) header = exr_image_header(path);
  if (!header) {
    check_exr_header_sizes(path, file_bytes);
    header.emplace();
    if (std::string error; !image_reader_for(path).read_header(path.string(), *header, error))
      throw InputError({path.string(), 0, ""}, "cannot read the image: " + error);
  }
  check_image_header(*header, file_bytes, path.string());
  return {header->width, header->height};
}

}  // namespace rimu
