// Display PNGs are written in-process by libpng (render/output/png_file.h): the codes read back bit for bit, the
// file says what the OpenImageIO module's PNGs said (sRGB with its gAMA/cHRM fallbacks unless the view is Raw, the
// Software and rimu:view text), a render with --png leaves OpenImageIO unloaded, and failures name the file.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "image_module_test_support.h"
#include "render/image/image_file.h"
#include "render/image/image_library.h"
#include "render/output/png_file.h"
#include "render/render_job.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// The chunks of a PNG file in order: type and body (the file's structure, checked with its signature).
std::vector<std::pair<std::string, std::string>> png_chunks(const fs::path& path) {
  const std::string bytes = test::file_bytes(path);
  REQUIRE(bytes.size() >= 8);
  REQUIRE(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  std::vector<std::pair<std::string, std::string>> chunks;
  size_t at = 8;
  while (at + 12 <= bytes.size()) {
    const auto byte = [&](size_t i) { return uint32_t(uint8_t(bytes[at + i])); };
    const uint32_t length = byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3);
    REQUIRE(at + 12 + length <= bytes.size());
    chunks.emplace_back(bytes.substr(at + 4, 4), bytes.substr(at + 8, length));
    at += 12 + length;
  }
  CHECK(at == bytes.size());
  return chunks;
}

std::vector<uint8_t> test_codes(int width, int height) {
  std::vector<uint8_t> codes(size_t(width) * size_t(height) * 3);
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = uint8_t((i * 37 + i / 7) & 0xff);
  return codes;
}

}  // namespace

TEST_CASE("PNG output: the codes read back bit for bit, with the display's colour chunks and text") {
  test::ScratchFolder dir("png_file");
  for (const bool srgb : {true, false}) {
    CAPTURE(srgb);
    const fs::path file = dir / (srgb ? "srgb.png" : "raw.png");
    const std::vector<uint8_t> codes = test_codes(7, 5);
    write_png_rgb8(file, 7, 5, codes, PngMetadata{{{"Software", "Rimu test"}, {"rimu:view", "Standard"}}, srgb});
    DecodedImage image = read_image_file(file, true, true);
    CHECK(image.width == 7);
    CHECK(image.height == 5);
    CHECK(image.channels == 3);
    CHECK(image.bytes == codes);
    std::map<std::string, std::string> chunks;
    std::vector<std::string> text;
    for (const auto& [type, body] : png_chunks(file)) {
      chunks[type] = body;
      if (type == "tEXt") text.push_back(body);
    }
    CHECK(chunks.count("sRGB") == (srgb ? 1u : 0u));
    CHECK(chunks.count("gAMA") == (srgb ? 1u : 0u));
    CHECK(chunks.count("cHRM") == (srgb ? 1u : 0u));
    if (srgb) {
      CHECK(chunks["sRGB"] == std::string(1, '\x03'));  // absolute colorimetric, as the OpenImageIO module wrote
      CHECK(chunks["gAMA"] == std::string("\x00\x00\xb1\x8f", 4));  // 1/2.2 as 45455
    }
    CHECK(text == std::vector<std::string>{std::string("Software\0Rimu test", 18), std::string("rimu:view\0Standard", 18)});
  }
}

TEST_CASE("PNG output: a render with --png does not load OpenImageIO") {
  if (test::reran_alone_as_module_is_loaded("PNG output: a render with --png*")) return;
  test::ScratchFolder dir("png_unloaded");
  RenderJob job = test::tiny_render_job(dir / "box.exr");
  job.png_output = dir / "box.png";
  std::ostringstream log;
  run_render_job(job, log);
  CHECK(fs::exists(dir / "box.png"));
  CHECK_FALSE(image_library_loaded());
  // The check itself works: a JPEG still goes through OpenImageIO.
  job.png_output = dir / "box.jpg";
  run_render_job(job, log);
  CHECK(image_library_loaded());
}

TEST_CASE("PNG output: failures are errors naming the file") {
  test::ScratchFolder dir("png_errors");
  const fs::path nowhere = dir / "no_such_folder" / "x.png";
  try {
    write_png_rgb8(nowhere, 2, 2, test_codes(2, 2), {});
    FAIL("expected a RenderError");
  } catch (const RenderError& e) {
    CHECK(std::string(e.what()).find(nowhere.string()) != std::string::npos);
  }
  CHECK_THROWS_AS(write_png_rgb8(dir / "short.png", 3, 2, test_codes(2, 2), {}), RenderError);
  // libpng's own refusal (a row wider than its limit of 10^6 pixels) comes back as an error naming the file.
  const fs::path wide = dir / "wide.png";
  try {
    write_png_rgb8(wide, 1000001, 1, std::vector<uint8_t>(3000003, 0), {});
    FAIL("expected a RenderError");
  } catch (const RenderError& e) {
    CHECK(std::string(e.what()).find(wide.string()) != std::string::npos);
  }
}
