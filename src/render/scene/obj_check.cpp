#include "render/scene/obj_check.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu::obj {

namespace {

using Words = std::vector<std::string_view>;

// Calls fn(line_number, words) for each line, with at most `max_words` words. Line ends are \n, \r\n or a
// lone \r, as tinyobjloader counts them, so the line numbers here and in its messages agree.
template <typename Fn>
void for_each_line(std::string_view text, size_t max_words, Fn fn) {
  Words words;
  size_t i = 0;
  for (int line_number = 1; i < text.size(); ++line_number) {
    words.clear();
    while (i < text.size() && text[i] != '\n' && text[i] != '\r') {
      if (words.size() == max_words) {
        i = std::min(text.find_first_of("\r\n", i), text.size());
        break;
      }
      while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
      const size_t start = i;
      while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\n' && text[i] != '\r') ++i;
      if (i > start) words.push_back(text.substr(start, i - start));
    }
    if (i < text.size() && text[i] == '\r') {
      ++i;
      if (i < text.size() && text[i] == '\n') ++i;
    } else if (i < text.size()) {
      ++i;  // '\n'
    }
    if (!words.empty() && words[0][0] != '#') fn(line_number, words);
  }
}

// A number that is finite in single precision (the mesh stores floats).
bool parse_finite_float(std::string_view word, double& value) {
  if (word.size() > 1 && word[0] == '+') word.remove_prefix(1);  // from_chars rejects a leading '+'; OBJ allows it
  const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  return ec == std::errc() && ptr == word.data() + word.size() && std::isfinite(value) &&
         std::fabs(value) <= std::numeric_limits<float>::max();
}

void check_numbers(const Words& words, size_t required, size_t checked, const SourceLocation& where) {
  if (words.size() < required + 1)
    throw InputError(where, "'" + std::string(words[0]) + "' needs at least " + std::to_string(required) +
                                (required == 1 ? " number" : " numbers") + ", found " +
                                std::to_string(words.size() - 1));
  for (size_t i = 1; i <= checked && i < words.size(); ++i) {
    double value = 0.0;
    if (!parse_finite_float(words[i], value))
      throw InputError(where, "'" + std::string(words[i]) + "' is not a finite number");
  }
}

struct Counts {
  long long positions = 0, texcoords = 0, normals = 0;
};

// Checks one index of a face corner: 1-based, or negative = counted back from the statements so far.
// Positive indices may point forward (tinyobjloader resolves them against the whole file), so they are checked
// against the file's totals.
void check_index(std::string_view part, const char* what, const char* what_plural, long long so_far, long long total,
                 std::string_view corner, const SourceLocation& where) {
  long long index = 0;
  const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
  if (ec != std::errc() || ptr != part.data() + part.size())
    throw InputError(where, "face corner '" + std::string(corner) + "': '" + std::string(part) + "' is not an index");
  if (index == 0)
    throw InputError(where, "face corner '" + std::string(corner) + "': OBJ indices start at 1 (0 is not an index)");
  if (index > total)
    throw InputError(where, "face corner '" + std::string(corner) + "' refers to " + what + " " +
                                std::to_string(index) + " but the file has " + std::to_string(total));
  // Compared as index < -so_far: negating the index itself overflows for -9223372036854775808.
  if (index < 0 && index < -so_far)
    throw InputError(where, "face corner '" + std::string(corner) + "' refers " + std::string(part.substr(1)) + " " +
                                what_plural + " back but only " + std::to_string(so_far) + " come before this line");
}

void check_face(const Words& words, const Counts& so_far, const Counts& total, const SourceLocation& where) {
  if (words.size() < 4)
    throw InputError(where, "a face needs at least 3 corners, found " + std::to_string(words.size() - 1));
  if (words.size() - 1 > kMaxFaceCorners)
    throw InputError(where, "a face has " + std::to_string(words.size() - 1) + " corners; Rimu reads faces of at most " +
                                std::to_string(kMaxFaceCorners) +
                                " (triangulating one takes time growing with the square of its corners): split it, "
                                "or triangulate the mesh when exporting it");
  for (size_t w = 1; w < words.size(); ++w) {
    const std::string_view corner = words[w];
    // "p", "p/t", "p//n" or "p/t/n".
    std::string_view parts[3];
    size_t part = 0, start = 0;
    for (size_t i = 0; i <= corner.size(); ++i) {
      if (i < corner.size() && corner[i] != '/') continue;
      if (part == 3) throw InputError(where, "face corner '" + std::string(corner) + "' has more than 3 indices");
      parts[part++] = corner.substr(start, i - start);
      start = i + 1;
    }
    check_index(parts[0], "vertex", "vertices", so_far.positions, total.positions, corner, where);
    if (!parts[1].empty())
      check_index(parts[1], "texture coordinate", "texture coordinates", so_far.texcoords, total.texcoords, corner,
                  where);
    if (!parts[2].empty()) check_index(parts[2], "normal", "normals", so_far.normals, total.normals, corner, where);
    if (part == 3 && parts[2].empty())
      throw InputError(where, "face corner '" + std::string(corner) + "' ends in '/' with no normal index");
  }
}

}  // namespace

StatementLines check_obj_text(std::string_view text, const std::string& file) {
  reject_nul_bytes(text, file);
  Counts total;
  for_each_line(text, 1, [&](int, const Words& words) {
    total.positions += words[0] == "v";
    total.texcoords += words[0] == "vt";
    total.normals += words[0] == "vn";
  });

  StatementLines lines;
  Counts so_far;
  for_each_line(text, std::numeric_limits<size_t>::max(), [&](int line_number, const Words& words) {
    const SourceLocation where{file, line_number, ""};
    if (words[0] == "v") {
      check_numbers(words, 3, 3, where);  // x y z [w] [r g b]: only x y z reach the mesh
      lines.positions.push_back(line_number);
      ++so_far.positions;
    } else if (words[0] == "vt") {
      check_numbers(words, 1, 2, where);  // u [v] [w]
      lines.texcoords.push_back(line_number);
      ++so_far.texcoords;
    } else if (words[0] == "vn") {
      check_numbers(words, 3, 3, where);
      lines.normals.push_back(line_number);
      ++so_far.normals;
    } else if (words[0] == "f") {
      check_face(words, so_far, total, where);
    }
  });
  return lines;
}

}  // namespace rimu::obj
