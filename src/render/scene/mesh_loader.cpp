#include "render/scene/mesh_loader.h"

#include <algorithm>
#include <cctype>

#include "render/scene/gzip_bytes.h"
#include "render/scene/obj_loader.h"
#include "render/scene/ply_loader.h"
#include "spectral/error.h"

namespace rimu {

TriangleMesh load_mesh(const std::filesystem::path& path, const std::string& object) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".obj") return load_obj(path, object);
  if (has_gzip_extension(path)) {
    std::string inner = path.stem().extension().string();  // "mesh.ply.gz" → ".ply"
    std::transform(inner.begin(), inner.end(), inner.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (inner == ".ply") extension = ".ply";
  }
  if (extension == ".ply") {
    if (!object.empty())
      throw InputError({path.string(), 0, ""},
                       "a PLY file holds a single mesh; object '" + object + "' can only be chosen in an OBJ file");
    return load_ply(path);
  }
  throw InputError(
      {path.string(), 0, ""},
      "unsupported mesh format '" + (extension.empty() ? "(no extension)" : extension) + "'; supported: .obj, .ply, .ply.gz");
}

}  // namespace rimu
