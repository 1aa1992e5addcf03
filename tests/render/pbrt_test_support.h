// What the pbrt-v4 import tests share: a text imported as a file in tests/data/pbrt, the message of the InputError
// an import raises, and a file's text.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_support.h"

namespace rimu::test {

/// `text` imported as the pbrt-v4 file `name` in tests/data/pbrt: its Includes, meshes and images resolve there,
/// and its messages name `name`.
inline PbrtImport import_pbrt_test_text(const std::string& text, const std::string& name = "t.pbrt",
                                        const PbrtImportOptions& options = {}) {
  return import_pbrt_text(text, name, test_data("pbrt"), library(), options);
}

/// The message of the InputError that importing `text` as above raises, or "no error".
inline std::string pbrt_import_error(const std::string& text, const std::string& name = "t.pbrt",
                                     const PbrtImportOptions& options = {}) {
  try {
    import_pbrt_test_text(text, name, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

/// The whole text of a file.
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rimu::test
