// libFuzzer target: the pbrt-v4 reader (tokenizer, parser, Include/Import, the translation into a Rimu scene
// document), then the same JSON loader a rendered .pbrt goes through, up to the committed Embree scene (no
// rendering). The input is written as a .pbrt file into a private folder that also holds copies of
// fuzz/scene_files, so mutated scenes reach the PLY (.ply and .ply.gz), image, spectrum and Include paths.
//
// One input may hold several files, so the Include graph is fuzzed too: a line "#file NAME" (a pbrt comment, so
// any input is still one ordinary pbrt file) starts the file NAME, written beside the input (NAME may name a
// sub-folder: "sub/part.pbrt"); what comes before the first such line is the scene file itself.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "spectral/library/spectral_library.h"

namespace {

// Generated triangles (Loop subdivision, sphere and disk meshes) cost about 15 µs each to import and load under the
// sanitizers (a 65,536-triangle loopsubdiv: 9 s at load 12), so the reader's own limit (2^21 per scene, several
// seconds in a release build) would let one input run past libFuzzer's timeout. Fuzzed scenes get two spheres'
// worth; the limit itself is checked the same way whatever its value. The same holds for the statements, included
// files and instances of the Include graph: an include or instance bomb stops at these within a second.
rimu::PbrtImportOptions fuzz_import_options(bool strict) {
  rimu::PbrtImportOptions options;
  options.strict = strict;
  options.max_generated_triangles = 20000;
  options.max_instances = 2000;
  options.max_shapes = 2000;
  options.parse_limits.max_statements = 20000;
  options.parse_limits.max_included_files = 256;
  return options;
}

// Copies fuzz/scene_files into the private folder once, beside the input file; returns their names.
const std::set<std::string>& scene_file_names() {
  static const std::set<std::string> names = [] {
    std::set<std::string> copied;
    const std::filesystem::path& private_folder = rimu::fuzz::private_folder();
    for (const auto& entry : std::filesystem::directory_iterator(RIMU_FUZZ_SCENE_FILES_DIR)) {
      std::filesystem::copy_file(entry.path(), private_folder / entry.path().filename(),
                                 std::filesystem::copy_options::overwrite_existing);
      copied.insert(entry.path().filename().string());
    }
    return copied;
  }();
  return names;
}

// A file of a multi-file input: its name inside the private folder, and its bytes.
struct ExtraFile {
  std::string name;
  std::string_view bytes;
};

// NAME of "#file NAME" if it is usable: 1-64 characters of [A-Za-z0-9._-], up to three '/'-separated parts, no
// "." or ".." part, and no clash with the input file or the copied scene files (which must stay as they are).
bool usable_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' || c == '/')) return false;
  int parts = 0;
  for (const auto& part : std::filesystem::path(name)) {
    const std::string text = part.string();
    if (text.empty() || text == "." || text == ".." || text == "/") return false;
    if (parts == 0 && (text == "input.pbrt" || scene_file_names().contains(text))) return false;
    ++parts;
  }
  return parts >= 1 && parts <= 3 && name.front() != '/' && name.back() != '/';
}

// Splits the input at "#file NAME" lines: the main file's bytes and up to 32 named files (a later file of the same
// name replaces an earlier one; a section with an unusable name is dropped).
std::string_view split_input(std::string_view text, std::vector<ExtraFile>& extra) {
  constexpr std::string_view marker = "#file ";
  std::string_view main = text;
  std::optional<size_t> section_start;  // of the file being collected
  std::string section_name;
  const auto close_section = [&](size_t end) {
    if (section_start && usable_name(section_name) && extra.size() < 32)
      extra.push_back({section_name, text.substr(*section_start, end - *section_start)});
  };
  for (size_t found = text.find(marker); found != std::string_view::npos; found = text.find(marker, found + 1)) {
    if (found != 0 && text[found - 1] != '\n') continue;  // only at the start of a line
    if (!section_start) main = text.substr(0, found);
    close_section(found);
    const size_t name_end = std::min(text.find('\n', found), text.size());
    section_name = std::string(text.substr(found + marker.size(), name_end - found - marker.size()));
    while (!section_name.empty() && (section_name.back() == '\r' || section_name.back() == ' ')) section_name.pop_back();
    section_start = std::min(name_end + 1, text.size());
  }
  close_section(text.size());
  return main;
}

// Writes this input's extra files, after removing the previous input's (so no input sees another's files).
void write_extra_files(const std::vector<ExtraFile>& extra) {
  static std::set<std::filesystem::path> written_tops;
  const std::filesystem::path& folder = rimu::fuzz::private_folder();
  std::error_code ignored;
  for (const std::filesystem::path& top : written_tops) std::filesystem::remove_all(folder / top, ignored);
  written_tops.clear();
  for (const ExtraFile& file : extra) {
    const std::filesystem::path path = folder / file.name;
    written_tops.insert(*std::filesystem::path(file.name).begin());
    std::filesystem::create_directories(path.parent_path(), ignored);
    if (std::filesystem::is_directory(path, ignored)) continue;  // "a/b" after "a/b/c": keep the folder
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(file.bytes.data(), std::streamsize(file.bytes.size()));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static rimu::SpectralLibrary library(RIMU_FUZZ_DATA_DIR);
  (void)scene_file_names();
  std::vector<ExtraFile> extra;
  const std::string_view main = split_input(rimu::fuzz::as_text(data, size), extra);
  write_extra_files(extra);
  const std::filesystem::path file =
      rimu::fuzz::write_private_file(reinterpret_cast<const uint8_t*>(main.data()), main.size(), ".pbrt");
  return rimu::fuzz::run_reader("fuzz_pbrt", [&] {
    // `rimu --strict` (anything unsupported is an error, thrown from where it is found, destructors included)
    // for inputs that hold the comment "# --strict".
    const bool strict = rimu::fuzz::as_text(data, size).find("# --strict") != std::string_view::npos;
    const rimu::PbrtImport imported = rimu::import_pbrt(file, library, fuzz_import_options(strict));
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
