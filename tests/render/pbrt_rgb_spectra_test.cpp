// pbrt-v4's RGB spectra in the importer (pbrt_rgb_spectra.cpp, docs/pbrt-import.md "RGB parameters"): constant RGB
// reflectances and RGB lights become pbrt's sigmoid-polynomial spectra as 1 nm tables, in the ColorSpace in effect;
// an RGB light keeps the film luminance of Rimu's RGB emission; --rgb-upsampler rimu keeps the old forms.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "pbrt_test_support.h"
#include "render/film/spectral_response.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"
#include "spectral/upsampling/sigmoid_polynomial.h"
#include "spectral/upsampling/upsampling_whites.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_rgb_spectra_test {

const std::string kCamera = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

const SigmoidFitter& fitter(const std::string& space) {
  static const SigmoidFitter srgb(test::library(), RgbColourSpace::named("srgb-linear"));
  static const SigmoidFitter rec2020(test::library(), RgbColourSpace::named("rec2020"));
  return space == "rec2020" ? rec2020 : srgb;
}

void check_table(const json& table, const std::function<double(double)>& expected) {
  REQUIRE(table.contains("wavelengths_nm"));
  const std::vector<double> nm = table["wavelengths_nm"], values = table["values"];
  REQUIRE(nm.size() == 471);
  CHECK(nm.front() == 360.0);
  CHECK(nm.back() == 830.0);
  for (size_t i = 0; i < nm.size(); ++i) {
    CAPTURE(nm[i]);
    REQUIRE(values[i] == doctest::Approx(expected(nm[i])).epsilon(1e-12));
  }
}

TEST_CASE("pbrt rgb reflectance: pbrt's albedo spectrum of the colour, in the ColorSpace in effect") {
  const PbrtImport imported = test::import_pbrt_test_text(
      kCamera + "MakeNamedMaterial \"red\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.63 0.065 0.05]\n"
                "MakeNamedMaterial \"grey\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.4 0.4 0.4]\n"
                "MakeNamedMaterial \"bright\" \"string type\" \"diffuse\" \"rgb reflectance\" [1.2 0.5 0.5]\n"
                "ColorSpace \"rec2020\"\n"
                "MakeNamedMaterial \"red2020\" \"string type\" \"coateddiffuse\" \"rgb reflectance\" [0.63 0.065 0.05]\n"
                "NamedMaterial \"red\"\nShape \"sphere\"\n");
  CHECK(imported.ignored.empty());
  const json& materials = imported.document["materials"];
  const SigmoidSpectrum red = fitter("srgb-linear").fit_albedo({0.63, 0.065, 0.05});
  CHECK(red.delta_e_ab < 0.1);
  check_table(materials["red"]["reflectance"], [&](double nm) { return red.value(nm); });
  const SigmoidSpectrum red2020 = fitter("rec2020").fit_albedo({0.63, 0.065, 0.05});
  check_table(materials["red2020"]["reflectance"], [&](double nm) { return red2020.value(nm); });
  CHECK(red2020.value(620) != doctest::Approx(red.value(620)));  // a different colour in a different space
  CHECK(materials["grey"]["reflectance"] == 0.4);                // greys are their constant
  // pbrt's albedo spectrum holds no component above 1: such a colour goes through Rimu's gamut mapping.
  CHECK(materials["bright"]["reflectance"] == json({{"rgb", {1.2, 0.5, 0.5}}, {"space", "srgb-linear"}}));
  CHECK_NOTHROW(load_scene(imported.document, "t.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt rgb L: pbrt's illuminant spectrum (unbounded fit × the space's white) at the RGB's own luminance") {
  const double k = SpectralResponse::cie_xyz(test::library()).luminance_nits_per_unit_y();
  const std::string scene = kCamera +
                            "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [17 12 4] \"float scale\" 2\n"
                            "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"integer indices\" [0 1 2]\nAttributeEnd\n"
                            "LightSource \"point\" \"rgb I\" [1 0.5 0.25]\n";
  const PbrtImport imported = test::import_pbrt_test_text(scene);
  CHECK(imported.ignored.empty());
  const json& emission = imported.document["shapes"][0]["emission"];
  const TabulatedSpectrum d65 = upsampling_illuminant(test::library(), upsampling_white_for(RgbColourSpace::named("srgb-linear").white()));
  const SigmoidSpectrum orange = fitter("srgb-linear").fit_unbounded({17, 12, 4});
  CHECK(orange.scale == 34.0);
  check_table(emission["spectrum"], [&](double nm) { return orange.value(nm) * d65.value(nm); });
  // Film Y = scale · Y_rgb, as the scene format's RGB emission gives (and pbrt: its luminance is the fit's m·Y).
  const double y_rgb = RgbColourSpace::named("srgb-linear").to_xyz({17, 12, 4}).y;
  CHECK(emission["luminance_nt"].get<double>() == doctest::Approx(2 * y_rgb * k).epsilon(1e-12));
  const json& point = imported.document["lights"][0];
  CHECK(point["luminous_intensity_cd"].get<double>() ==
        doctest::Approx(RgbColourSpace::named("srgb-linear").to_xyz({1, 0.5, 0.25}).y * k).epsilon(1e-12));
  CHECK_NOTHROW(load_scene(imported.document, "t.pbrt", test::test_data("pbrt"), test::library()));

  // Rimu's upsampler: the scene format's RGB emission, as before.
  PbrtImportOptions rimu_upsampler;
  rimu_upsampler.rgb_upsampler = PbrtRgbUpsampler::rimu;
  const PbrtImport old = test::import_pbrt_test_text(scene, "t.pbrt", rimu_upsampler);
  CHECK(old.document["shapes"][0]["emission"] == json({{"rgb", {17.0, 12.0, 4.0}}, {"space", "srgb-linear"}, {"scale", 2.0}}));
  CHECK(old.document["lights"][0]["intensity"] == json({{"rgb", {1.0, 0.5, 0.25}}, {"space", "srgb-linear"}, {"scale", 1.0}}));
}

TEST_CASE("pbrt rgb L: both upsamplers' emissions have the same luminance once loaded") {
  // What the film records of a light is its spectrum's Y: Σ L(λ) ȳ(λ) over the 1 nm grid; the two forms of one RGB
  // light agree to the sigmoid fit's colour error (ΔE*ab < 1e-6 here: far below the 1e-6 relative tolerance).
  const std::string scene = kCamera + "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [17 12 4]\n"
                                      "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 1 1 0] \"integer indices\" [0 1 2]\nAttributeEnd\n"
                                      "LightSource \"point\" \"rgb I\" [0.2 0.9 0.4] \"float scale\" 3\n";
  PbrtImportOptions rimu_upsampler;
  rimu_upsampler.rgb_upsampler = PbrtRgbUpsampler::rimu;
  const Observer& observer = test::library().observer(StandardObserver::cie1931_2deg);
  const auto luminances = [&](const PbrtImportOptions& options) {
    const PbrtImport imported = test::import_pbrt_test_text(scene, "t.pbrt", options);
    const auto loaded = load_scene(imported.document, "t.pbrt", test::test_data("pbrt"), test::library());
    std::vector<double> y;
    for (const auto& light : loaded->lights) {
      const LightSpectrum* spectrum = light->emitted_spectrum();
      REQUIRE(spectrum);
      double sum = 0;
      for (int nm = 360; nm <= 830; ++nm) sum += spectrum->value(nm) * observer.y_bar.value(nm);
      y.push_back(sum);
    }
    return y;
  };
  const std::vector<double> sigmoid = luminances({}), rimu = luminances(rimu_upsampler);
  REQUIRE(sigmoid.size() == 2);
  REQUIRE(rimu.size() == 2);
  for (size_t i = 0; i < 2; ++i) CHECK(sigmoid[i] == doctest::Approx(rimu[i]).epsilon(1e-4));
}

}  // namespace pbrt_rgb_spectra_test
