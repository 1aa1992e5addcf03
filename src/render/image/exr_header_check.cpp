#include "render/image/exr_header_check.h"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <optional>
#include <string>

#include "spectral/error.h"

namespace rimu {
namespace {

constexpr std::array<unsigned char, 4> kMagic{0x76, 0x2f, 0x31, 0x01};
constexpr std::uint32_t kMultiPartFlag = 0x1000;  // bit 12 of the version field (OpenEXR file layout)
constexpr std::size_t kMaxNameBytes = 255;        // OpenEXR 3.1 reads every name with this limit
constexpr std::uintmax_t kChannelBytes = 16;      // a channel after its name: type, pLinear, 3 reserved, sampling

// A little-endian 32-bit field, as OpenEXR stores every integer.
std::uint32_t little_endian_u32(const unsigned char* bytes) {
  return std::uint32_t(bytes[0]) | std::uint32_t(bytes[1]) << 8 | std::uint32_t(bytes[2]) << 16 |
         std::uint32_t(bytes[3]) << 24;
}

// The value sizes of OpenEXR's predefined attribute types that are read by type, whatever size the file declares
// (the types OpenEXR 3.1's Header::staticInitialize registers; their layouts in "OpenEXR File Layout").
std::optional<std::int64_t> fixed_value_bytes(const std::string& type) {
  static const std::map<std::string, std::int64_t, std::less<>> kFixed{
      {"box2i", 16},    {"box2f", 16},   {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
      {"double", 8},    {"envmap", 1},   {"float", 4},           {"int", 4},         {"keycode", 28},
      {"lineOrder", 1}, {"m33f", 36},    {"m33d", 72},           {"m44f", 64},       {"m44d", 128},
      {"rational", 8},  {"tiledesc", 9}, {"timecode", 8},        {"v2i", 8},         {"v2f", 8},
      {"v2d", 16},      {"v3i", 12},     {"v3f", 12},            {"v3d", 24}};
  const auto found = kFixed.find(type);
  if (found == kFixed.end()) return std::nullopt;
  return found->second;
}

// Reads a header's layout (names, types, sizes and the extents of values), keeping count of the position, and
// throws InputError naming the file at the first inconsistency. Allocates nothing for values.
class ExrHeaderWalk {
 public:
  ExrHeaderWalk(const std::filesystem::path& path, std::uintmax_t file_bytes)
      : path_(path), file_bytes_(file_bytes), in_(path, std::ios::binary) {}

  // Returns the version field, or nothing for a file that is not OpenEXR.
  std::optional<std::uint32_t> read_magic_and_version() {
    std::array<unsigned char, 8> start{};
    in_.read(reinterpret_cast<char*>(start.data()), start.size());
    if (in_.gcount() < 4 || !std::equal(kMagic.begin(), kMagic.end(), start.begin())) return std::nullopt;
    if (in_.gcount() != 8) fail("the file ends inside its magic number and version");
    position_ = 8;
    return little_endian_u32(start.data() + 4);
  }

  // A null-terminated name of at most kMaxNameBytes characters ("" ends a header or a channel list).
  std::string read_name(const char* what) {
    std::string name;
    for (char c; in_.get(c);) {
      ++position_;
      if (c == '\0') return name;
      if (name.size() == kMaxNameBytes) fail(std::string("a ") + what + " runs past 255 characters");
      name += c;
    }
    fail(std::string("the file ends inside a ") + what);
    return name;  // not reached
  }

  std::uint32_t read_u32(const std::string& what) {
    std::array<unsigned char, 4> bytes{};
    in_.read(reinterpret_cast<char*>(bytes.data()), 4);
    if (in_.gcount() != 4) fail("the file ends inside " + what);
    position_ += 4;
    return little_endian_u32(bytes.data());
  }

  // One attribute after its name: the type, the size (refused beyond the file), and the value's extent.
  void read_attribute(const std::string& name) {
    const std::string type = read_name("type name");
    const std::int32_t size = std::int32_t(read_u32("the size of attribute '" + name + "'"));
    const std::uintmax_t left = file_bytes_ - std::min(position_, file_bytes_);
    if (size < 0 || std::uintmax_t(size) > left)
      fail("attribute '" + name + "' (" + type + ") claims " + std::to_string(size) + " bytes, but only " +
           std::to_string(left) + " follow it in the file");
    read_value_extent(name, type, std::uintmax_t(size));
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError({path_.string(), 0, ""}, "its OpenEXR header is damaged: " + what);
  }

 private:
  void skip(std::uintmax_t bytes) {
    in_.seekg(std::streamoff(bytes), std::ios::cur);
    position_ += bytes;
  }

  // Passes over one value the way OpenEXR's reader of its type does, and refuses a value whose extent is not its
  // declared size: afterwards the stream is where the library's would be.
  void read_value_extent(const std::string& name, const std::string& type, std::uintmax_t size) {
    const std::uintmax_t start = position_;
    const auto mismatch = [&](const std::string& extent) {
      fail("attribute '" + name + "' (" + type + ") declares " + std::to_string(size) + " bytes, but its value " +
           extent);
    };
    if (const auto fixed = fixed_value_bytes(type)) {
      if (std::uintmax_t(*fixed) != size) mismatch("is " + std::to_string(*fixed) + " bytes for its type");
      skip(size);
    } else if (type == "chlist") {
      // Channels up to an empty name, however many bytes that takes.
      while (!read_name("channel name").empty()) {
        if (position_ - start + kChannelBytes > size) mismatch("does not end within them (a channel list)");
        skip(kChannelBytes);
      }
      if (position_ - start != size) mismatch("ends after " + std::to_string(position_ - start) + " bytes");
    } else if (type == "stringvector") {
      // Length-prefixed strings until the declared size is used up (OpenEXR checks each length against it).
      while (position_ - start < size) {
        if (position_ - start + 4 > size) mismatch("ends inside a string's length");
        const std::uint32_t length = read_u32("a string's length in attribute '" + name + "'");
        if (length > size - (position_ - start)) mismatch("holds a string of " + std::to_string(length) + " bytes");
        skip(length);
      }
    } else if (type == "preview") {
      // Width and height, then 4 bytes per pixel: the reader allocates width × height pixels.
      if (size < 8) mismatch("needs 8 bytes for its width and height");
      const std::uint64_t width = read_u32("the preview width in attribute '" + name + "'");
      const std::uint64_t height = read_u32("the preview height in attribute '" + name + "'");
      if (width * height * 4 + 8 != size)
        mismatch("is a " + std::to_string(width) + " × " + std::to_string(height) + " preview image");
      skip(size - 8);
    } else if (type == "floatvector" && size % 4 != 0) {
      mismatch("is a whole number of 4-byte floats for its type");
    } else {
      // string, floatvector, idmanifest and the types OpenEXR does not know (kept opaque) are read by their size.
      skip(size);
    }
  }

  const std::filesystem::path& path_;
  std::uintmax_t file_bytes_;
  std::ifstream in_;
  std::uintmax_t position_ = 0;
};

}  // namespace

void check_exr_header_sizes(const std::filesystem::path& path, std::uintmax_t file_bytes) {
  ExrHeaderWalk walk(path, file_bytes);
  const std::optional<std::uint32_t> version = walk.read_magic_and_version();
  if (!version) return;  // not OpenEXR
  const bool multi_part = (*version & kMultiPartFlag) != 0;
  for (int header = 0;; ++header) {
    std::string name = walk.read_name("attribute name");
    // Single part: one header, ended by an empty name. Multi-part: headers one after another; an empty name where
    // a header would start ends the list.
    if (name.empty()) {
      if (!multi_part || header > 0) return;
      walk.fail("its first header is empty");
    }
    while (!name.empty()) {
      walk.read_attribute(name);
      name = walk.read_name("attribute name");
    }
    if (!multi_part) return;
  }
}

}  // namespace rimu
