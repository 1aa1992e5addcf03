// OpenEXR headers are walked before any library reads them (render/image/exr_header_check.h): a value must span
// exactly the bytes its attribute declares, read the way OpenEXR 3.1 reads its type, so the library's position
// never drifts from the declared layout into bytes that it would take for a size.
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "input_error_check.h"
#include "render/image/exr_header_check.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;
using test::input_error;

namespace {

std::string le32(std::uint32_t value) {
  std::string bytes;
  for (int shift = 0; shift < 32; shift += 8) bytes += char((value >> shift) & 0xff);
  return bytes;
}

// One attribute: name, type, the declared size and the value's bytes (which may differ from what it declares).
std::string attribute(const std::string& name, const std::string& type, std::uint32_t declared,
                      const std::string& value) {
  return name + '\0' + type + '\0' + le32(declared) + value;
}
std::string attribute(const std::string& name, const std::string& type, const std::string& value) {
  return attribute(name, type, std::uint32_t(value.size()), value);
}

// A channel of a channel list: its name, then HALF, pLinear 0, 3 reserved bytes, sampling 1 × 1 (16 bytes).
std::string channel(const std::string& name) { return name + '\0' + le32(1) + std::string(4, '\0') + le32(1) + le32(1); }

// A single-part scanline file: magic, version 2, the attributes, the empty name ending the header, then `tail`
// (standing in for the offset table and pixels).
fs::path write_exr(const fs::path& path, const std::string& attributes, const std::string& tail = std::string(64, '\0')) {
  std::ofstream(path, std::ios::binary) << std::string("\x76\x2f\x31\x01", 4) + le32(2) + attributes + '\0' + tail;
  return path;
}

void check(const fs::path& path) { check_exr_header_sizes(path, fs::file_size(path)); }

}  // namespace

TEST_CASE("OpenEXR headers: every value type OpenEXR reads by its type spans exactly its declared size") {
  test::ScratchFolder dir("exr_header_check");
  const std::string channels = channel("R") + channel("G") + '\0';
  const std::string box = le32(0) + le32(0) + le32(1) + le32(1);

  // Well-formed values of each kind the walk reads by type pass: a channel list, fixed-size values, a string
  // vector, a preview image (2 × 1 RGBA), a float vector and an attribute type OpenEXR does not know.
  const fs::path good = write_exr(
      dir.path / "good.exr",
      attribute("channels", "chlist", channels) + attribute("compression", "compression", std::string(1, '\0')) +
          attribute("dataWindow", "box2i", box) + attribute("names", "stringvector", le32(2) + "ab" + le32(0)) +
          attribute("preview", "preview", le32(2) + le32(1) + std::string(8, '\x7f')) +
          attribute("weights", "floatvector", std::string(8, '\0')) +
          attribute("studio:note", "someStudioType", std::string(5, 'x')));
  CHECK_NOTHROW(check(good));

  // The fuzzer's case: a channel list that runs past its declared size (OpenEXR reads on to the empty name and
  // takes later bytes for the next attribute's size).
  const fs::path long_list =
      write_exr(dir.path / "long_list.exr", attribute("channels", "chlist", 17, channels) +
                                                attribute("comments", "string", "Rendered by Rimu"));
  input_error([&] { check(long_list); }, {long_list.string(), "'channels' (chlist) declares 17 bytes", "does not end"});
  // … and one that ends before its declared size.
  const fs::path short_list = write_exr(dir.path / "short_list.exr",
                                        attribute("channels", "chlist", std::uint32_t(channels.size() + 4),
                                                  channels + std::string(4, '\0')));
  input_error([&] { check(short_list); }, {"'channels' (chlist)", "ends after 37 bytes"});

  // A fixed-size type declared at another size: OpenEXR reads 16 bytes of a box2i whatever the file says.
  const fs::path small_box =
      write_exr(dir.path / "small_box.exr", attribute("dataWindow", "box2i", 12, box.substr(0, 12)));
  input_error([&] { check(small_box); }, {"'dataWindow' (box2i) declares 12 bytes", "is 16 bytes for its type"});

  // A preview image's pixels are allocated from its width and height: they must be what its size holds.
  const fs::path huge_preview =
      write_exr(dir.path / "huge_preview.exr", attribute("preview", "preview", le32(65535) + le32(65535) + "RGBA"));
  input_error([&] { check(huge_preview); }, {"'preview' (preview) declares 12 bytes", "65535 × 65535 preview"});

  // A string of a string vector longer than what is left of the vector's size.
  const fs::path long_string =
      write_exr(dir.path / "long_string.exr", attribute("names", "stringvector", le32(1000) + "ab"));
  input_error([&] { check(long_string); }, {"'names' (stringvector)", "holds a string of 1000 bytes"});

  // A float vector that is not a whole number of floats would leave OpenEXR's reader mid-value.
  const fs::path ragged = write_exr(dir.path / "ragged.exr", attribute("weights", "floatvector", std::string(6, '\0')));
  input_error([&] { check(ragged); }, {"'weights' (floatvector)", "whole number of 4-byte floats"});
}
