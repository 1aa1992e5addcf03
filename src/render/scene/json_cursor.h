// Reading a JSON scene with errors that point at the offending key path.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "spectral/error.h"
#include "transport/geometry/frame.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// Arrays and objects nested deeper than this are refused before parsing (docs/scene-format.md, "Limits"): copying
/// or printing a parsed value recurses, so a 100 000-deep array would overflow the stack.
inline constexpr int kMaxJsonNesting = 256;

/// Parses JSON text; a syntax error becomes an InputError with the file and line (and column) where it was found.
/// A NUL byte, or nesting deeper than kMaxJsonNesting, is an InputError with its line.
nlohmann::json parse_json_text(const std::string& text, const std::string& name);
/// parse_json_text on a file read by read_input_file (a regular file of at most kMaxJsonFileBytes, input_file.h).
nlohmann::json parse_json_file(const std::filesystem::path& path);

/// The value as JSON text for an error message: at most 3 levels deep ("[...]" below) and about `max_chars` long.
std::string json_preview(const nlohmann::json& value, size_t max_chars = 80);

/// A position in a parsed JSON document: the value, its key path ("/materials/white/reflectance") and the file.
/// Every accessor checks the type and range it expects and otherwise throws an InputError naming the path.
class JsonCursor {
 public:
  JsonCursor(const nlohmann::json& value, std::string file, std::string path = "")
      : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

  const nlohmann::json& value() const { return *value_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  SourceLocation where() const { return {file_, 0, path_.empty() ? "/" : path_}; }
  [[noreturn]] void fail(const std::string& what) const;
  /// Runs `build` and returns what it returns; an InputError from a lower layer (a material's constructor, a
  /// spectrum table) that names no key is raised again at this cursor's key path, keeping the file and line it
  /// named if any, so that the message says which value of the scene was wrong.
  template <typename F>
  auto blame(F&& build) const -> decltype(build()) {
    try {
      return build();
    } catch (const InputError& e) {
      if (!e.where().key.empty()) throw;
      SourceLocation location = e.where();
      location.key = path_.empty() ? "/" : path_;
      if (location.file.empty()) location.file = file_;
      throw InputError(location, e.explanation());
    }
  }

  bool has(const std::string& key) const;
  /// The member `key`; error if it is missing or this is not an object.
  JsonCursor at(const std::string& key) const;
  std::optional<JsonCursor> find(const std::string& key) const;
  /// Element `index` of an array.
  JsonCursor at(size_t index) const;
  size_t size() const;
  bool is_object() const { return value_->is_object(); }
  bool is_array() const { return value_->is_array(); }
  bool is_number() const { return value_->is_number(); }
  bool is_string() const { return value_->is_string(); }

  /// A finite number in [min, max].
  double number(double min = -1e30, double max = 1e30) const;
  double number_or(const std::string& key, double fallback, double min = -1e30, double max = 1e30) const;
  int integer(int min, int max) const;
  int integer_or(const std::string& key, int fallback, int min, int max) const;
  bool boolean() const;
  bool boolean_or(const std::string& key, bool fallback) const;
  std::string string() const;
  std::string string_or(const std::string& key, const std::string& fallback) const;
  /// One of `choices`; the error lists them.
  std::string choice(std::initializer_list<const char*> choices) const;
  Vec3 vec3() const;
  Vec2 vec2() const;
  /// Three directions [s, t, n], perpendicular to one another to 1e-4 after normalising (either handedness):
  /// an environment image's or a spherical camera's axes.
  Frame frame() const;
  /// Rejects members other than `allowed` (catches typos such as "radious").
  void only_keys(std::initializer_list<const char*> allowed) const;
  /// The same for a list built at run time (e.g. a texture's own keys plus its mapping's).
  void only_keys(const std::vector<const char*>& allowed) const;

 private:
  const nlohmann::json* value_;
  std::string file_;
  std::string path_;
};

}  // namespace rimu
