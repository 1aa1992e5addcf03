#include "render/scene/pbrt/pbrt_tokenizer.h"

#include <cctype>

#include <nlohmann/json.hpp>

#include "spectral/error.h"

namespace rimu {

namespace {

bool is_delimiter(char c) {
  return std::isspace(static_cast<unsigned char>(c)) || c == '[' || c == ']' || c == '"' || c == '\'' || c == '#';
}

// The escapes pbrt's tokenizer resolves inside strings.
char escaped(char c, const std::string& file, int line) {
  switch (c) {
    case 'b': return '\b';
    case 'f': return '\f';
    case 'n': return '\n';
    case 'r': return '\r';
    case 't': return '\t';
    case '\\': return '\\';
    case '\'': return '\'';
    case '"': return '"';
    default: throw InputError({file, line, ""}, std::string("unknown escape '\\") + c + "' in a quoted string");
  }
}

// A quoted string becomes a JSON string (a name, a file path) and a message: it must be UTF-8. Comments and
// bare words may hold anything (a Latin-1 comment is common in old files). The JSON library checks it (its
// strict serializer refuses what is not UTF-8); only strings with a byte above 127 need the check.
void check_utf8(const std::string& text, const std::string& file, int line) {
  bool ascii = true;
  for (const char c : text) ascii = ascii && static_cast<unsigned char>(c) < 0x80;
  if (ascii) return;
  try {
    (void)nlohmann::json(text).dump();
  } catch (const nlohmann::json::type_error&) {
    std::string shown;
    for (const char c : text) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte < 0x80) {
        shown += c;
      } else {
        static const char* hex = "0123456789ABCDEF";
        shown += std::string("\\x") + hex[byte >> 4] + hex[byte & 15];
      }
    }
    throw InputError({file, line, ""}, "the quoted string \"" + shown +
                                           "\" is not UTF-8 (bytes above 127 shown as \\xHH; a Latin-1 file?); "
                                           "pbrt strings are UTF-8: convert the file, e.g. iconv -f latin1 -t utf-8");
  }
}

}  // namespace

std::optional<PbrtToken> PbrtTokenizer::next() {
  const std::string& contents = contents_;
  const std::string& file = file_;
  const size_t n = contents.size();
  size_t& i = i_;
  int& line = line_;
  while (i < n) {
    const char c = contents[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '#') {
      while (i < n && contents[i] != '\n') ++i;
    } else if (c == '[' || c == ']') {
      ++i;
      return PbrtToken{std::string(1, c), false, line};
    } else if (c == '"' || c == '\'') {
      const int start_line = line;
      std::string text;
      ++i;
      while (true) {
        if (i >= n) throw InputError({file, start_line, ""}, std::string("unterminated string: no closing ") + c);
        const char d = contents[i];
        if (d == c) break;
        if (d == '\n') throw InputError({file, start_line, ""}, "a quoted string runs past the end of its line");
        if (d == '\\') {
          if (i + 1 >= n) throw InputError({file, start_line, ""}, "unterminated string: no closing quote");
          text += escaped(contents[i + 1], file, line);
          i += 2;
        } else {
          text += d;
          ++i;
        }
      }
      ++i;
      check_utf8(text, file, start_line);
      return PbrtToken{std::move(text), true, start_line};
    } else {
      const size_t start = i;
      while (i < n && !is_delimiter(contents[i])) ++i;
      return PbrtToken{contents.substr(start, i - start), false, line};
    }
  }
  return std::nullopt;
}

std::vector<PbrtToken> tokenize_pbrt(const std::string& contents, const std::string& file) {
  PbrtTokenizer tokenizer(contents, file);
  std::vector<PbrtToken> tokens;
  while (std::optional<PbrtToken> token = tokenizer.next()) tokens.push_back(std::move(*token));
  return tokens;
}

}  // namespace rimu
