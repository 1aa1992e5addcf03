// libFuzzer target: the JSON scene loader, from the text to a committed Embree scene (no rendering).
#include <nlohmann/json.hpp>

#include "fuzz_support.h"
#include "render/json_cursor.h"
#include "render/scene.h"
#include "spectral/spectral_library.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // One library for the whole run, as a tool has for one scene: its CSV cache is what a scene's named spectra
  // read. Relative paths in a scene resolve against fuzz/scene_files, which holds one small file of each kind a
  // scene refers to (mesh, IES, voxel grid, CSV, image), so mutated scenes reach those readers through the loader.
  static rimu::SpectralLibrary library(RIMU_FUZZ_DATA_DIR);
  static const std::filesystem::path scene_directory = RIMU_FUZZ_SCENE_FILES_DIR;
  return rimu::fuzz::run_reader("fuzz_scene", [&] {
    const nlohmann::json document = rimu::parse_json_text(std::string(rimu::fuzz::as_text(data, size)), "fuzz.json");
    (void)rimu::load_scene(document, "fuzz.json", scene_directory, library);
  });
}
