#include "render/image/stb_image_decoder.h"

#include <stb_image.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "spectral/error.h"

namespace rimu {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

std::uint32_t little_endian(const unsigned char* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

bool ends_with_tga(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".tga";
}

// OpenImageIO's name for the format of a file starting with `head` (n bytes), if it is one stb_image_decoder.h
// takes; "" otherwise (PNM and Radiance HDR among them: stb_image_decoder.h says why). Signatures decide, except
// for TGA, which has none: there the extension (as OpenImageIO tries the extension's reader first) and the header
// fields that select what stb_image reads as OpenImageIO does.
std::string format_of(const std::filesystem::path& path, const unsigned char* head, size_t n) {
  const auto starts = [&](const char* magic, size_t length) {
    return n >= length && std::memcmp(head, magic, length) == 0;
  };
  if (starts("\x89PNG\r\n\x1a\n", 8)) return "png";
  if (starts("\xff\xd8\xff", 3)) return "jpeg";
  // BMP: a BITMAPINFOHEADER or later (size ≥ 40), 24 bits per pixel, uncompressed (BI_RGB).
  if (starts("BM", 2) && n >= 34 && little_endian(head + 14, 4) >= 40 && little_endian(head + 28, 2) == 24 &&
      little_endian(head + 30, 4) == 0)
    return "bmp";
  // TGA: no colour map; true colour (2, RLE 10) of 24 bits or grey (3, RLE 11) of 8; no alpha bits; left to right.
  if (ends_with_tga(path) && n >= 18 && head[1] == 0 && (head[17] & 0x1f) == 0 &&
      (((head[2] == 2 || head[2] == 10) && head[16] == 24) || ((head[2] == 3 || head[2] == 11) && head[16] == 8)))
    return "targa";
  return "";
}

// stb_image's I/O callbacks over a FILE, as its own stdio ones, noting whether the decoder asked for bytes past the
// end: stb_image reads zeros there without an error for TGA and BMP (and for JPEG pads the entropy data).
// It refills its 128-byte buffer with reads of 128 bytes, which get fewer at the end of a complete file; every
// other read is an exact one (pixel or chunk data). So a read that gets nothing, or an exact read that gets fewer
// bytes than it asked for, means the file ends before the decoder's data do.
constexpr int kStbRefillBytes = 128;  // sizeof stbi__context::buffer_start (stb_image.h, v2.27)

struct Reader {
  std::FILE* file;
  bool ran_out = false;
};

int read_bytes(void* user, char* data, int size) {
  auto& reader = *static_cast<Reader*>(user);
  if (size <= 0) return 0;
  const size_t got = std::fread(data, 1, size_t(size), reader.file);
  if (got == 0 || (got < size_t(size) && size != kStbRefillBytes)) reader.ran_out = true;
  return int(got);
}

void skip_bytes(void* user, int n) {
  std::FILE* file = static_cast<Reader*>(user)->file;
  std::fseek(file, n, SEEK_CUR);
  const int c = std::fgetc(file);  // sets the end-of-file flag, as stb_image's own callback does
  if (c != EOF) std::ungetc(c, file);
}

int at_end(void* user) {
  std::FILE* file = static_cast<Reader*>(user)->file;
  return std::feof(file) || std::ferror(file);
}

const stbi_io_callbacks kCallbacks{read_bytes, skip_bytes, at_end};

// stb_image skips a PNG chunk's CRC-32 and does not check zlib's Adler-32, so a damaged PNG whose data still inflate
// would decode to wrong pixels without a word; libpng (OpenImageIO) refuses it. So every chunk's CRC (PNG spec §5.3:
// CRC-32 of the type and data) is checked first, walking the chunks' framing (length, type, data, CRC) up to IEND.
// Returns "" or what is wrong.
std::string png_chunk_error(std::FILE* file) {
  std::fseek(file, 8, SEEK_SET);  // after the signature
  std::vector<unsigned char> block(65536);  // a chunk is read in blocks: an IDAT may hold the whole image
  for (;;) {
    unsigned char length_and_type[8];
    if (std::fread(length_and_type, 1, 8, file) != 8) return "the file ends before its IEND chunk (is it truncated?)";
    const std::uint32_t length = std::uint32_t(length_and_type[0]) << 24 | std::uint32_t(length_and_type[1]) << 16 |
                                 std::uint32_t(length_and_type[2]) << 8 | length_and_type[3];
    if (length > 0x7fffffffu) return "a chunk claims more than 2^31 bytes";
    uLong crc = crc32(0L, length_and_type + 4, 4);
    for (std::uint32_t left = length; left > 0;) {
      const size_t n = std::min<size_t>(left, block.size());
      if (std::fread(block.data(), 1, n, file) != n) return "the file ends inside a chunk (is it truncated?)";
      crc = crc32(crc, block.data(), uInt(n));
      left -= std::uint32_t(n);
    }
    unsigned char stored_crc[4];
    if (std::fread(stored_crc, 1, 4, file) != 4) return "the file ends inside a chunk (is it truncated?)";
    const std::uint32_t stored = std::uint32_t(stored_crc[0]) << 24 | std::uint32_t(stored_crc[1]) << 16 |
                                 std::uint32_t(stored_crc[2]) << 8 | stored_crc[3];
    const std::string type(reinterpret_cast<const char*>(length_and_type + 4), 4);
    if (std::uint32_t(crc) != stored) return "the " + type + " chunk's CRC does not match its data (the file is damaged)";
    if (type == "IEND") return "";
  }
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError({path.string(), 0, ""}, what);
}

}  // namespace

std::optional<DecodedImage> stb_image_header(const std::filesystem::path& path, bool as_stored) {
  const File file(std::fopen(path.c_str(), "rb"));
  if (!file) return std::nullopt;  // OpenImageIO then reports why it cannot be opened
  unsigned char head[34] = {};
  const size_t n = std::fread(head, 1, sizeof head, file.get());
  const std::string format = format_of(path, head, n);
  if (format.empty()) return std::nullopt;
  std::rewind(file.get());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_file(file.get(), &width, &height, &channels)) return std::nullopt;
  DecodedImage header;
  header.width = width;
  header.height = height;
  header.channels = channels;
  header.format_name = format;
  header.stored_as_float = false;  // integer codes in every format taken
  header.bits_per_sample = stbi_is_16_bit_from_file(file.get()) ? 16 : 8;
  // Grey + alpha or RGB + alpha, alpha last (a PNG's, or a palette's or colour key's tRNS chunk made one).
  header.alpha_channel = channels == 2 || channels == 4 ? channels - 1 : -1;
  if (header.alpha_channel >= 0 && !as_stored) return std::nullopt;  // OpenImageIO premultiplies it
  header.as_stored = as_stored;
  return header;
}

DecodedImage stb_image_pixels(const std::filesystem::path& path, const DecodedImage& header, bool bytes_if_8bit) {
  const File file(std::fopen(path.c_str(), "rb"));
  if (!file) fail(path, std::string("cannot open the image: ") + std::strerror(errno));
  if (header.format_name == "png")
    if (const std::string error = png_chunk_error(file.get()); !error.empty()) fail(path, error);
  std::rewind(file.get());
  Reader reader{file.get()};
  DecodedImage image = header;
  image.bytes_if_8bit = bytes_if_8bit;
  int width = 0, height = 0, channels = 0;
  std::unique_ptr<void, StbFree> decoded;
  if (header.bits_per_sample == 16)
    decoded.reset(stbi_load_16_from_callbacks(&kCallbacks, &reader, &width, &height, &channels, 0));
  else
    decoded.reset(stbi_load_from_callbacks(&kCallbacks, &reader, &width, &height, &channels, 0));
  if (!decoded) {
    const char* reason = stbi_failure_reason();
    fail(path, std::string("cannot decode the pixels (stb_image: ") + (reason ? reason : "no reason") +
                   "): the file is damaged or truncated");
  }
  if (reader.ran_out) fail(path, "the file ends before its pixels do (is it truncated?)");
  if (width != header.width || height != header.height || channels != header.channels)
    fail(path, "the image changed while it was read");
  const size_t samples = size_t(width) * size_t(height) * size_t(channels);
  // Integer codes become floats as OpenImageIO converts them: code times the float 1/max (not code / max).
  if (header.bits_per_sample == 16) {
    const auto* codes = static_cast<const stbi_us*>(decoded.get());
    image.pixels.resize(samples);
    for (size_t i = 0; i < samples; ++i) image.pixels[i] = float(codes[i]) * (1.0f / 65535.0f);
  } else if (bytes_if_8bit) {
    const auto* codes = static_cast<const stbi_uc*>(decoded.get());
    image.bytes.assign(codes, codes + samples);
  } else {
    const auto* codes = static_cast<const stbi_uc*>(decoded.get());
    image.pixels.resize(samples);
    for (size_t i = 0; i < samples; ++i) image.pixels[i] = float(codes[i]) * (1.0f / 255.0f);
  }
  return image;
}

}  // namespace rimu
