#include "render/scene/ply_format.h"

#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <utility>

#include "spectral/error.h"

namespace rimu::ply {

namespace {

struct TypeName {
  std::string_view name;
  Type type;
};
// PLY 1.0 names (Turk 1994) and the sized aliases most writers use today.
constexpr TypeName kTypeNames[] = {
    {"char", Type::int8},     {"int8", Type::int8},       {"uchar", Type::uint8},    {"uint8", Type::uint8},
    {"short", Type::int16},   {"int16", Type::int16},     {"ushort", Type::uint16},  {"uint16", Type::uint16},
    {"int", Type::int32},     {"int32", Type::int32},     {"uint", Type::uint32},    {"uint32", Type::uint32},
    {"float", Type::float32}, {"float32", Type::float32}, {"double", Type::float64}, {"float64", Type::float64},
};

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

Type parse_type(std::string_view word, const SourceLocation& where) {
  for (const TypeName& t : kTypeNames)
    if (t.name == word) return t.type;
  throw InputError(where, "unknown PLY property type '" + std::string(word) +
                              "'; the types are char uchar short ushort int uint float double "
                              "(or int8 uint8 int16 uint16 int32 uint32 float32 float64)");
}

}  // namespace

size_t size_of(Type type) {
  switch (type) {
    case Type::int8:
    case Type::uint8:
      return 1;
    case Type::int16:
    case Type::uint16:
      return 2;
    case Type::int32:
    case Type::uint32:
    case Type::float32:
      return 4;
    case Type::float64:
      return 8;
  }
  return 0;
}

bool is_integer(Type type) { return type != Type::float32 && type != Type::float64; }

uint64_t max_body_bytes(const Header& header) {
  // In long double (64-bit mantissa): counts up to 2^64 times record sizes, then saturated.
  long double total = 0;
  for (const Element& element : header.elements) {
    long double record = 0;
    for (const Property& property : element.properties) {
      if (!property.is_list) {
        record += header.format == Format::ascii ? kMaxAsciiValueChars : size_of(property.type);
        continue;
      }
      const uint64_t count_max = property.count_type == Type::int8 ? 127 : kMaxMeanListItems;
      record += header.format == Format::ascii
                    ? (1 + count_max) * kMaxAsciiValueChars
                    : size_of(property.count_type) + count_max * size_of(property.type);
    }
    total += record * static_cast<long double>(element.count);
  }
  return total >= 18446744073709551615.0L ? std::numeric_limits<uint64_t>::max() : static_cast<uint64_t>(total);
}

const Property* Element::find(std::string_view property_name) const {
  const int i = index_of(property_name);
  return i < 0 ? nullptr : &properties[static_cast<size_t>(i)];
}

int Element::index_of(std::string_view property_name) const {
  for (size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == property_name) return static_cast<int>(i);
  return -1;
}

Header parse_header(std::string_view bytes, const std::string& file) {
  Header header;
  bool has_format = false;
  size_t offset = 0;
  for (int line_number = 1;; ++line_number) {
    const SourceLocation where{file, line_number, ""};
    if (offset >= bytes.size()) throw InputError(where, "the PLY header has no 'end_header' line");
    size_t end = bytes.find('\n', offset);
    const size_t next = end == std::string_view::npos ? bytes.size() : end + 1;
    if (end == std::string_view::npos) end = bytes.size();
    std::string_view line = bytes.substr(offset, end - offset);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // files written on Windows
    offset = next;

    const std::vector<std::string_view> words = split_words(line);
    if (line_number == 1) {
      if (words.size() != 1 || words[0] != "ply")
        throw InputError(where, "not a PLY file: it does not start with 'ply'");
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    const std::string_view keyword = words[0];

    if (keyword == "format") {
      if (words.size() != 3)
        throw InputError(where, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (words[1] == "ascii")
        header.format = Format::ascii;
      else if (words[1] == "binary_little_endian")
        header.format = Format::binary_little_endian;
      else if (words[1] == "binary_big_endian")
        header.format = Format::binary_big_endian;
      else
        throw InputError(where, "unknown PLY format '" + std::string(words[1]) +
                                    "'; supported: ascii, binary_little_endian, binary_big_endian");
      if (words[2] != "1.0")
        throw InputError(where, "unsupported PLY version '" + std::string(words[2]) + "' (only 1.0)");
      has_format = true;
    } else if (keyword == "element") {
      Element element;
      if (words.size() != 3) throw InputError(where, "expected 'element <name> <count>'");
      element.name = std::string(words[1]);
      const auto [ptr, ec] = std::from_chars(words[2].data(), words[2].data() + words[2].size(), element.count);
      if (ec != std::errc() || ptr != words[2].data() + words[2].size())
        throw InputError(where, "element '" + element.name + "': the count '" + std::string(words[2]) +
                                    "' is not a non-negative integer");
      for (const Element& e : header.elements)
        if (e.name == element.name) throw InputError(where, "element '" + element.name + "' is declared twice");
      element.header_line = line_number;
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) throw InputError(where, "a property comes before any element");
      Property property;
      property.header_line = line_number;
      if (words.size() == 5 && words[1] == "list") {
        property.is_list = true;
        property.count_type = parse_type(words[2], where);
        if (!is_integer(property.count_type)) throw InputError(where, "a list's length type must be an integer type");
        property.type = parse_type(words[3], where);
        property.name = std::string(words[4]);
      } else if (words.size() == 3 && words[1] != "list") {
        property.type = parse_type(words[1], where);
        property.name = std::string(words[2]);
      } else {
        throw InputError(where, "expected 'property <type> <name>' or 'property list <count type> <item type> <name>'");
      }
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      if (!has_format) throw InputError(where, "the PLY header has no 'format' line");
      header.body_offset = offset;
      header.body_line = line_number + 1;
      return header;
    } else {
      throw InputError(where, "unknown PLY header keyword '" + std::string(keyword) + "'");
    }
  }
}

BodyReader::BodyReader(std::string_view bytes, const Header& header, const std::string& file)
    : bytes_(bytes), offset_(header.body_offset), line_(header.body_line), format_(header.format), file_(file) {}

void BodyReader::fail(const std::string& what) const {
  std::ostringstream message;
  if (element_) message << *element_ << " " << record_ << ": ";
  message << what;
  if (format_ != Format::ascii) message << " (at byte " << offset_ << ")";
  throw InputError({file_, format_ == Format::ascii ? line_ : 0, ""}, message.str());
}

bool BodyReader::native_order() const {
  if (format_ == Format::ascii) return false;
  return (format_ == Format::binary_little_endian) == (std::endian::native == std::endian::little);
}

double BodyReader::read(Type type) { return format_ == Format::ascii ? read_ascii(type) : read_binary(type); }

void BodyReader::skip(Type type, uint64_t n) {
  if (format_ != Format::ascii) {
    // Binary values have a fixed size, so a skip is a bounds check and a jump.
    const uint64_t size = size_of(type);
    if (n > remaining() / size) fail("the file ends inside this record (is it truncated?)");
    offset_ += static_cast<size_t>(n * size);
    return;
  }
  for (uint64_t i = 0; i < n; ++i) read_ascii(type);
}

double BodyReader::read_binary(Type type) {
  const size_t size = size_of(type);
  if (remaining() < size) fail("the file ends inside this record (is it truncated?)");
  unsigned char raw[8];
  std::memcpy(raw, bytes_.data() + offset_, size);
  offset_ += size;
  const bool file_is_little = format_ == Format::binary_little_endian;
  if (file_is_little != (std::endian::native == std::endian::little))
    for (size_t i = 0; i < size / 2; ++i) std::swap(raw[i], raw[size - 1 - i]);
  auto as = [&raw]<typename T>(T value) {
    std::memcpy(&value, raw, sizeof(T));
    return static_cast<double>(value);
  };
  switch (type) {
    case Type::int8:
      return as(int8_t{});
    case Type::uint8:
      return as(uint8_t{});
    case Type::int16:
      return as(int16_t{});
    case Type::uint16:
      return as(uint16_t{});
    case Type::int32:
      return as(int32_t{});
    case Type::uint32:
      return as(uint32_t{});
    case Type::float32:
      return as(float{});
    case Type::float64:
      return as(double{});
  }
  return 0.0;
}

double BodyReader::read_ascii(Type type) {
  while (offset_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[offset_]))) {
    if (bytes_[offset_] == '\n') ++line_;
    ++offset_;
  }
  const size_t start = offset_;
  while (offset_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[offset_]))) ++offset_;
  if (offset_ == start) fail("the file ends inside this record (is it truncated?)");
  const std::string_view token = bytes_.substr(start, offset_ - start);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size())
    fail("expected a number, found '" + std::string(token.substr(0, 40)) + "'");
  if (is_integer(type)) {
    // The integer types' ranges, for the check that an ascii value fits the type the header declared.
    const double bits = 8.0 * static_cast<double>(size_of(type));
    const bool is_signed = type == Type::int8 || type == Type::int16 || type == Type::int32;
    const double lowest = is_signed ? -std::exp2(bits - 1) : 0.0;
    const double highest = is_signed ? std::exp2(bits - 1) - 1 : std::exp2(bits) - 1;
    if (!(value == std::floor(value) && value >= lowest && value <= highest))
      fail("'" + std::string(token) + "' is not a value of the property's integer type");
  }
  return value;
}

}  // namespace rimu::ply
