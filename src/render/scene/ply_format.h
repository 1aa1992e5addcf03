// The PLY container: its header (elements and their typed properties) and a cursor over the body.
//
// PLY (Turk, "The PLY Polygon File Format", 1994) describes a file as a list of elements (vertex, face, ...)
// with a count each; every element record is its properties in header order. A property is a scalar of one of
// eight types, or a list: a count (an integer type) followed by that many items. The body is either
// whitespace-separated text or packed binary in a stated byte order. This file knows nothing about meshes;
// ply_loader.cpp picks the vertex and face elements out of it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace rimu::ply {

enum class Format { ascii, binary_little_endian, binary_big_endian };

/// The eight PLY scalar types; both the 1994 names (char, uchar, ...) and the sized ones (int8, ...) map here.
enum class Type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

/// Bytes one value of `type` takes in a binary body.
size_t size_of(Type type);
bool is_integer(Type type);

struct Property {
  std::string name;
  Type type = Type::float32;  ///< the scalar's type, or a list's item type
  bool is_list = false;
  Type count_type = Type::uint8;  ///< a list's length type (an integer type)
  int header_line = 0;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  int header_line = 0;

  /// The property called `name`, or nullptr.
  const Property* find(std::string_view property_name) const;
  /// Where `name` sits in `properties`, or -1.
  int index_of(std::string_view property_name) const;
};

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  size_t body_offset = 0;  ///< first byte after the end_header line
  int body_line = 0;       ///< the line the body starts on (meaningful for ascii)
};

/// The scalar of `type` stored at `p` in native byte order, as a double (exact for every PLY type).
inline double native_value(const char* p, Type type) {
  switch (type) {
    case Type::int8: { int8_t v; std::memcpy(&v, p, 1); return v; }
    case Type::uint8: { uint8_t v; std::memcpy(&v, p, 1); return v; }
    case Type::int16: { int16_t v; std::memcpy(&v, p, 2); return v; }
    case Type::uint16: { uint16_t v; std::memcpy(&v, p, 2); return v; }
    case Type::int32: { int32_t v; std::memcpy(&v, p, 4); return v; }
    case Type::uint32: { uint32_t v; std::memcpy(&v, p, 4); return v; }
    case Type::float32: { float v; std::memcpy(&v, p, 4); return v; }
    case Type::float64: { double v; std::memcpy(&v, p, 8); return v; }
  }
  return 0.0;
}

/// Parses the header at the start of `bytes`; throws InputError naming `file` and the header line.
Header parse_header(std::string_view bytes, const std::string& file);

/// A list in a compressed PLY is counted at up to this many items on average when bounding its body (a uchar
/// count's own maximum, and far above a triangle mesh's 3).
inline constexpr uint64_t kMaxMeanListItems = 255;
/// An ascii value is counted at up to this many characters, its separator included (a double printed in full,
/// "-1.2345678901234567e-308 ", takes 25).
inline constexpr uint64_t kMaxAsciiValueChars = 64;

/// The most bytes a body can hold and still be read by the header (every element's records; lists at most
/// kMaxMeanListItems items on average, ascii values at most kMaxAsciiValueChars), saturated at UINT64_MAX.
/// Bounds how far a .ply.gz may decompress: bytes beyond it could not be part of the mesh.
uint64_t max_body_bytes(const Header& header);

/// Reads body values one at a time, in file order. Every read is bounds-checked: a truncated or garbled body
/// throws InputError naming the element and record being read (set with `at`), never reads out of range.
class BodyReader {
 public:
  BodyReader(std::string_view bytes, const Header& header, const std::string& file);

  /// Names the record being read, for error messages ("face 17").
  void at(const std::string& element, uint64_t record) {
    element_ = &element;
    record_ = record;
  }
  /// One scalar, converted to double (exact for every PLY type). Integer types must hold integers in range.
  double read(Type type);
  /// Skips `n` values of `type`.
  void skip(Type type, uint64_t n);
  /// Binary bodies: the next `n` raw bytes (bounds-checked like read, then skipped), for readers that decode a
  /// whole record in place. The caller converts byte order (native_order() says whether it must).
  const char* take(size_t n) {
    if (n > remaining()) fail("the file ends inside this record (is it truncated?)");
    const char* at = bytes_.data() + offset_;
    offset_ += n;
    return at;
  }
  /// True for a binary body in this machine's byte order: values can be copied out as they are.
  bool native_order() const;
  /// Bytes (binary) or characters (ascii) left; a bound on how many values can follow.
  size_t remaining() const { return bytes_.size() - offset_; }

  /// Throws InputError at the current record with `what` as the explanation.
  [[noreturn]] void fail(const std::string& what) const;

 private:
  double read_binary(Type type);
  double read_ascii(Type type);

  std::string_view bytes_;
  size_t offset_;
  int line_;
  Format format_;
  const std::string& file_;
  const std::string* element_ = nullptr;
  uint64_t record_ = 0;
};

}  // namespace rimu::ply
