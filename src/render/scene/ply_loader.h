// Triangle meshes from PLY files (ascii, binary little-endian, binary big-endian).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "render/scene/triangle_mesh.h"

namespace rimu {

/// Reads a PLY mesh (gzip-compressed if the name ends in .gz, e.g. mesh.ply.gz): element `vertex` with x y z (any numeric type), optionally nx ny nz (normalised on load)
/// and one of the uv pairs u v / s t / texture_u texture_v / texture_s texture_t; element `face` with a list
/// property `vertex_indices` (or `vertex_index`). Polygons are fan-triangulated (0, i, i+1), which is exact for
/// convex faces. Other elements and properties are skipped. Degenerate triangles are kept (the scene removes
/// and counts them); the result always passes TriangleMesh::validate().
/// Throws InputError naming the file and the header line, or the element and record ("face 17"), for anything
/// malformed: unknown format, truncated body, out-of-range index, non-finite coordinate. Cost: one pass.
TriangleMesh load_ply(const std::filesystem::path& path);

/// A .ply.gz's header must lie in its first 1 MiB (a real header takes a few hundred bytes); the file may then
/// decompress to at most its header plus ply::max_body_bytes of it (docs/scene-format.md, "Limits").
inline constexpr std::uintmax_t kMaxCompressedPlyHeaderBytes = std::uintmax_t(1) << 20;

/// load_ply on bytes already in memory; `file` is the name errors carry.
TriangleMesh parse_ply(std::string_view bytes, const std::string& file);

}  // namespace rimu
