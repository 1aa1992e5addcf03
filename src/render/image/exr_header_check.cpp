#include "render/image/exr_header_check.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <string>

#include "spectral/error.h"

namespace rimu {
namespace {

constexpr std::array<unsigned char, 4> kMagic{0x76, 0x2f, 0x31, 0x01};
constexpr std::uint32_t kMultiPartFlag = 0x1000;  // bit 12 of the version field (OpenEXR file layout)
constexpr std::size_t kMaxNameBytes = 255;        // with the "long names" flag; 31 without

// A little-endian 32-bit field, as OpenEXR stores every integer.
std::uint32_t little_endian_u32(const unsigned char* bytes) {
  return std::uint32_t(bytes[0]) | std::uint32_t(bytes[1]) << 8 | std::uint32_t(bytes[2]) << 16 |
         std::uint32_t(bytes[3]) << 24;
}

}  // namespace

void check_exr_header_sizes(const std::filesystem::path& path, std::uintmax_t file_bytes) {
  const auto fail = [&path](const std::string& what) {
    throw InputError({path.string(), 0, ""}, "its OpenEXR header is damaged: " + what);
  };
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 8> start{};
  in.read(reinterpret_cast<char*>(start.data()), start.size());
  if (in.gcount() < 4 || !std::equal(kMagic.begin(), kMagic.end(), start.begin())) return;  // not OpenEXR
  if (in.gcount() != 8) fail("the file ends inside its magic number and version");
  const std::uint32_t version = little_endian_u32(start.data() + 4);
  std::uintmax_t position = 8;
  // A null-terminated name of at most kMaxNameBytes characters ("" ends a header).
  const auto read_name = [&](const char* what) {
    std::string name;
    for (char c; in.get(c);) {
      ++position;
      if (c == '\0') return name;
      if (name.size() == kMaxNameBytes) fail(std::string("an attribute's ") + what + " runs past 255 characters");
      name += c;
    }
    fail(std::string("the file ends inside an attribute's ") + what);
    return name;  // not reached
  };
  const bool multi_part = (version & kMultiPartFlag) != 0;
  for (int header = 0;; ++header) {
    std::string name = read_name("name");
    // Single part: one header, ended by an empty name. Multi-part: headers one after another; an empty name where
    // a header would start ends the list.
    if (name.empty()) {
      if (!multi_part || header > 0) return;
      fail("its first header is empty");
    }
    while (!name.empty()) {
      const std::string type = read_name("type name");
      std::array<unsigned char, 4> size_bytes{};
      in.read(reinterpret_cast<char*>(size_bytes.data()), 4);
      if (in.gcount() != 4) fail("the file ends inside the size of attribute '" + name + "'");
      position += 4;
      const std::int32_t size = std::int32_t(little_endian_u32(size_bytes.data()));
      if (size < 0 || std::uintmax_t(size) > file_bytes - std::min(position, file_bytes))
        fail("attribute '" + name + "' (" + type + ") claims " + std::to_string(size) + " bytes, but only " +
             std::to_string(file_bytes - std::min(position, file_bytes)) + " follow it in the file");
      in.seekg(size, std::ios::cur);
      position += std::uintmax_t(size);
      name = read_name("name");
    }
    if (!multi_part) return;
  }
}

}  // namespace rimu
