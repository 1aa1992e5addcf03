// pbrt-v4 spectra written as wavelength-value pairs, inline or in a file (docs/pbrt-import.md), and the inline
// table form of Rimu's spectral values they become.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "pbrt_test_support.h"

using namespace rimu;
using nlohmann::json;

using rimu::test::pbrt_t::import_error;

namespace pbrt_spectra_test {
const std::string kCamera = "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

TEST_CASE("pbrt spectra: inline pairs and spectrum files become inline tables carried out to 360-830 nm") {
  const std::filesystem::path file = test::test_data("pbrt/spectra.pbrt");
  const PbrtImport imported = import_pbrt(file, test::library());
  CHECK(imported.ignored.empty());
  const json& d = imported.document;
  // The light: pbrt normalises its spectrum to luminance 1, so only the shape travels, with a photometric amount.
  const json& light = d["lights"][0];
  CHECK(light["spectrum"] == json({{"wavelengths_nm", {360, 400, 500, 600, 700, 830}}, {"values", {1, 1, 2, 1.5, 0.5, 0.5}}}));
  CHECK(light.contains("illuminance_lx"));
  const json& diffuse = d["materials"][d["shapes"][0]["material"].get<std::string>()];
  CHECK(diffuse["reflectance"] == json({{"wavelengths_nm", {360, 400, 550, 700, 830}}, {"values", {0.1, 0.1, 0.5, 0.9, 0.9}}}));
  const json& conductor = d["materials"][d["shapes"][1]["material"].get<std::string>()];
  CHECK(conductor["n"] == json({{"wavelengths_nm", {360, 400, 700, 830}}, {"values", {1.2, 1.2, 0.3, 0.3}}}));
  CHECK(conductor["k"] == json({{"wavelengths_nm", {360, 400, 700, 830}}, {"values", {2.5, 2.5, 4, 4}}}));
  // Rimu's loader accepts them (and range-checks them at every nanometre) and renders without NaNs.
  const auto scene = load_scene(d, file.string(), file.parent_path(), test::library());
  const auto rendered = test::render_xyz(*scene, 4, 1);
  CHECK(rendered.film->sample_counts().discarded() == 0);
  CHECK(rendered.film->sample_counts().accepted > 0);
}

TEST_CASE("pbrt spectra: bad pairs and files are errors with the file and line") {
  CHECK_MESSAGE(import_error(kCamera + "Material \"diffuse\" \"spectrum reflectance\" [500 0.1 400 0.2]").find("t.pbrt:5: Material \"spectrum reflectance\": wavelengths must increase") != std::string::npos,
                import_error(kCamera + "Material \"diffuse\" \"spectrum reflectance\" [500 0.1 400 0.2]"));
  CHECK(import_error(kCamera + "Material \"diffuse\" \"spectrum reflectance\" \"missing.spd\"").find("t.pbrt:5: cannot find the spectrum file") != std::string::npos);
  const std::string bad_number = import_error(kCamera + "Material \"diffuse\" \"spectrum reflectance\" \"bad_spectrum_number.spd\"");
  CHECK_MESSAGE(bad_number.find("bad_spectrum_number.spd:2: expected a number, not 'half'") != std::string::npos, bad_number);
  // A named spectrum Rimu does not have is listed, not an error.
  const PbrtImport named = import_pbrt_text(kCamera + "Material \"dielectric\" \"spectrum eta\" \"glass-SF66\"", "t.pbrt", test::test_data("pbrt"), test::library());
  REQUIRE(named.ignored.size() == 1);
  CHECK(named.ignored[0].what.find("spectrum \"glass-SF66\"") != std::string::npos);
}

TEST_CASE("scene spectra: the inline table form is checked like a CSV column") {
  const auto reflectance_error = [](const json& reflectance) {
    json scene = {{"camera", {{"from", {0, 0, 5}}, {"to", {0, 0, 0}}, {"vertical_fov_deg", 30}}},
                  {"film", {{"resolution", {4, 4}}}},
                  {"materials", {{"m", {{"type", "diffuse"}, {"reflectance", reflectance}}}}},
                  {"shapes", {{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}}}};
    try {
      test::scene_from_json(scene);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(reflectance_error({{"wavelengths_nm", {400, 700}}, {"values", {0.2, 0.6}}}) == "no error");
  const std::string above_one = reflectance_error({{"wavelengths_nm", {400, 700}}, {"values", {0.2, 1.6}}});
  CHECK_MESSAGE(above_one.find("/materials/m/reflectance") != std::string::npos, above_one);
  const std::string unordered = reflectance_error({{"wavelengths_nm", {700, 400}}, {"values", {0.2, 0.6}}});
  CHECK_MESSAGE(unordered.find("increase") != std::string::npos, unordered);
  const std::string count = reflectance_error({{"wavelengths_nm", {400, 500, 700}}, {"values", {0.2, 0.6}}});
  CHECK_MESSAGE(count.find("expected 3 values") != std::string::npos, count);
}

TEST_CASE("pbrt float textures that are constant everywhere become numbers (constant, scale, mix)") {
  const PbrtImport imported = import_pbrt_text(
      kCamera +
          "Texture \"r\" \"float\" \"constant\" \"float value\" 0.04\n"
          "Texture \"half\" \"float\" \"scale\" \"texture tex\" \"r\" \"float scale\" 0.5\n"
          "Texture \"blend\" \"float\" \"mix\" \"texture tex1\" \"r\" \"float tex2\" 0.16 \"float amount\" 0.25\n"
          "Material \"conductor\" \"texture roughness\" \"half\" \"bool remaproughness\" false\n"
          "Shape \"sphere\"\n"
          "Material \"conductor\" \"texture roughness\" \"blend\" \"bool remaproughness\" false\n"
          "Shape \"sphere\"\n"
          "Texture \"grid\" \"float\" \"checkerboard\"\n"
          "Material \"conductor\" \"texture roughness\" \"grid\"\n"
          "Shape \"sphere\"\n",
      "t.pbrt", test::test_data("pbrt"), test::library());
  const json& d = imported.document;
  const auto material = [&](int shape) { return d["materials"][d["shapes"][shape]["material"].get<std::string>()]; };
  const auto roughness = [&](int shape) { return material(shape).value("roughness", -1.0); };
  // Rimu's roughness r is √α; without remapping α is pbrt's roughness: 0.04·0.5 = 0.02, and 0.75·0.04 + 0.25·0.16 = 0.07.
  CHECK(roughness(0) == doctest::Approx(std::pow(0.02, 0.5)));
  CHECK(roughness(1) == doctest::Approx(std::pow(0.07, 0.5)));
  // A texture that varies becomes a Rimu float texture (pbrt_texture_test.cpp has the classes), raised to ¼ per hit
  // under remaproughness; nothing is listed.
  CHECK(material(2)["roughness"] ==
        json({{"power", {{{"checkerboard", {1.0, 0.0}}, {"uv_scale", {1.0, 1.0}}, {"uv_offset", {0.0, 0.0}}}, 0.25}}}));
  CHECK(imported.ignored.empty());
}

}  // namespace pbrt_spectra_test
