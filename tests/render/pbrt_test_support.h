// What the pbrt-v4 import tests share: a text imported as a file in tests/data/pbrt, the message of the InputError
// an import raises, short names for both with the film and camera tests' camera, a file's text, and a check that
// a message names every expected part.
#pragma once

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>

#include "render/scene/pbrt/pbrt_to_scene.h"
#include "spectral/upsampling/sigmoid_polynomial.h"
#include "test_support.h"

// Checks that `text` contains every part, printing the text when it does not.
#define CHECK_CONTAINS(text, ...)                                                                   \
  do {                                                                                              \
    const std::string checked_text = (text);                                                        \
    for (const std::string& part : std::initializer_list<std::string>{__VA_ARGS__})                 \
      CHECK_MESSAGE(checked_text.find(part) != std::string::npos, "'" << checked_text << "' lacks '" << part << "'"); \
  } while (0)

namespace rimu::test {

/// What the importer writes for a constant `rgb reflectance` (r, g, b) of linear sRGB (not grey, components ≤ 1):
/// pbrt's sigmoid-polynomial albedo spectrum as a 1 nm table (docs/pbrt-import.md, "RGB parameters").
inline nlohmann::json pbrt_rgb_reflectance(double r, double g, double b) {
  static const SigmoidFitter fitter(library(), RgbColourSpace::named("srgb-linear"));
  const SigmoidSpectrum s = fitter.fit_albedo({r, g, b});
  nlohmann::json nm = nlohmann::json::array(), values = nlohmann::json::array();
  for (int wavelength_nm = 360; wavelength_nm <= 830; ++wavelength_nm) {
    nm.push_back(wavelength_nm);
    values.push_back(s.value(wavelength_nm));
  }
  return {{"wavelengths_nm", nm}, {"values", values}};
}

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

/// Short names for tests that import every text as t.pbrt (the film and camera tests: `using namespace
/// rimu::test::pbrt_t;`; others take a using-declaration of the one they need).
namespace pbrt_t {
inline PbrtImport import_text(const std::string& text) { return import_pbrt_test_text(text); }
inline std::string import_error(const std::string& text) { return pbrt_import_error(text); }
/// A perspective camera at (0, 0, 5) looking at the origin; the text goes on with Film and WorldBegin.
inline const std::string kCamera = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\n";
}  // namespace pbrt_t

/// The whole text of a file.
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace rimu::test
