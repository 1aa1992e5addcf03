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

/// The most corners a face may have. tinyobjloader triangulates a polygon by ear clipping, in time that grows with
/// at least the square of its corners: one convex face took 0.3 ms at 256 corners, 50-90 ms at 1024 and 1.7 s at
/// 8192 (ObjReader::ParseFromString with triangulate, tinyobjloader from Debian 12, 2-core AMD EPYC at load 20),
/// and one face of 100 000 corners took 111 s. Up to 256 a face costs about what parsing its text does.
inline constexpr size_t kMaxFaceCorners = 256;

/// Checks the text has no NUL byte, every v/vt/vn has finite numbers and every f has 3 to kMaxFaceCorners corners
/// whose indices (1-based, or negative = relative to the statements so far) are in range. Throws InputError naming
/// `file` and the line.
StatementLines check_obj_text(std::string_view text, const std::string& file);

}  // namespace rimu::obj
