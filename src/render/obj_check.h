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

/// Checks every v/vt/vn has finite numbers and every f has at least 3 corners whose indices (1-based, or
/// negative = relative to the statements so far) are in range. Throws InputError naming `file` and the line.
StatementLines check_obj_text(std::string_view text, const std::string& file);

}  // namespace rimu::obj
