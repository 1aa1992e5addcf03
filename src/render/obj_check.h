// A line-by-line check of OBJ text before tinyobjloader parses it.
//
// tinyobjloader reads an unparsable number as 0 and drops faces with out-of-range indices with at most a
// warning that names the file's last line. Rimu's rule is that bad input fails at load time with its line, so
// this pass checks the statements the mesh is built from (v, vt, vn, f) and remembers where each v, vt and vn
// is, for errors found later (a zero normal, say). Other statements are left to tinyobjloader.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rimu::obj {

/// The 1-based line of every v, vt and vn statement, in file order (so positions[i] is the line of vertex i).
struct StatementLines {
  std::vector<int> positions;
  std::vector<int> texcoords;
  std::vector<int> normals;
};

/// The most corners a face may have. tinyobjloader triangulates a polygon by ear clipping, in time that grows
/// faster than the square of its corners: measured on one convex face (AMD EPYC, under load), 256 corners 0.3 ms,
/// 1024 corners 50-90 ms, 8192 corners 1.7 s; one face of 100 000 corners took 111 s. Up to 256 the cost per byte
/// of the file stays that of parsing it; a cylinder's cap from a modelling package has up to a few hundred corners.
inline constexpr size_t kMaxFaceCorners = 256;

/// Checks the text has no NUL byte, every v/vt/vn has finite numbers and every f has 3 to kMaxFaceCorners corners
/// whose indices (1-based, or negative = relative to the statements so far) are in range. Throws InputError naming
/// `file` and the line.
StatementLines check_obj_text(std::string_view text, const std::string& file);

}  // namespace rimu::obj
