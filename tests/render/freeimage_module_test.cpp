// PFM and Radiance HDR files are read by the FreeImage module (render/image/image_module/freeimage_module.cpp)
// instead of the OpenImageIO module: they decode to what OpenImageIO gives for the same file (header fields, and
// every sample bit for bit: PFM colour and grey, both byte orders, scales other than 1; HDR flat and run-length
// encoded), reading one leaves OpenImageIO unloaded, and damaged files are errors naming the file.
#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "image_module_test_support.h"
#include "input_error_check.h"
#include "render/image/image_file.h"
#include "render/image/image_library.h"
#include "render/image/rgb_image.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// Samples over many octaves, some negative (test::hdr_test_values), and a subnormal.
std::vector<float> test_samples(size_t count) {
  std::vector<float> samples = test::hdr_test_values(count);
  samples[0] = 1e-40f;
  return samples;
}

// A PFM written byte by byte: `channels` 3 ("PF") or 1 ("Pf"), the header's scale as given (its sign the byte
// order: negative little-endian), rows stored bottom first; `samples` top row first.
fs::path write_pfm_file(const fs::path& path, int width, int height, int channels, const std::string& scale,
                        const std::vector<float>& samples) {
  const bool big_endian = scale[0] != '-';
  std::ofstream out(path, std::ios::binary);
  out << (channels == 3 ? "PF" : "Pf") << "\n" << width << " " << height << "\n" << scale << "\n";
  for (int y = height - 1; y >= 0; --y)
    for (int i = 0; i < width * channels; ++i) {
      uint32_t bits = std::bit_cast<uint32_t>(samples[size_t(y) * size_t(width * channels) + size_t(i)]);
      if (big_endian) bits = __builtin_bswap32(bits);
      out.write(reinterpret_cast<const char*>(&bits), 4);
    }
  return path;
}

DecodedImage pfm_module_decode(const fs::path& path) {
  DecodedImage image;
  std::string error;
  REQUIRE_MESSAGE(image_reader_for(path).read_pixels(path.string(), image, error), error);
  return image;
}

}  // namespace

TEST_CASE("PFM: the FreeImage module decodes what OpenImageIO decodes, bit for bit") {
  test::ScratchFolder dir("pfm_module");
  struct Case {
    int width, height, channels;
    const char* scale;
  };
  for (const Case c : {Case{5, 3, 3, "-1.0"}, Case{5, 3, 3, "1.0"}, Case{7, 2, 1, "-1"}, Case{4, 6, 1, "1.000"},
                       Case{3, 4, 3, "-2.5"}, Case{2, 5, 3, "0.125"}, Case{1, 1, 3, "-1.0"}}) {
    const std::string name = std::to_string(c.width) + "x" + std::to_string(c.height) + "_" +
                             std::to_string(c.channels) + "_" + c.scale + ".pfm";
    CAPTURE(name);
    const std::vector<float> samples = test_samples(size_t(c.width * c.height * c.channels));
    const fs::path file = write_pfm_file(dir / name, c.width, c.height, c.channels, c.scale, samples);
    const DecodedImage freeimage = pfm_module_decode(file);
    const DecodedImage oiio = test::module_decode(file, false, false);
    test::check_same_header(freeimage, oiio);
    REQUIRE(freeimage.pixels.size() == oiio.pixels.size());
    CHECK(freeimage.bytes.empty());
    CHECK(std::memcmp(freeimage.pixels.data(), oiio.pixels.data(), oiio.pixels.size() * sizeof(float)) == 0);
    // And both are the samples written, times the scale's magnitude (a check of the test's own file too).
    const float magnitude = std::fabs(std::stof(c.scale));
    for (size_t i = 0; i < samples.size(); ++i) CHECK(freeimage.pixels[i] == samples[i] * magnitude);
  }
}

TEST_CASE("HDR: the FreeImage module decodes what OpenImageIO decodes, bit for bit") {
  test::ScratchFolder dir("hdr_module");
  // Widths below 8 and above 32767 are stored flat, the others run-length encoded (Radiance's rule, which
  // OpenImageIO's writer follows); a band of equal pixels makes runs.
  for (const auto& [width, height] : std::vector<std::pair<int, int>>{{5, 3}, {53, 37}, {8, 2}, {1, 1}}) {
    const std::string name = std::to_string(width) + "x" + std::to_string(height) + ".hdr";
    CAPTURE(name);
    std::vector<float> samples = test::hdr_test_values(size_t(width * height * 3));
    for (float& v : samples) v = std::fabs(v);  // RGBE holds no negative values
    for (int x = 0; x < width && height > 1; ++x)
      for (int c = 0; c < 3; ++c) samples[size_t((width + x) * 3 + c)] = 1.5f;
    const fs::path file = dir / name;
    auto out = OIIO::ImageOutput::create(file.string());
    REQUIRE(out);
    REQUIRE(out->open(file.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)));
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, samples.data()));
    REQUIRE(out->close());
    const DecodedImage freeimage = pfm_module_decode(file);
    const DecodedImage oiio = test::module_decode(file, false, false);
    test::check_same_header(freeimage, oiio);
    REQUIRE(freeimage.pixels.size() == oiio.pixels.size());
    CHECK(std::memcmp(freeimage.pixels.data(), oiio.pixels.data(), oiio.pixels.size() * sizeof(float)) == 0);
  }
  // Another orientation ("+Y": rows stored bottom first) is left to OpenImageIO; the standard one comes here, rows
  // top first as stored.
  const std::string rgbe = "\x80\x80\x80\x81" "\x40\x40\x40\x81";  // RGBE of (1, 1, 1) and (0.5, 0.5, 0.5)
  std::ofstream(dir / "up.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 2 +X 1\n" << rgbe;
  std::ofstream(dir / "down.hdr", std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 1\n" << rgbe;
  CHECK(&image_reader_for(dir / "up.hdr") == &image_library());
  CHECK(&image_reader_for(dir / "down.hdr") == &freeimage_library());
  CHECK(pfm_module_decode(dir / "down.hdr").pixels == std::vector<float>{1, 1, 1, 0.5f, 0.5f, 0.5f});
  // OpenImageIO returns the other orientations' pixels as stored and only reports the orientation: its module turns
  // them upright. Four pixels p0..p3 (1, 0.5, 0.25, 0.125) stored in this order under each size line whose
  // scanlines are rows (Radiance's file format: the first axis is the one the scanlines step along, its sign the
  // direction they step in, the second the direction along a scanline) land where the line says: rows top first,
  // left to right. Lines whose scanlines are columns are refused with a message naming the fix (OpenImageIO turns
  // "+X 2 -Y 2", which stores the left column first, top down, into the anti-diagonal mirror of what it means).
  const std::string four = "\x80\x80\x80\x81" "\x80\x80\x80\x80" "\x80\x80\x80\x7f" "\x80\x80\x80\x7e";
  const float p0 = 1, p1 = 0.5f, p2 = 0.25f, p3 = 0.125f;
  const struct {
    const char* size_line;
    int width, height;
    std::vector<float> upright;  // first channel, rows top first
  } orientations[] = {
      {"-Y 2 +X 2", 2, 2, {p0, p1, p2, p3}},  // standard (FreeImage)
      {"+Y 2 +X 2", 2, 2, {p2, p3, p0, p1}},  // scanlines bottom first
      {"-Y 2 -X 2", 2, 2, {p1, p0, p3, p2}},  // each scanline right to left
      {"+Y 2 -X 2", 2, 2, {p3, p2, p1, p0}},  // both: turned by 180°
  };
  for (const auto& o : orientations) {
    CAPTURE(std::string(o.size_line));
    const fs::path file = dir / "oriented.hdr";
    std::ofstream(file, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" << o.size_line << "\n"
                                          << four.substr(0, size_t(4 * o.width * o.height));
    const DecodedImage decoded = test::module_decode(file, false, false);
    CHECK(decoded.width == o.width);
    CHECK(decoded.height == o.height);
    CHECK(read_image_size(file).width == o.width);
    if (o.upright.empty()) continue;
    REQUIRE(decoded.pixels.size() == 12);
    const std::vector<float> first_channel = {decoded.pixels[0], decoded.pixels[3], decoded.pixels[6],
                                              decoded.pixels[9]};
    INFO("decoded " << first_channel[0] << " " << first_channel[1] << " " << first_channel[2] << " " << first_channel[3]);
    CHECK(first_channel == o.upright);
  }
  for (const char* size_line : {"+X 2 -Y 2", "-X 2 +Y 2", "+X 2 +Y 2", "-X 3 -Y 1"}) {
    CAPTURE(std::string(size_line));
    const fs::path file = dir / "columns.hdr";
    std::ofstream(file, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" << size_line << "\n" << four;
    DecodedImage image;
    std::string error;
    CHECK_FALSE(image_library().read_pixels(file.string(), image, error));
    CHECK(error.find("standard orientation") != std::string::npos);
    CHECK_THROWS_WITH_AS(read_image_size(file), doctest::Contains("columns.hdr"), InputError);
  }
}

TEST_CASE("PFM: reading a PFM environment map or texture does not load the OpenImageIO module") {
  if (test::reran_alone_if(image_library_loaded() || freeimage_library_loaded(), "PFM: reading a PFM environment map*")) return;
  test::ScratchFolder dir("pfm_unloaded");
  const fs::path pfm = write_pfm_file(dir / "sky.pfm", 8, 4, 3, "-1.0", test_samples(8 * 4 * 3));
  CHECK_FALSE(freeimage_library_loaded());
  const RgbImage image = RgbImage::read(pfm, default_encoding_for(pfm));
  CHECK(image.width() == 8);
  CHECK(read_image_size(pfm).width == 8);
  CHECK(freeimage_library_loaded());
  CHECK_FALSE(image_library_loaded());
}

TEST_CASE("PFM: damaged files are errors naming the file") {
  test::ScratchFolder dir("pfm_damaged");
  const auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return dir / name;
  };
  const std::string pixels(3 * 4 * 2, '\0');
  // A scale of 0 or not a number: neither a byte order nor a factor.
  const fs::path zero = write("zero.pfm", "PF\n2 1\n0.0\n" + pixels);
  test::input_error([&] { RgbImage::read(zero, {}); }, {zero.string(), "scale"});
  const fs::path nan = write("nan.pfm", "PF\n2 1\nnan\n" + pixels);
  test::input_error([&] { RgbImage::read(nan, {}); }, {nan.string()});
  // A width that is no number, a negative height.
  const fs::path words = write("words.pfm", "PF\ntwo one\n-1.0\n" + pixels);
  test::input_error([&] { RgbImage::read(words, {}); }, {words.string()});
  const fs::path negative = write("negative.pfm", "PF\n2 -1\n-1.0\n" + pixels);
  test::input_error([&] { RgbImage::read(negative, {}); }, {negative.string()});
  // Cut short: Rimu's own check, before FreeImage reads the pixels.
  const fs::path cut = write("cut.pfm", "PF\n4 4\n-1.0\n" + pixels);
  test::input_error([&] { RgbImage::read(cut, {}); }, {cut.string(), "truncated"});
  // A Radiance file cut inside its run-length encoded pixels (stb_image loops for ever on one: why HDR never went
  // to stb_image) is an error naming it.
  std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X 16\n";
  for (int row = 0; row < 2; ++row) hdr += std::string("\x02\x02\x00\x10", 4) + std::string(1, char(0x80 + 16)) + "A";
  const fs::path short_hdr = write("short.hdr", hdr);
  test::input_error([&] { RgbImage::read(short_hdr, {}); }, {short_hdr.string()});
}
