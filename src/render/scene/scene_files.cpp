#include "render/scene/scene_files.h"

#include <fstream>
#include <iterator>
#include <set>

#include "render/scene/json_cursor.h"
#include "render/scene/pbrt/pbrt_to_scene.h"

namespace rimu {
namespace {

// A name resolved as the loaders resolve it, or nothing if it is not an existing regular file.
bool add_if_file(const std::string& name, const std::filesystem::path& folder, std::set<SceneFile>& files) {
  if (name.empty() || name.size() > 4096 || name.find('\0') != std::string::npos) return false;
  const std::filesystem::path written(name);
  const std::filesystem::path path = written.is_absolute() ? written : folder / written;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  files.insert({name, path});
  return true;
}

void add_json_strings(const nlohmann::json& value, const std::filesystem::path& folder, std::set<SceneFile>& files) {
  if (value.is_string()) {
    add_if_file(value.get<std::string>(), folder, files);
  } else if (value.is_structured()) {
    for (const auto& element : value) add_json_strings(element, folder, files);
  }
}

// Every "..." token of a pbrt-v4 file (pbrt strings have no escapes that matter for file names).
void add_pbrt_strings(const std::string& text, const std::filesystem::path& folder, std::set<SceneFile>& files,
                      int depth) {
  for (size_t open = text.find('"'); open != std::string::npos;) {
    const size_t close = text.find('"', open + 1);
    if (close == std::string::npos) break;
    const std::string name = text.substr(open + 1, close - open - 1);
    const size_t before = files.size();
    if (add_if_file(name, folder, files) && files.size() > before && depth < 8 &&
        std::filesystem::path(name).extension() == ".pbrt") {
      const std::filesystem::path written(name);
      std::ifstream in(written.is_absolute() ? written : folder / written, std::ios::binary);
      const std::string included((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      add_pbrt_strings(included, folder, files, depth + 1);  // pbrt resolves includes against the main file's folder
    }
    open = text.find('"', close + 1);
  }
}

}  // namespace

std::vector<SceneFile> scene_referenced_files(const std::string& text, const std::filesystem::path& scene_path) {
  std::set<SceneFile> files;
  const std::filesystem::path folder = scene_path.parent_path();
  if (is_pbrt_scene_path(scene_path)) add_pbrt_strings(text, folder, files, 0);
  else add_json_strings(parse_json_text(text, scene_path.string()), folder, files);
  return {files.begin(), files.end()};
}

}  // namespace rimu
