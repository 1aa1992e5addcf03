// pbrt-v4 statements with their typed parameter lists (pbrt.org/fileformat-v4), read from a file and the files it
// Includes or Imports. The parser checks syntax and types; what the statements mean is pbrt_to_scene's business.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "spectral/error.h"

namespace rimu {

/// The parameter types of pbrt-v4 ("point" and "vector" are accepted for point3 and vector3, "normal3" for normal).
enum class PbrtParamType { integer, real, point2, vector2, point3, vector3, normal, boolean, string, rgb, spectrum,
                           blackbody, texture };

/// One `"type name" value(s)` entry of a statement.
struct PbrtParam {
  PbrtParamType type = PbrtParamType::real;
  std::string type_name;  ///< as written ("float", "point3", ...)
  std::string name;
  std::vector<double> numbers;       ///< integer, float, point/vector/normal, rgb, blackbody, inline spectrum pairs
  std::vector<std::string> strings;  ///< string, texture, named spectrum or spectrum file
  std::vector<bool> bools;
  SourceLocation where;  ///< file and line of the declaration
};

/// One statement: its keyword, positional arguments and parameters.
struct PbrtStatement {
  std::string keyword;  ///< "Shape", "Translate", ...
  SourceLocation where;
  std::filesystem::path directory;   ///< folder of the file it is in: relative file names resolve against it
  std::vector<double> numbers;       ///< positional numbers (Translate x y z, Transform [16 numbers])
  std::vector<std::string> strings;  ///< positional strings (Shape "sphere", Texture "name" "spectrum" "imagemap")
  std::vector<PbrtParam> params;
  /// The parameter of that name, or null. pbrt looks parameters up by name only; the type is checked by the caller.
  const PbrtParam* find(const std::string& name) const;
};

/// Bounds on the work one scene's files expand to, counted over the whole Include graph (a file included twice
/// counts twice): 41 files of a few lines that each include the next twice would otherwise be read 2^40 times.
/// Each bound is far above what production scenes use (docs/pbrt-import.md, "Limits"); crossing one is an
/// InputError at the statement that crossed it.
struct PbrtParseLimits {
  std::size_t max_statements = std::size_t(1) << 24;  ///< statements handed on (16,777,216), Includes not counted
  std::size_t max_included_files = std::size_t(1) << 16;  ///< Include and Import statements followed (65,536)
};

/// The most bytes of one pbrt file: its text is held while it is parsed (each Include level holds its own file).
inline constexpr std::uintmax_t kMaxPbrtFileBytes = std::uintmax_t(1) << 30;

/// Reads `file` and calls `handle` on each statement in order, following Include and Import (paths relative to the
/// directory of the file that names them; Import is read as Include). Every file is read by read_input_file
/// (input_file.h: regular files only, at most kMaxPbrtFileBytes; recorded by an active InputFileLog). Throws
/// InputError with the file and line for unknown statements, wrong arguments, badly typed parameters, non-finite
/// numbers, strings that are not UTF-8, missing or unreadable files and a crossed limit.
void parse_pbrt_file(const std::filesystem::path& file, const std::function<void(const PbrtStatement&)>& handle,
                     const PbrtParseLimits& limits = {});
/// The same on text already in memory; `file` is the name errors carry and `directory` resolves Includes.
void parse_pbrt_text(const std::string& text, const std::string& file, const std::filesystem::path& directory,
                     const std::function<void(const PbrtStatement&)>& handle, const PbrtParseLimits& limits = {});

}  // namespace rimu
