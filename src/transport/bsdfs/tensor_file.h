// The "tensor file" container of measured BRDFs (the RGL material database of Dupuy & Jakob 2018, which pbrt-v4's
// `measured` material and Mitsuba read): named arrays ("fields") of a given element type and shape.
//
// Layout (little-endian): the 12 bytes "tensor_file\0"; version bytes 1, 0; uint32 field count; per field a uint16
// name length, the name, a uint16 rank, a uint8 element type (1 uint8, 2 int8, 3 uint16, 4 int16, 5 uint32, 6 int32,
// 7 uint64, 8 int64, 9 float16, 10 float32, 11 float64), a uint64 byte offset of the data from the file's start,
// and `rank` uint64 extents (outermost first). The data of the fields follow the header.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace rimu {

class TensorFile {
 public:
  enum class ElementType : uint8_t {
    uint8 = 1, int8, uint16, int16, uint32, int32, uint64, int64, float16, float32, float64,
  };
  struct Field {
    ElementType type = ElementType::uint8;
    std::vector<uint64_t> shape;  ///< extents, outermost first
    std::string bytes;            ///< the elements, little-endian, row-major
    uint64_t element_count() const;
  };

  /// Parses a tensor file held in memory. `name` (the file's path) prefixes every error. Throws InputError: wrong
  /// magic or version, a truncated header, an unknown element type, a field whose data lie outside the file or
  /// whose size overflows, a repeated field name.
  static TensorFile parse(std::string_view bytes, const std::string& name);
  /// Reads and parses a file (spectral/io/input_file.h's reader: regular files only, at most 1 GiB).
  static TensorFile read(const std::filesystem::path& path);

  const std::string& name() const { return name_; }
  bool has(const std::string& field) const { return fields_.count(field) != 0; }
  /// Throws InputError "<file>: no field "x"" if absent.
  const Field& field(const std::string& field) const;
  /// A float32 field's elements; throws InputError naming the file and field unless its type is float32 and its
  /// rank is `rank`.
  std::vector<float> floats(const std::string& field, size_t rank) const;

  /// The bytes of a tensor file holding `fields` (for tests and for tabulating analytic BRDFs).
  static std::string serialise(const std::map<std::string, Field>& fields);
  /// A float32 field of the given shape and elements.
  static Field float_field(std::vector<uint64_t> shape, const std::vector<float>& values);

 private:
  std::string name_;
  std::map<std::string, Field> fields_;
};

}  // namespace rimu
