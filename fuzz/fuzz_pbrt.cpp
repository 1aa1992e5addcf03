// libFuzzer target: the pbrt-v4 reader (tokenizer, parser, Include/Import, the translation into a Rimu scene
// document), then the same JSON loader a rendered .pbrt goes through, up to the committed Embree scene (no
// rendering). The input is written as a .pbrt file into a private folder that also holds copies of
// fuzz/scene_files, so mutated scenes reach the PLY (.ply and .ply.gz), image, spectrum and Include paths.
#include <filesystem>
#include <optional>

#include "fuzz_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "spectral/spectral_library.h"

namespace {

// Generated triangles (Loop subdivision, sphere and disk meshes) cost about 15 µs each to import and load under the
// sanitizers (a 65,536-triangle loopsubdiv: 9 s at load 12), so the reader's own limit (2^21 per scene, several
// seconds in a release build) would let one input run past libFuzzer's timeout. Fuzzed scenes get two spheres'
// worth; the limit itself is checked the same way whatever its value.
constexpr std::size_t kFuzzGeneratedTriangles = 20000;

// Copies fuzz/scene_files into the private folder once, beside the input file.
const std::filesystem::path& folder_with_scene_files() {
  static const std::filesystem::path folder = [] {
    const std::filesystem::path& private_folder = rimu::fuzz::private_folder();
    for (const auto& entry : std::filesystem::directory_iterator(RIMU_FUZZ_SCENE_FILES_DIR))
      std::filesystem::copy_file(entry.path(), private_folder / entry.path().filename(),
                                 std::filesystem::copy_options::overwrite_existing);
    return private_folder;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static rimu::SpectralLibrary library(RIMU_FUZZ_DATA_DIR);
  (void)folder_with_scene_files();
  const std::filesystem::path file = rimu::fuzz::write_private_file(data, size, ".pbrt");
  return rimu::fuzz::run_reader("fuzz_pbrt", [&] {
    // `rimu --strict` (anything unsupported is an error, thrown from where it is found, destructors included)
    // for inputs that hold the comment "# --strict".
    const bool strict = rimu::fuzz::as_text(data, size).find("# --strict") != std::string_view::npos;
    const rimu::PbrtImport imported = rimu::import_pbrt(file, library, {strict, {}, kFuzzGeneratedTriangles});
    (void)rimu::describe_ignored(imported.ignored);
    try {
      (void)rimu::load_scene(imported.document, file.string(), file.parent_path(), library);
    } catch (const rimu::InputError& e) {
      // As `rimu scene.pbrt` does: the error moves to the pbrt statement that made the part it names.
      if (std::optional<rimu::InputError> at_pbrt = rimu::at_pbrt_origin(e, imported.origins)) throw *at_pbrt;
      throw;
    }
  });
}
