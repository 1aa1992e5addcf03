// OpenEXR images read by OpenEXR itself (render/image/exr_image_decoder.h) decode to what the OpenImageIO module
// gives for the same file, header fields and floats bit for bit; other channel sets go to the module; a short file
// is an error naming it; and reading an EXR leaves OpenImageIO unloaded.
#include <doctest/doctest.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "image_module_test_support.h"
#include "input_error_check.h"
#include "render/image/exr_image_decoder.h"
#include "render/image/image_file.h"
#include "render/image/image_library.h"
#include "render/image/rgb_image.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {


struct ExrSpec {
  ExrSpec(std::vector<std::string> names, OIIO::TypeDesc all = OIIO::TypeDesc::HALF)
      : channels(std::move(names)), type(all) {}
  std::vector<std::string> channels;
  OIIO::TypeDesc type;
  bool tiled = false;
  int x = 0, y = 0;  // the data window's origin
  std::vector<OIIO::TypeDesc> channel_types;  // per channel, if not all `type`
};

// An EXR written by OpenImageIO's writer (OpenEXR underneath), width × height, channels as named.
fs::path write_exr(const fs::path& path, int width, int height, const ExrSpec& e) {
  auto out = OIIO::ImageOutput::create(path.string());
  REQUIRE(out);
  OIIO::ImageSpec spec(width, height, int(e.channels.size()), e.type);
  spec.channelnames = e.channels;
  spec.alpha_channel = -1;
  for (size_t c = 0; c < e.channels.size(); ++c)
    if (e.channels[c] == "A") spec.alpha_channel = int(c);
  spec.x = e.x;
  spec.y = e.y;
  spec.full_x = 0;
  spec.full_y = 0;
  if (!e.channel_types.empty()) spec.channelformats = e.channel_types;
  if (e.tiled) {
    spec.tile_width = 16;
    spec.tile_height = 16;
  }
  REQUIRE(out->open(path.string(), spec));
  const std::vector<float> values = test::hdr_test_values(size_t(width) * size_t(height) * e.channels.size());
  REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
  REQUIRE(out->close());
  return path;
}

void check_identical(const fs::path& path, int bits) {
  CAPTURE(path.string());
  const std::optional<DecodedImage> header = exr_image_header(path);
  REQUIRE(header);
  CHECK(header->bits_per_sample == bits);
  const DecodedImage exr = read_image_file(path, true);
  const DecodedImage oiio = test::module_decode(path, true, false);
  test::check_same_header(exr, oiio);
  CHECK(exr.bytes.empty());
  // Bit for bit: memcmp, so that -0 and NaN would count too.
  REQUIRE(exr.pixels.size() == oiio.pixels.size());
  CHECK(std::memcmp(exr.pixels.data(), oiio.pixels.data(), exr.pixels.size() * sizeof(float)) == 0);
  // Read compact (as RgbImage reads): a file of halves keeps them, each equal to the float OpenImageIO gives;
  // any other file comes as floats.
  const DecodedImage compact = read_image_file(path, true, true);
  if (bits == 16) {
    CHECK(compact.pixels.empty());
    REQUIRE(compact.halves.size() == oiio.pixels.size());
    for (size_t i = 0; i < compact.halves.size(); ++i) CHECK(imath_half_to_float(compact.halves[i]) == oiio.pixels[i]);
  } else {
    CHECK(compact.halves.empty());
    CHECK(compact.pixels == exr.pixels);
  }
}

}  // namespace

TEST_CASE("OpenEXR images decode bit for bit as OpenImageIO decodes them") {
  test::ScratchFolder dir("exr_decoder");
  check_identical(write_exr(dir / "rgb_half.exr", 37, 23, {{"R", "G", "B"}}), 16);
  check_identical(write_exr(dir / "rgba_float.exr", 37, 23, {{"R", "G", "B", "A"}, OIIO::TypeDesc::FLOAT}), 32);
  check_identical(write_exr(dir / "y.exr", 37, 23, {{"Y"}}), 16);
  check_identical(write_exr(dir / "ya.exr", 37, 23, {{"Y", "A"}, OIIO::TypeDesc::FLOAT}), 32);
  ExrSpec tiled{{"R", "G", "B"}};
  tiled.tiled = true;
  check_identical(write_exr(dir / "tiled.exr", 37, 23, tiled), 16);
  ExrSpec offset{{"R", "G", "B"}};
  offset.x = 5;
  offset.y = -3;
  check_identical(write_exr(dir / "offset.exr", 37, 23, offset), 16);
  ExrSpec mixed{{"R", "G", "B"}};
  mixed.channel_types = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::HALF};
  check_identical(write_exr(dir / "mixed.exr", 37, 23, mixed), 32);
}

TEST_CASE("RgbImage keeps the R, G, B of float and half images of one, three and four channels, pixel by pixel") {
  // RgbImage::read compacts three or more channels in place and widens grey into a new buffer, as floats or as
  // halves: each pixel's values must be the decoder's floats, in order, whatever the channel count (37 × 23: no
  // power of two).
  const int w = 37, h = 23;
  test::ScratchFolder dir("rgb_image_channels");
  for (const OIIO::TypeDesc type : {OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::HALF})
  for (const std::vector<std::string>& names :
       {std::vector<std::string>{"Y"}, std::vector<std::string>{"R", "G", "B"}, std::vector<std::string>{"R", "G", "B", "A"}}) {
    CAPTURE(names.size());
    CAPTURE(type == OIIO::TypeDesc::HALF);
    const fs::path path = write_exr(dir / ("channels_" + std::to_string(names.size()) + "_" + type.c_str() + ".exr"), w,
                                    h, {names, type});
    const DecodedImage decoded = read_image_file(path, true);
    const RgbImage image = RgbImage::read(path, {});
    REQUIRE(image.width() == w);
    REQUIRE(image.height() == h);
    const size_t channels = names.size();
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = (size_t(y) * w + size_t(x)) * channels;
        const Rgb p = image.pixel(x, y);
        CHECK(float(p.r) == decoded.pixels[i]);
        CHECK(float(p.g) == decoded.pixels[i + (channels >= 3 ? 1 : 0)]);
        CHECK(float(p.b) == decoded.pixels[i + (channels >= 3 ? 2 : 0)]);
      }
  }
}

TEST_CASE("a half OpenEXR image with an infinite or NaN pixel is refused, naming the file and the pixel") {
  test::ScratchFolder dir("rgb_image_half_nonfinite");
  for (const float bad_value : {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                                std::numeric_limits<float>::quiet_NaN(), 1e6f /* above half's 65504: infinite */}) {
    CAPTURE(bad_value);
    const fs::path path = dir / "bad.exr";
    auto out = OIIO::ImageOutput::create(path.string());
    REQUIRE(out);
    REQUIRE(out->open(path.string(), OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::HALF)));
    const std::vector<float> values = {0.5f, 0.5f, 0.5f, 0.25f, bad_value, 0.0f, 0.0f, 0.0f, bad_value, 1.0f, 1.0f, 1.0f};
    REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, values.data()));
    REQUIRE(out->close());
    REQUIRE(read_image_file(path, true, true).halves.size() == 12);  // the half path is the one tested
    test::input_error([&] { RgbImage::read(path, {}); }, {path.string(), "pixel (1, 0) is not a finite number"});
  }
}

TEST_CASE("OpenEXR images with other channels are left to OpenImageIO") {
  test::ScratchFolder dir("exr_decoder_other");
  CHECK_FALSE(exr_image_header(write_exr(dir / "rgbz.exr", 8, 8, {{"R", "G", "B", "Z"}})));
  CHECK_FALSE(exr_image_header(write_exr(dir / "layer.exr", 8, 8, {{"diffuse.R", "diffuse.G", "diffuse.B"}})));
  CHECK_FALSE(exr_image_header(write_exr(dir / "rg.exr", 8, 8, {{"R", "G"}})));
  ExrSpec uint{{"R", "G", "B"}, OIIO::TypeDesc::UINT};
  CHECK_FALSE(exr_image_header(write_exr(dir / "uint.exr", 8, 8, uint)));
  // Not an EXR at all.
  CHECK_FALSE(exr_image_header(dir.write("text.exr", "not an image")));
}

TEST_CASE("a truncated OpenEXR image is an InputError naming it") {
  test::ScratchFolder dir("exr_decoder_bad");
  const fs::path whole = write_exr(dir / "whole.exr", 64, 64, {{"R", "G", "B"}, OIIO::TypeDesc::FLOAT});
  const std::string bytes = test::file_bytes(whole);
  const fs::path cut = dir.write("short.exr", bytes.substr(0, bytes.size() * 6 / 10));
  test::input_error([&] { RgbImage::read(cut, {}); }, {cut.string()});
}

TEST_CASE("reading an OpenEXR image does not load the OpenImageIO module") {
  if (test::reran_alone_as_module_is_loaded("reading an OpenEXR image does not*")) return;
  // The file is written with OpenImageIO's library, which this test binary links; what is checked is the module, a
  // separate shared object that only image_library() loads.
  test::ScratchFolder dir("exr_decoder_unloaded");
  const fs::path exr = write_exr(dir / "sky.exr", 8, 4, {{"R", "G", "B"}});
  (void)RgbImage::read(exr, default_encoding_for(exr));
  CHECK_FALSE(image_library_loaded());
}
