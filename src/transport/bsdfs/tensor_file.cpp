#include "transport/bsdfs/tensor_file.h"

#include <cstring>
#include <limits>

#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {

namespace {

constexpr char kMagic[12] = {'t', 'e', 'n', 's', 'o', 'r', '_', 'f', 'i', 'l', 'e', '\0'};
// RGL's spectral files are tens of MB; 1 GiB bounds what a damaged or hostile file can make Rimu allocate.
constexpr std::uintmax_t kMaxTensorFileBytes = std::uintmax_t(1) << 30;

uint64_t element_bytes(TensorFile::ElementType type) {
  switch (type) {
    case TensorFile::ElementType::uint8: case TensorFile::ElementType::int8: return 1;
    case TensorFile::ElementType::uint16: case TensorFile::ElementType::int16: case TensorFile::ElementType::float16: return 2;
    case TensorFile::ElementType::uint32: case TensorFile::ElementType::int32: case TensorFile::ElementType::float32: return 4;
    case TensorFile::ElementType::uint64: case TensorFile::ElementType::int64: case TensorFile::ElementType::float64: return 8;
  }
  return 0;
}

const char* type_name(TensorFile::ElementType type) {
  static const char* names[] = {"uint8", "int8", "uint16", "int16", "uint32", "int32", "uint64", "int64", "float16", "float32", "float64"};
  return names[int(type) - 1];
}

// Reads little-endian integers from the header, failing with the file's name when it ends first.
class HeaderReader {
 public:
  HeaderReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}
  template <typename T>
  T read(const char* what) {
    if (bytes_.size() - position_ < sizeof(T)) fail(std::string("the header ends inside ") + what + " (truncated file?)");
    T value = 0;
    for (size_t i = 0; i < sizeof(T); ++i) value |= T(T(uint8_t(bytes_[position_ + i])) << (8 * i));
    position_ += sizeof(T);
    return value;
  }
  std::string_view take(size_t count, const char* what) {
    if (bytes_.size() - position_ < count) fail(std::string("the header ends inside ") + what + " (truncated file?)");
    const std::string_view s = bytes_.substr(position_, count);
    position_ += count;
    return s;
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputError({name_, 0, ""}, "tensor file: " + what); }

 private:
  std::string_view bytes_;
  const std::string& name_;
  size_t position_ = 0;
};

}  // namespace

uint64_t TensorFile::Field::element_count() const {
  uint64_t n = 1;
  for (const uint64_t extent : shape) n *= extent;
  return n;
}

TensorFile TensorFile::parse(std::string_view bytes, const std::string& name) {
  HeaderReader header(bytes, name);
  if (std::memcmp(header.take(sizeof kMagic, "the magic \"tensor_file\"").data(), kMagic, sizeof kMagic) != 0)
    header.fail("not a tensor file (it does not start with \"tensor_file\"; expected a measured BRDF of the RGL database)");
  const uint8_t major = header.read<uint8_t>("the version"), minor = header.read<uint8_t>("the version");
  if (major != 1 || minor != 0)
    header.fail("version " + std::to_string(major) + "." + std::to_string(minor) + " is not the one Rimu reads (1.0)");
  const uint32_t field_count = header.read<uint32_t>("the field count");

  TensorFile file;
  file.name_ = name;
  for (uint32_t f = 0; f < field_count; ++f) {
    const uint16_t name_length = header.read<uint16_t>("a field's name length");
    const std::string field_name(header.take(name_length, "a field's name"));
    const uint16_t rank = header.read<uint16_t>("a field's rank");
    const uint8_t type = header.read<uint8_t>("a field's element type");
    const uint64_t offset = header.read<uint64_t>("a field's offset");
    if (type < 1 || type > uint8_t(ElementType::float64))
      header.fail("field \"" + field_name + "\": unknown element type " + std::to_string(type));
    Field field;
    field.type = ElementType(type);
    uint64_t size = element_bytes(field.type);
    for (uint16_t d = 0; d < rank; ++d) {
      const uint64_t extent = header.read<uint64_t>("a field's shape");
      // Overflow-safe: a product beyond the file's size is refused before it is formed.
      if (extent != 0 && size > uint64_t(bytes.size()) / extent)
        header.fail("field \"" + field_name + "\": its shape asks for more bytes than the file holds");
      size *= extent;
      field.shape.push_back(extent);
    }
    if (offset > bytes.size() || size > bytes.size() - offset)
      header.fail("field \"" + field_name + "\": its data (" + std::to_string(size) + " bytes at offset " +
                  std::to_string(offset) + ") lie beyond the end of the file (" + std::to_string(bytes.size()) +
                  " bytes; truncated?)");
    field.bytes.assign(bytes.substr(size_t(offset), size_t(size)));
    if (!file.fields_.emplace(field_name, std::move(field)).second)
      header.fail("field \"" + field_name + "\" appears twice");
  }
  return file;
}

TensorFile TensorFile::read(const std::filesystem::path& path) {
  return parse(read_input_file(path, kMaxTensorFileBytes), path.string());
}

const TensorFile::Field& TensorFile::field(const std::string& field) const {
  const auto found = fields_.find(field);
  if (found == fields_.end())
    throw InputError({name_, 0, ""}, "tensor file: no field \"" + field + "\" (a measured BRDF of the RGL database has it)");
  return found->second;
}

std::vector<float> TensorFile::floats(const std::string& name, size_t rank) const {
  const Field& f = field(name);
  if (f.type != ElementType::float32 || f.shape.size() != rank)
    throw InputError({name_, 0, ""}, "tensor file: field \"" + name + "\" is " + type_name(f.type) + " of rank " +
                                         std::to_string(f.shape.size()) + "; expected float32 of rank " + std::to_string(rank));
  std::vector<float> values(size_t(f.element_count()));
  for (size_t i = 0; i < values.size(); ++i) {
    uint32_t word = 0;
    for (size_t b = 0; b < 4; ++b) word |= uint32_t(uint8_t(f.bytes[4 * i + b])) << (8 * b);
    std::memcpy(&values[i], &word, 4);
  }
  return values;
}

std::string TensorFile::serialise(const std::map<std::string, Field>& fields) {
  const auto put = [](std::string& out, uint64_t value, size_t bytes) {
    for (size_t i = 0; i < bytes; ++i) out.push_back(char((value >> (8 * i)) & 0xff));
  };
  size_t header_size = sizeof kMagic + 2 + 4;
  for (const auto& [name, f] : fields) header_size += 2 + name.size() + 2 + 1 + 8 + 8 * f.shape.size();
  std::string out(kMagic, sizeof kMagic);
  out.push_back(1);
  out.push_back(0);
  put(out, fields.size(), 4);
  uint64_t offset = header_size;
  for (const auto& [name, f] : fields) {
    put(out, name.size(), 2);
    out += name;
    put(out, f.shape.size(), 2);
    put(out, uint8_t(f.type), 1);
    put(out, offset, 8);
    for (const uint64_t extent : f.shape) put(out, extent, 8);
    offset += f.bytes.size();
  }
  for (const auto& [name, f] : fields) out += f.bytes;
  return out;
}

TensorFile::Field TensorFile::float_field(std::vector<uint64_t> shape, const std::vector<float>& values) {
  Field f;
  f.type = ElementType::float32;
  f.shape = std::move(shape);
  f.bytes.resize(values.size() * 4);
  for (size_t i = 0; i < values.size(); ++i) {
    uint32_t word = 0;
    std::memcpy(&word, &values[i], 4);
    for (size_t b = 0; b < 4; ++b) f.bytes[4 * i + b] = char((word >> (8 * b)) & 0xff);
  }
  return f;
}

}  // namespace rimu
