// Mesh files by extension: the one entry point the scene loader calls.
#pragma once

#include <filesystem>
#include <string>

#include "render/scene/triangle_mesh.h"

namespace rimu {

/// Loads a mesh file by its extension (case-insensitive): .obj (load_obj), .ply or .ply.gz (load_ply). `object` names an
/// OBJ object/group to load instead of the whole file; a PLY file holds one mesh, so `object` must be empty.
/// Throws InputError naming the file for an unsupported extension (listing the supported ones) and for
/// everything the format loaders reject.
TriangleMesh load_mesh(const std::filesystem::path& path, const std::string& object = {});

}  // namespace rimu
