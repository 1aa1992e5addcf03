// The files a scene names (meshes, CSV spectra, textures, IES profiles, volumes, included pbrt files): what the
// scene hash covers besides the scene file itself, so that a farm task, a merge or a resume sees a changed mesh or
// spectrum as a changed scene (render_job.h, scene_hash()).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rimu {

/// A file named by a scene: the name as the scene writes it, and where it resolves.
struct SceneFile {
  std::string name;             ///< as written (relative names stay relative, so a moved scene folder keeps its hash)
  std::filesystem::path path;   ///< resolved against the scene's folder
  friend bool operator<(const SceneFile& a, const SceneFile& b) { return a.name < b.name; }
};

/// The existing regular files named by `text`, the scene file at `scene_path` after frame substitution, sorted by
/// name and without repeats. In a JSON scene every string value is a candidate (a relative one resolved against the
/// scene's folder, as the loader does); any string that names an existing regular file counts, so a new key that
/// names a file is covered without a list to keep up to date. In a pbrt-v4 scene every quoted string is a
/// candidate, and the .pbrt files it includes are searched in turn (to 8 levels). Cost: one stat per string.
std::vector<SceneFile> scene_referenced_files(const std::string& text, const std::filesystem::path& scene_path);

}  // namespace rimu
