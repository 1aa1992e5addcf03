// Triangle meshes from Wavefront OBJ files, parsed by tinyobjloader.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "render/scene/triangle_mesh.h"

namespace rimu {

/// Reads an OBJ mesh. `object` picks the shapes named so by an `o` or `g` statement; empty = every face in the
/// file, merged into one mesh. Polygons are triangulated by tinyobjloader; OBJ's separate position/uv/normal
/// index streams are de-indexed into one vertex per distinct (position, uv, normal) corner. Normals are
/// normalised. If only some corners carry a normal, the others get their triangle's geometric normal (flat
/// shading where the file gave none); if only some carry a uv, the others get (0, 0). Materials (mtllib,
/// usemtl) are ignored: the scene assigns materials. Degenerate triangles are kept (the scene removes and
/// counts them); the result always passes TriangleMesh::validate().
/// Throws InputError naming the file and line for malformed statements, out-of-range indices, non-finite
/// numbers, zero normals referenced by a face, an unknown `object`, or a file without faces.
/// Cost: two line scans plus tinyobjloader's parse.
TriangleMesh load_obj(const std::filesystem::path& path, const std::string& object = {});

/// load_obj on text already in memory; `file` is the name errors carry.
TriangleMesh parse_obj(std::string_view text, const std::string& file, const std::string& object = {});

}  // namespace rimu
