// Image headers are checked against the file's size and the pixel limit before any pixel is allocated
// (render/image/image_file.h); environment pixels and light colours whose radiance would overflow are refused by name.
#include <doctest/doctest.h>
#include <zlib.h>

#include <cfloat>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "input_error_check.h"
#include "integration_support.h"
#include "render/image/alpha_mask.h"
#include "render/image/image_file.h"
#include "render/image/rgb_image.h"
#include "spectral/error.h"
#include "test_image_files.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;
namespace fs = std::filesystem;
using test::input_error;

namespace {

void put_be32(std::string& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += char((v >> shift) & 0xff);
}

// One PNG chunk: length, type, data, CRC-32 of type and data (PNG spec §5.3).
std::string png_chunk(const std::string& type, const std::string& data) {
  std::string chunk;
  put_be32(chunk, uint32_t(data.size()));
  const std::string body = type + data;
  chunk += body;
  put_be32(chunk, uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
  return chunk;
}

// A valid PNG header (8-bit RGB) claiming width × height, with one scanline of data: the "69-byte PNG" of the report.
std::string png_claiming(uint32_t width, uint32_t height) {
  std::string ihdr;
  put_be32(ihdr, width);
  put_be32(ihdr, height);
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // bit depth 8, colour type 2 (RGB), deflate, filter 0, no interlace
  const std::string row(4, '\0');                   // filter byte + one pixel
  std::string idat(compressBound(uLong(row.size())), '\0');
  uLongf length = uLongf(idat.size());
  REQUIRE(compress(reinterpret_cast<Bytef*>(idat.data()), &length, reinterpret_cast<const Bytef*>(row.data()),
                   uLong(row.size())) == Z_OK);
  idat.resize(length);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", idat) + png_chunk("IEND", "");
}

fs::path write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace

TEST_CASE("image headers: sizes a file cannot hold are refused before the pixels are allocated") {
  test::ScratchFolder dir("image_headers");
  // 65535 × 65535 RGB would be 51.5 GB of floats: before, std::bad_alloc (exit 2), or memory exhausted.
  const fs::path png = write_file(dir.path / "claims.png", png_claiming(65535, 65535));
  CHECK(fs::file_size(png) < 100);
  input_error([&] { RgbImage::read(png, {}); }, {png.string(), "65535 x 65535", "more than the limit"});
  // Within the pixel limit but far beyond what 70 bytes of deflate can expand to.
  const fs::path wide = write_file(dir.path / "wide.png", png_claiming(8192, 8192));
  input_error([&] { RgbImage::read(wide, {}); }, {wide.string(), "8192 x 8192", "can hold"});
  input_error([&] { AlphaMask::read(wide, 0, false, false, true); }, {wide.string(), "can hold"});

  // PFM is uncompressed: the pixel data must be in the file, exactly (100000² × 12 bytes = 120 GB before).
  const fs::path pfm = write_file(dir.path / "claims.pfm", "PF\n100000 100000\n-1.0\n" + std::string(48, '\0'));
  input_error([&] { RgbImage::read(pfm, {}); }, {pfm.string(), "more than the limit"});
  const fs::path short_pfm = write_file(dir.path / "short.pfm", "PF\n300 200\n-1.0\n" + std::string(48, '\0'));
  input_error([&] { RgbImage::read(short_pfm, {}); }, {short_pfm.string(), "300 x 200", "720000 bytes", "truncated"});
  // A genuine 16384² image is refused by the limit, whatever its file holds (16384 × 8192 is the largest allowed).
  const fs::path square = write_file(dir.path / "square.pfm", "PF\n16384 16384\n-1.0\n");
  input_error([&] { RgbImage::read(square, {}); }, {"16384 x 16384", "134217728", "memory"});

  // A binary PBM packs 8 pixels a byte (OpenImageIO calls it 8-bit: the module says 1 bit), so 2 bytes hold 8 x 2.
  const fs::path pbm = write_file(dir.path / "bitmap.pbm", std::string("P4\n8 2\n\xaa\x55", 9));
  CHECK(RgbImage::read(pbm, {}).width() == 8);
  input_error([&] { RgbImage::read(write_file(dir.path / "cut.pbm", "P4\n64 3\n\xaa\x55"), {}); },
              {"64 x 3", "24 bytes of pixel data", "truncated"});
  // OpenEXR allocates each header attribute at the size it claims: a 1.2 KB file whose lineOrder claimed 128 MB
  // took fuzz_image past 2 GB. The attribute list is checked against the file before the library reads it.
  std::string exr("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
  exr += std::string("lineOrder\0lineOrder\0", 20);
  const std::uint32_t claimed = 134217729;  // little-endian on this machine, as in the file
  exr.append(reinterpret_cast<const char*>(&claimed), 4);
  exr += std::string(16, '\0');
  const fs::path damaged = write_file(dir.path / "damaged.exr", exr);
  input_error([&] { RgbImage::read(damaged, {}); }, {damaged.string(), "'lineOrder'", "claims 134217729 bytes"});
  // A complete small PFM still loads.
  const auto good = test::write_pfm("header_ok", 3, 2, std::vector<float>(18, 0.25f));
  CHECK(RgbImage::read(good, {}).width() == 3);
}

TEST_CASE("image headers: the bounds themselves, per format") {
  DecodedImage header;
  header.width = 1000;
  header.height = 1000;
  header.channels = 1;
  header.bits_per_sample = 1;
  header.format_name = "pnm";  // a PBM: 1000 rows of 125 bytes
  CHECK_NOTHROW(check_image_header(header, 125000, "a.pbm"));
  CHECK_THROWS_AS(check_image_header(header, 124999, "a.pbm"), InputError);
  header.format_name = "png";  // compressed: at most kMaxPixelsPerFileByte pixels per byte
  const std::uintmax_t least = (1000000 + kMaxPixelsPerFileByte - 1) / kMaxPixelsPerFileByte;
  CHECK_NOTHROW(check_image_header(header, least, "a.png"));
  CHECK_THROWS_AS(check_image_header(header, least - 1, "a.png"), InputError);
  header.width = 0;
  CHECK_THROWS_AS(check_image_header(header, 1 << 20, "a.png"), InputError);
  header.width = 16384;
  header.height = 8192;  // exactly the limit
  CHECK_NOTHROW(check_image_header(header, std::uintmax_t(1) << 20, "a.png"));
  header.height = 8193;
  CHECK_THROWS_AS(check_image_header(header, std::uintmax_t(1) << 30, "a.png"), InputError);
}

TEST_CASE("environment pixels and light colours whose radiance overflows single precision are refused by name") {
  test::ScratchFolder dir("overflowing_environment");
  json scene = json::parse(R"({
    "camera": {"from": [0, 0, -3], "to": [0, 0, 0]},
    "film": {"resolution": [4, 4]},
    "materials": {"white": {"type": "diffuse", "reflectance": 0.8}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}]
  })");
  const auto environment = [&](const std::vector<float>& pixels, double scale) {
    const auto path = dir.path / "sky.pfm";
    std::ofstream out(path, std::ios::binary);
    out << "PF\n2 2\n-1.0\n";
    for (int y = 1; y >= 0; --y) out.write(reinterpret_cast<const char*>(&pixels[size_t(y) * 6]), 24);
    out.close();
    json s = scene;
    s["lights"] = json::array({{{"type", "environment"}, {"image", path.string()}, {"scale", scale}}});
    return s;
  };
  // One FLT_MAX pixel: before, its samples were silently discarded as infinite (138 in the report's render).
  std::vector<float> pixels(12, 0.5f);
  pixels[3] = FLT_MAX;  // pixel (1, 0)
  input_error([&] { test::scene_from_json(environment(pixels, 1.0), "sky.json"); },
              {"sky.json", "sky.pfm", "pixel (1, 0)", "1e30"});
  // Every pixel FLT_MAX: before, a black render with exit 0.
  input_error([&] { test::scene_from_json(environment(std::vector<float>(12, FLT_MAX), 1.0), "sky.json"); },
              {"pixel (0, 0)"});
  // The light's scale counts: 1e20 × 1e20 overflows as surely.
  input_error([&] { test::scene_from_json(environment(std::vector<float>(12, 1e20f), 1e20), "sky.json"); },
              {"pixel (0, 0)", "scale"});
  CHECK_NOTHROW(test::scene_from_json(environment(std::vector<float>(12, 1e20f), 1.0), "sky.json"));

  // An RGB light colour of FLT_MAX is refused as a number (JSON numbers are at most 1e30); a colour within that
  // times a "scale" within it can still overflow: before, it loaded and every sample of it was discarded.
  json lit = scene;
  lit["lights"] = json::array({{{"type", "environment"}, {"radiance", {{"rgb", {FLT_MAX, 1, 1}}}}}});
  input_error([&] { test::scene_from_json(lit, "rgb.json"); }, {"rgb.json", "/lights/0/radiance/rgb/0"});
  lit["lights"][0]["radiance"] = {{"rgb", {1e30, 1e30, 1e30}}, {"scale", 1e30}};
  input_error([&] { test::scene_from_json(lit, "rgb.json"); }, {"rgb.json", "/lights/0/radiance", "at most 1e30"});
  lit["lights"][0]["radiance"] = {{"illuminant", "D65"}, {"scale", 1e29}};  // 100 at 560 nm: 1e31
  input_error([&] { test::scene_from_json(lit, "d65.json"); }, {"d65.json", "at most 1e30", "scale"});
  lit["lights"][0]["radiance"] = {{"rgb", {1e20, 1e20, 1e20}}, {"scale", 1e5}};
  CHECK_NOTHROW(test::scene_from_json(lit, "rgb.json"));
}
