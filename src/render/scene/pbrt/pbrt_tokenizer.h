// Tokens of pbrt-v4's scene description (pbrt.org/fileformat-v4): bare words and numbers, quoted strings,
// '[' and ']', with '#' comments to the end of the line.
#pragma once

#include <string>
#include <vector>

namespace rimu {

struct PbrtToken {
  std::string text;     ///< a quoted string's contents with escapes resolved; otherwise the word as written
  bool quoted = false;  ///< written in "double" or 'single' quotes
  int line = 0;         ///< 1-based line where the token starts
};

/// Splits a whole file into tokens. Throws InputError (file:line) for an unterminated string or a bad escape.
/// Cost: one pass; the token list holds a copy of every word (fine for scene files, not for gigabyte ones).
std::vector<PbrtToken> tokenize_pbrt(const std::string& contents, const std::string& file);

}  // namespace rimu
