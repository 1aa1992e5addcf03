#include "render/json_cursor.h"

#include <cmath>
#include <fstream>
#include <sstream>

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

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& name) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const auto [line, column] = line_and_column(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    // nlohmann's message starts with "[json.exception.parse_error.101] parse error at line L, column C: ";
    // keep only the explanation after the last ": " prefix of the position.
    if (const size_t colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
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
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError({path.string(), 0, ""}, "cannot open the scene file (does it exist and is it readable?)");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_json_text(text.str(), path.string());
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
  if (!value_->is_number()) fail(std::string("expected a number, found ") + type_name(*value_) + " " + value_->dump());
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
  if (!value_->is_number_integer()) fail(std::string("expected an integer, found ") + value_->dump());
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
  if (!value_->is_boolean()) fail(std::string("expected true or false, found ") + value_->dump());
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
  if (!value_->is_array() || value_->size() != 3) fail("expected an array of 3 numbers, found " + value_->dump());
  return {float(at(size_t(0)).number()), float(at(size_t(1)).number()), float(at(size_t(2)).number())};
}

Vec2 JsonCursor::vec2() const {
  if (!value_->is_array() || value_->size() != 2) fail("expected an array of 2 numbers, found " + value_->dump());
  return {float(at(size_t(0)).number()), float(at(size_t(1)).number())};
}

void JsonCursor::only_keys(std::initializer_list<const char*> allowed) const {
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
