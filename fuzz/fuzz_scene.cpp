// libFuzzer target: the JSON scene loader, from the text to a committed Embree scene (no rendering).
#include <nlohmann/json.hpp>

#include "fuzz_support.h"
#include "render/scene/json_cursor.h"
#include "render/scene/scene.h"
#include "spectral/library/spectral_library.h"

namespace {

// A procedural cloud costs resolution³ × its 12 blobs at load (docs/scene-format.md allows 1–512): a legitimate
// slow input, not a defect, yet 200³ already takes 20 s under the sanitizers, which libFuzzer would report as a
// timeout. Such scenes are skipped; 64³ (the shipped scene's) and below are fuzzed.
bool has_large_procedural_medium(const nlohmann::json& document) {
  if (!document.is_object() || !document.contains("media") || !document["media"].is_object()) return false;
  for (const auto& [name, medium] : document["media"].items()) {
    if (!medium.is_object() || !medium.contains("procedural")) continue;
    const auto resolution = medium.find("resolution");
    if (resolution != medium.end() && resolution->is_number() && resolution->get<double>() > 64.0) return true;
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // One library for the whole run, as a tool has for one scene: its CSV cache is what a scene's named spectra
  // read. Relative paths in a scene resolve against fuzz/scene_files, which holds one small file of each kind a
  // scene refers to (mesh, IES, voxel grid, CSV, image), so mutated scenes reach those readers through the loader.
  static rimu::SpectralLibrary library(RIMU_FUZZ_DATA_DIR);
  static const std::filesystem::path scene_directory = RIMU_FUZZ_SCENE_FILES_DIR;
  return rimu::fuzz::run_reader("fuzz_scene", [&] {
    const nlohmann::json document = rimu::parse_json_text(std::string(rimu::fuzz::as_text(data, size)), "fuzz.json");
    if (has_large_procedural_medium(document)) return;
    (void)rimu::load_scene(document, "fuzz.json", scene_directory, library);
  });
}
