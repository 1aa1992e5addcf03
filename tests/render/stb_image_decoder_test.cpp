// The formats read in-process by stb_image (render/image/stb_image_decoder.h) decode to what the OpenImageIO module
// gives for the same file: header fields, and codes bit for bit (JPEG within a stated bound); truncated files are
// errors naming the file; and reading a PNG leaves OpenImageIO unloaded.
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "image_module_test_support.h"
#include "input_error_check.h"
#include "render/image/image_file.h"
#include "render/image/image_library.h"
#include "render/image/rgb_image.h"
#include "render/image/stb_image_decoder.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// Codes that reach every value and vary from pixel to pixel and channel to channel (a hash, not a ramp, so a
// decoder that swapped channels, flipped rows or dropped a bit would show).
std::vector<uint16_t> test_codes(int width, int height, int channels, int bits) {
  std::vector<uint16_t> codes(size_t(width) * size_t(height) * size_t(channels));
  uint32_t h = 0x9e3779b9u;
  for (size_t i = 0; i < codes.size(); ++i) {
    h ^= uint32_t(i) * 0x85ebca6bu;
    h = (h ^ (h >> 13)) * 0xc2b2ae35u;
    h ^= h >> 16;
    codes[i] = uint16_t(h >> (32 - bits));
  }
  return codes;
}

// A file written by OpenImageIO's own writer for `format` (the extension of `path`), with `attributes` such as
// compression; 8- or 16-bit codes.
fs::path write_image(const fs::path& path, int width, int height, int channels, int bits,
                     const std::vector<std::pair<std::string, std::string>>& attributes = {}) {
  auto out = OIIO::ImageOutput::create(path.string());
  REQUIRE(out);
  const OIIO::TypeDesc type = bits == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(width, height, channels, type);
  if (channels == 2 || channels == 4) spec.alpha_channel = channels - 1;
  for (const auto& [name, value] : attributes) spec.attribute(name, value);
  // Unassociated alpha, as PNG stores it: the codes below are written as they are.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  REQUIRE(out->open(path.string(), spec));
  const std::vector<uint16_t> codes = test_codes(width, height, channels, bits);
  if (bits == 16) {
    REQUIRE(out->write_image(type, codes.data()));
  } else {
    std::vector<uint8_t> bytes(codes.begin(), codes.end());
    REQUIRE(out->write_image(type, bytes.data()));
  }
  REQUIRE(out->close());
  return path;
}

// The largest difference between the two decodes in codes of `max_code` (floats), or in bytes.
double max_code_difference(const DecodedImage& a, const DecodedImage& b, double max_code) {
  REQUIRE(a.pixels.size() == b.pixels.size());
  REQUIRE(a.bytes.size() == b.bytes.size());
  double worst = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    worst = std::max(worst, std::abs(double(a.pixels[i]) - double(b.pixels[i])) * max_code);
  for (size_t i = 0; i < a.bytes.size(); ++i) worst = std::max(worst, std::abs(double(a.bytes[i]) - double(b.bytes[i])));
  return worst;
}

// `path` is taken by stb_image, and decodes exactly as the module does: as stored and not, floats and bytes.
void check_identical(const fs::path& path, const std::string& format, int bits) {
  CAPTURE(path.string());
  for (const bool as_stored : {true, false}) {
    const std::optional<DecodedImage> header = stb_image_header(path, as_stored);
    const DecodedImage oiio_header = test::module_decode(path, as_stored, false);
    // Colour with alpha, read as not stored, is OpenImageIO's (premultiplied); all else is stb_image's.
    const bool with_alpha = oiio_header.alpha_channel >= 0;
    REQUIRE(header.has_value() == (as_stored || !with_alpha));
    if (!header) continue;
    CHECK(header->format_name == format);
    CHECK(header->bits_per_sample == bits);
    for (const bool bytes : {false, true}) {
      CAPTURE(as_stored);
      CAPTURE(bytes);
      const DecodedImage stb = read_image_file(path, as_stored, bytes);
      const DecodedImage oiio = test::module_decode(path, as_stored, bytes);
      test::check_same_header(stb, oiio);
      CHECK(stb.bytes.size() == oiio.bytes.size());
      CHECK(stb.pixels.size() == oiio.pixels.size());
      CHECK(stb.bytes == oiio.bytes);
      // Bit for bit: memcmp, so that -0 and NaN would count too.
      CHECK((stb.pixels.size() == oiio.pixels.size() &&
             std::memcmp(stb.pixels.data(), oiio.pixels.data(), stb.pixels.size() * sizeof(float)) == 0));
    }
  }
}

}  // namespace

TEST_CASE("stb_image: PNG, TGA and BMP decode bit for bit as OpenImageIO decodes them") {
  test::ScratchFolder dir("stb_image");
  // Odd sizes: rows that are not a multiple of 4 bytes (BMP pads them) and an unequal width and height.
  const int w = 37, h = 23;
  SUBCASE("PNG") {
    check_identical(write_image(dir / "rgb.png", w, h, 3, 8), "png", 8);
    check_identical(write_image(dir / "grey.png", w, h, 1, 8), "png", 8);
    check_identical(write_image(dir / "grey_alpha.png", w, h, 2, 8), "png", 8);
    check_identical(write_image(dir / "rgba.png", w, h, 4, 8), "png", 8);
    check_identical(write_image(dir / "rgb16.png", w, h, 3, 16), "png", 16);
    check_identical(write_image(dir / "grey16.png", w, h, 1, 16), "png", 16);
    check_identical(write_image(dir / "rgba16.png", w, h, 4, 16), "png", 16);
  }
  SUBCASE("TGA") {
    check_identical(write_image(dir / "rgb.tga", w, h, 3, 8), "targa", 8);
    check_identical(write_image(dir / "rgb_rle.tga", w, h, 3, 8, {{"compression", "rle"}}), "targa", 8);
    check_identical(write_image(dir / "grey.tga", w, h, 1, 8), "targa", 8);
  }
  SUBCASE("BMP") { check_identical(write_image(dir / "rgb.bmp", w, h, 3, 8), "bmp", 8); }
  SUBCASE("PNM is OpenImageIO's") {
    // stb_image 2.27 reads 16-bit samples in the machine's byte order and does not scale a maximum other than
    // 255 or 65535, where OpenImageIO does: every PNM is left to OpenImageIO.
    CHECK_FALSE(stb_image_header(write_image(dir / "rgb.ppm", w, h, 3, 8, {{"pnm:binary", "1"}}), true));
    CHECK_FALSE(stb_image_header(write_image(dir / "grey16.pgm", w, h, 1, 16, {{"pnm:binary", "1"}}), true));
  }
}

TEST_CASE("stb_image: a truncated Radiance HDR is OpenImageIO's, whose reader fails instead of looping") {
  // 8 x 2 pixels, run-length encoded (a scanline starts 2 2 0 8), cut in the first run: stb_image 2.27 reads zeros
  // past the end and a run of length 0 never advances (found by mutating a seed of fuzz/corpus/image).
  test::ScratchFolder dir("stb_image_hdr");
  const fs::path hdr = dir.write("cut.hdr", std::string("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 8\n") +
                                                 std::string("\x02\x02\x00\x08\x88\x64\x88", 7));
  CHECK_FALSE(stb_image_header(hdr, true));
  test::input_error([&] { RgbImage::read(hdr, {}); }, {hdr.string()});
}

TEST_CASE("stb_image: JPEG decodes within 8 codes (grey: 2) of OpenImageIO's decode (libjpeg)") {
  test::ScratchFolder dir("stb_image_jpeg");
  // A smooth image with an edge, and noise (the hash: every DCT coefficient in use). Two decoders differ in their
  // integer IDCTs and their colour conversions and chroma upsampling, not in the entropy decoding.
  const int w = 61, h = 45;
  for (const bool noise : {false, true}) {
    for (const int channels : {3, 1}) {
      CAPTURE(noise);
      CAPTURE(channels);
      const std::vector<uint16_t> hash = test_codes(w, h, channels, 8);
      std::vector<uint8_t> bytes(size_t(w) * size_t(h) * size_t(channels));
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < channels; ++c) {
            const size_t i = (size_t(y) * size_t(w) + size_t(x)) * size_t(channels) + size_t(c);
            bytes[i] = noise ? uint8_t(hash[i]) : uint8_t(x < w / 2 ? 40 + 3 * x + 50 * c : 230 - 2 * y - 30 * c);
          }
      const fs::path path = dir / (std::string(noise ? "noise" : "smooth") + (channels == 3 ? "_rgb.jpg" : "_grey.jpg"));
      auto out = OIIO::ImageOutput::create(path.string());
      REQUIRE(out);
      REQUIRE(out->open(path.string(), OIIO::ImageSpec(w, h, channels, OIIO::TypeDesc::UINT8)));
      REQUIRE(out->write_image(OIIO::TypeDesc::UINT8, bytes.data()));
      REQUIRE(out->close());
      const DecodedImage stb = read_image_file(path, false, true);
      const DecodedImage oiio = test::module_decode(path, false, true);
      test::check_same_header(stb, oiio);
      // Where the two can differ: both IDCTs are integer versions of libjpeg's accurate one (jidctint; stb_image
      // says so), within 1 code of the exact transform (IEEE 1180's peak error), so Y, Cb and Cr differ by at most
      // 2; chroma upsampling averages (still at most 2 apart) and rounds once more (3); the conversion to RGB
      // multiplies a chroma difference by up to 1.772 (B = Y + 1.772 (Cb - 128)) and rounds: at most
      // 2 + 1.772 · 3 + 1 = 8.3 codes for colour, 2 for grey. Measured (Debian 12: OpenImageIO 2.4.7 on
      // libjpeg-turbo, stb_image 2.27): smooth 1 (colour) and 0 (grey), noise 3 and 1.
      const double worst = max_code_difference(stb, oiio, 255.0);
      const double bound = channels == 3 ? 8.0 : 2.0;
      MESSAGE("JPEG " << std::string(noise ? "noise" : "smooth") << ", " << channels
                      << " channels: largest code difference stb_image - libjpeg = " << worst);
      CHECK(worst <= bound);
      CHECK(max_code_difference(read_image_file(path, true, false), test::module_decode(path, true, false), 255.0) <= bound);
    }
  }
}

TEST_CASE("stb_image: a truncated or damaged file is an InputError naming it") {
  test::ScratchFolder dir("stb_image_bad");
  const auto cut = [&](const fs::path& file, const std::string& name, double keep) {
    const std::string bytes = test::file_bytes(file);
    return dir.write(name, bytes.substr(0, size_t(double(bytes.size()) * keep)));
  };
  const fs::path png = write_image(dir / "whole.png", 64, 64, 3, 8);
  const fs::path short_png = cut(png, "short.png", 0.6);
  test::input_error([&] { RgbImage::read(short_png, {}); }, {short_png.string(), "stb_image"});
  // Uncompressed TGA: stb_image would read zeros past the end without a word; Rimu notices.
  const fs::path tga = write_image(dir / "whole.tga", 64, 64, 3, 8);
  const fs::path short_tga = cut(tga, "short.tga", 0.6);
  test::input_error([&] { RgbImage::read(short_tga, {}); }, {short_tga.string(), "truncated"});
  const fs::path short_rle = cut(write_image(dir / "rle.tga", 64, 64, 3, 8, {{"compression", "rle"}}), "rle_short.tga", 0.6);
  test::input_error([&] { RgbImage::read(short_rle, {}); }, {short_rle.string(), "truncated"});
  // A PNG whose pixel data are noise: zlib refuses them.
  std::string bytes = test::file_bytes(png);
  for (size_t i = 60; i + 20 < bytes.size(); ++i) bytes[i] = char(bytes[i] ^ 0x5a);
  const fs::path damaged = dir.write("damaged.png", bytes);
  test::input_error([&] { RgbImage::read(damaged, {}); }, {damaged.string()});
  // One bit flipped in the image data: stb_image checks neither the chunk's CRC nor zlib's Adler-32, Rimu the CRC.
  std::string flipped = test::file_bytes(png);
  const size_t idat = flipped.find("IDAT");
  REQUIRE(idat != std::string::npos);
  flipped[idat + 40] = char(flipped[idat + 40] ^ 0x01);
  const fs::path bit = dir.write("bit.png", flipped);
  test::input_error([&] { RgbImage::read(bit, {}); }, {bit.string(), "IDAT chunk's CRC"});
}

TEST_CASE("stb_image: reading a PNG or a TGA does not load the OpenImageIO module") {
  if (test::reran_alone_as_module_is_loaded("stb_image: reading a PNG or a TGA*")) return;
  test::ScratchFolder dir("stb_image_unloaded");
  const fs::path png = write_image(dir / "rgb.png", 8, 8, 3, 8);
  const fs::path tga = write_image(dir / "rgb.tga", 8, 8, 3, 8);
  const fs::path tiff = write_image(dir / "rgb.tif", 8, 8, 3, 8);
  (void)RgbImage::read(png, default_encoding_for(png));
  (void)RgbImage::read(tga, default_encoding_for(tga));
  CHECK_FALSE(image_library_loaded());
  // The check itself works: a TIFF goes to OpenImageIO.
  (void)RgbImage::read(tiff, default_encoding_for(tiff));
  CHECK(image_library_loaded());
}

TEST_CASE("a colour texture with alpha keeps its stored colour, not multiplied by alpha, as pbrt-v4 reads it") {
  // Read through stb_image (PNG, TGA) and through OpenImageIO (TIFF with unassociated alpha): the same texels.
  test::ScratchFolder dir("unassociated_colour");
  for (const char* name : {"rgba.png", "rgba.tif"}) {
    CAPTURE(name);
    const fs::path file = write_image(dir / name, 4, 3, 4, 8);
    const std::vector<uint16_t> codes = test_codes(4, 3, 4, 8);
    const RgbImage image = RgbImage::read(file, ImageEncoding{});  // linear: texel = code/255
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 4; ++x) {
        const size_t i = 4 * (size_t(y) * 4 + size_t(x));
        const Rgb texel = image.pixel(x, y);
        CHECK(texel.r == doctest::Approx(codes[i] / 255.0).epsilon(1e-6));
        CHECK(texel.g == doctest::Approx(codes[i + 1] / 255.0).epsilon(1e-6));
        CHECK(texel.b == doctest::Approx(codes[i + 2] / 255.0).epsilon(1e-6));
      }
  }
}
