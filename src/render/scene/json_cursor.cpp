#include "render/scene/json_cursor.h"

#include <cmath>
#include <sstream>

#include "spectral/io/input_file.h"

namespace rimu {
namespace {

const char* type_name(const nlohmann::json& v) { return v.type_name(); }

// Line and column of a byte offset, for JSON syntax errors.
std::pair<int, int> line_and_column(const std::string& text, size_t byte) {
  int line = 1, column = 1;
  for (size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Appends `text` to `out`, cut with "..." where `out` would pass `limit` characters.
void append_cut(const std::string& text, size_t limit, std::string& out) {
  const size_t room = out.size() < limit ? limit - out.size() : 0;
  out += text.size() <= room ? text : text.substr(0, room) + "...";
}

// Appends a JSON value to `out`, at most kDepth levels deep and stopping near `limit` characters: enough to show
// the user what was found, without printing (or recursing through) a whole document.
void append_preview(const nlohmann::json& v, int depth, size_t limit, std::string& out) {
  constexpr int kDepth = 3;
  if (out.size() >= limit) return;
  if (v.is_array() || v.is_object()) {
    const bool array = v.is_array();
    if (v.empty() || depth >= kDepth) {
      out += v.empty() ? (array ? "[]" : "{}") : (array ? "[...]" : "{...}");
      return;
    }
    out += array ? '[' : '{';
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (!first) out += ", ";
      first = false;
      if (out.size() >= limit) {
        out += "...";
        break;
      }
      if (!array) {
        append_cut(nlohmann::json(it.key()).dump(), limit, out);
        out += ": ";
      }
      append_preview(*it, depth + 1, limit, out);
    }
    out += array ? ']' : '}';
    return;
  }
  append_cut(v.dump(), limit, out);
}

// Throws at the first bracket of JSON text nested deeper than kMaxJsonNesting (a scan that skips strings).
// nlohmann's parser and destructor do not recurse (a 1 000 000-deep array parses), but copying, comparing or
// printing a parsed value does: copying that array overflowed an 8 MiB stack.
void check_nesting(const std::string& text, const std::string& name) {
  int depth = 0, line = 1;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == ']' || c == '}') --depth;
    else if ((c == '[' || c == '{') && ++depth > kMaxJsonNesting)
      throw InputError({name, line, ""}, "arrays and objects are nested more than " +
                                             std::to_string(kMaxJsonNesting) + " deep; a scene needs fewer than 10");
  }
}

}  // namespace

std::string json_preview(const nlohmann::json& value, size_t max_chars) {
  std::string out;
  append_preview(value, 0, max_chars, out);
  return out;
}

nlohmann::json parse_json_text(const std::string& text, const std::string& name) {
  reject_nul_bytes(text, name);
  check_nesting(text, name);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const auto [line, column] = line_and_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at line L, column C: ";
    // keep only the explanation after the last ": " prefix of the position.
    if (const size_t colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    // The message quotes the last token read, which can be a whole megabyte-long string.
    if (what.size() > 200) what = what.substr(0, 200) + "...";
    throw InputError({name, line, ""}, "column " + std::to_string(column) + ": malformed JSON: " + what);
  } catch (const nlohmann::json::exception& e) {
    // Out-of-range numbers (1e400) are reported without a position; find the quoted token to give its line.
    std::string what = e.what();
    int line = 0;
    const size_t open = what.find('\''), close = what.rfind('\'');
    if (open != std::string::npos && close > open + 1) {
      const size_t at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) line = line_and_column(text, at).first;
    }
    if (const size_t bracket = what.find("] "); bracket != std::string::npos) what = what.substr(bracket + 2);
    throw InputError({name, line, ""}, "invalid JSON value: " + what + " (numbers must fit in a double)");
  }
}

nlohmann::json parse_json_file(const std::filesystem::path& path) {
  return parse_json_text(read_input_file(path, kMaxJsonFileBytes), path.string());
}

void JsonCursor::fail(const std::string& what) const { throw InputError(where(), what); }

bool JsonCursor::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

JsonCursor JsonCursor::at(const std::string& key) const {
  if (!value_->is_object()) fail(std::string("expected an object, found ") + type_name(*value_));
  const auto it = value_->find(key);
  if (it == value_->end()) fail("missing required key '" + key + "'");
  return JsonCursor(*it, file_, path_ + "/" + key);
}

std::optional<JsonCursor> JsonCursor::find(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return at(key);
}

JsonCursor JsonCursor::at(size_t index) const {
  if (!value_->is_array()) fail(std::string("expected an array, found ") + type_name(*value_));
  if (index >= value_->size()) fail("index " + std::to_string(index) + " is past the end");
  return JsonCursor((*value_)[index], file_, path_ + "/" + std::to_string(index));
}

size_t JsonCursor::size() const {
  if (!value_->is_array() && !value_->is_object())
    fail(std::string("expected an array, found ") + type_name(*value_));
  return value_->size();
}

double JsonCursor::number(double min, double max) const {
  if (!value_->is_number())
    fail(std::string("expected a number, found ") + type_name(*value_) + " " + json_preview(*value_));
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number");
  if (v < min || v > max) {
    std::ostringstream msg;
    msg << "expected a number in [" << min << ", " << max << "], found " << v;
    fail(msg.str());
  }
  return v;
}

double JsonCursor::number_or(const std::string& key, double fallback, double min, double max) const {
  return has(key) ? at(key).number(min, max) : fallback;
}

int JsonCursor::integer(int min, int max) const {
  if (!value_->is_number_integer()) fail(std::string("expected an integer, found ") + json_preview(*value_));
  const long long v = value_->get<long long>();
  if (v < min || v > max)
    fail("expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], found " +
         std::to_string(v));
  return int(v);
}

int JsonCursor::integer_or(const std::string& key, int fallback, int min, int max) const {
  return has(key) ? at(key).integer(min, max) : fallback;
}

bool JsonCursor::boolean() const {
  if (!value_->is_boolean()) fail(std::string("expected true or false, found ") + json_preview(*value_));
  return value_->get<bool>();
}

bool JsonCursor::boolean_or(const std::string& key, bool fallback) const {
  return has(key) ? at(key).boolean() : fallback;
}

std::string JsonCursor::string() const {
  if (!value_->is_string()) fail(std::string("expected a string, found ") + type_name(*value_));
  return value_->get<std::string>();
}

std::string JsonCursor::string_or(const std::string& key, const std::string& fallback) const {
  return has(key) ? at(key).string() : fallback;
}

std::string JsonCursor::choice(std::initializer_list<const char*> choices) const {
  const std::string s = string();
  std::string list;
  for (const char* c : choices) {
    if (s == c) return s;
    list += std::string(list.empty() ? "" : ", ") + c;
  }
  fail("unknown value '" + s + "'; expected one of: " + list);
}

Vec3 JsonCursor::vec3() const {
  if (!value_->is_array() || value_->size() != 3)
    fail("expected an array of 3 numbers, found " + json_preview(*value_));
  return {float(at(size_t(0)).number()), float(at(size_t(1)).number()), float(at(size_t(2)).number())};
}

Frame JsonCursor::frame() const {
  if (!is_array() || size() != 3) fail("expected three directions [s, t, n]");
  Vec3 axes[3];
  for (size_t i = 0; i < 3; ++i) {
    axes[i] = at(i).vec3();
    if (!(length(axes[i]) > 0.0f)) at(i).fail("a direction cannot be zero");
    axes[i] = normalize(axes[i]);
  }
  if (std::fabs(dot(axes[0], axes[1])) > 1e-4f || std::fabs(dot(axes[0], axes[2])) > 1e-4f ||
      std::fabs(dot(axes[1], axes[2])) > 1e-4f)
    fail("the three directions must be perpendicular to one another");
  return {axes[0], axes[1], axes[2]};
}

Vec2 JsonCursor::vec2() const {
  if (!value_->is_array() || value_->size() != 2)
    fail("expected an array of 2 numbers, found " + json_preview(*value_));
  return {float(at(size_t(0)).number()), float(at(size_t(1)).number())};
}

void JsonCursor::only_keys(std::initializer_list<const char*> allowed) const {
  only_keys(std::vector<const char*>(allowed));
}

void JsonCursor::only_keys(const std::vector<const char*>& allowed) const {
  if (!value_->is_object()) fail(std::string("expected an object, found ") + type_name(*value_));
  for (const auto& [key, unused] : value_->items()) {
    bool known = false;
    for (const char* a : allowed) known = known || key == a;
    if (!known) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      JsonCursor(value_->at(key), file_, path_ + "/" + key).fail("unknown key '" + key + "'; expected one of: " + list);
    }
  }
}

}  // namespace rimu
