// pbrt-v4's RGB optical constants (docs/pbrt-import.md, Materials): a conductor's "rgb eta" / "rgb k" and a
// dielectric's "rgb eta" become pbrt's unbounded RGB spectra (the reflectance-like spectrum of rgb/(2·max) times
// 2·max), so two RGB metals stay two metals (a scene's silver and gold both became copper before), and a coloured
// eta disperses.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/scene.h"
#include "render/scene/spectrum_input.h"
#include "spectral/upsampling/sigmoid_polynomial.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_rgb_optical_constants_test {

const std::string kCamera = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

// pbrt-v4's RGBUnboundedSpectrum of `rgb` (in linear sRGB) at λ: the sigmoid fit the importer uses by default.
double unbounded(const std::array<double, 3>& rgb, double lambda_nm) {
  static const SigmoidFitter fitter(test::library(), RgbColourSpace::named("srgb-linear"));
  return fitter.fit_unbounded({rgb[0], rgb[1], rgb[2]}).value(lambda_nm);
}

// The same shape through Rimu's reflectance upsampler (the importer's --rgb-upsampler rimu).
double rimu_unbounded(const std::array<double, 3>& rgb, double lambda_nm) {
  const double scale = 2.0 * std::max({rgb[0], rgb[1], rgb[2]});
  const auto upsampler = shared_upsampler(test::library(), "srgb-linear");
  return scale * upsampler->reflectance_spectrum({rgb[0] / scale, rgb[1] / scale, rgb[2] / scale}).value(lambda_nm);
}

// The reflectance at normal incidence of the smooth material `name` for the four wavelengths `lambda`: the weight
// f·cos/pdf of its one (delta) sample, which for a conductor is the Fresnel reflectance.
Float4 normal_incidence_reflectance(const Scene& scene, const std::string& name, const SampledWavelengths& lambda) {
  const Bsdf bsdf = test::material_named(scene, name).bsdf(MaterialContext::at_uv({0.5f, 0.5f}), lambda);
  const auto sample = bsdf.sample({0, 0, 1}, 0.5f, {0.5f, 0.5f});
  REQUIRE(sample);
  REQUIRE(sample->is_delta);
  return sample->f * Float4(std::fabs(sample->wi.z)) / sample->pdf;
}

TEST_CASE("pbrt conductor with rgb eta and k: pbrt's unbounded RGB, and the Fresnel reflectance of those n, k") {
  const std::array<double, 3> silver_eta{0.16, 0.14, 0.13}, silver_k{4.0, 3.2, 2.4};
  const std::array<double, 3> gold_eta{0.14, 0.42, 1.35}, gold_k{3.98, 2.38, 1.6};
  const auto rgb = [](const std::array<double, 3>& c) {
    return "[" + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "]";
  };
  const PbrtImport imported = test::import_pbrt_test_text(
      kCamera + "MakeNamedMaterial \"silver\" \"string type\" \"conductor\" \"rgb eta\" " + rgb(silver_eta) + " \"rgb k\" " +
      rgb(silver_k) + "\nMakeNamedMaterial \"gold\" \"string type\" \"conductor\" \"rgb eta\" " + rgb(gold_eta) + " \"rgb k\" " +
      rgb(gold_k) + "\nNamedMaterial \"silver\"\nShape \"sphere\"\nNamedMaterial \"gold\"\nShape \"sphere\" \"float radius\" 0.5\n");
  CHECK(imported.ignored.empty());
  const json& materials = imported.document["materials"];
  CHECK_FALSE(materials["silver"].contains("metal"));  // not pbrt's copper
  const auto scene = load_scene(imported.document, "t.pbrt", test::test_data("pbrt"), test::library());
  // At the 1 nm knots of the written table the spectra are the fit's, so F is the formula's to single-precision rounding.
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 650.0f, 700.0f), Float4(1.0f));
  for (const auto& [name, eta, k] : {std::tuple{"silver", silver_eta, silver_k}, std::tuple{"gold", gold_eta, gold_k}}) {
    CAPTURE(name);
    const Float4 reflectance = normal_incidence_reflectance(*scene, name, lambda);
    for (int lane = 0; lane < 4; ++lane) {
      const double l = lambda.lambda_nm()[lane], n = unbounded(eta, l), kappa = unbounded(k, l);
      const double fresnel = ((n - 1) * (n - 1) + kappa * kappa) / ((n + 1) * (n + 1) + kappa * kappa);
      CAPTURE(l);
      CHECK(reflectance[lane] == doctest::Approx(fresnel).epsilon(1e-4));
    }
  }
  // Gold reflects red far more than blue; silver nearly evenly.
  const Float4 gold = normal_incidence_reflectance(*scene, "gold", lambda);
  const Float4 silver = normal_incidence_reflectance(*scene, "silver", lambda);
  CHECK(gold[3] - gold[0] > 0.3f);
  CHECK(std::abs(silver[3] - silver[0]) < 0.1f);
}

TEST_CASE("pbrt dielectric with rgb eta: accepted as pbrt's unbounded RGB (grey: a constant, coloured: dispersion)") {
  const PbrtImport imported = test::import_pbrt_test_text(
      kCamera + "MakeNamedMaterial \"grey\" \"string type\" \"dielectric\" \"rgb eta\" [1.5 1.5 1.5]\n"
                "MakeNamedMaterial \"flint\" \"string type\" \"dielectric\" \"rgb eta\" [1.60 1.62 1.66]\n"
                "MakeNamedMaterial \"coat\" \"string type\" \"coateddiffuse\" \"rgb eta\" [1.4 1.5 1.6]\n"
                "NamedMaterial \"flint\"\nShape \"sphere\"\n");
  CHECK(imported.ignored.empty());
  const json& materials = imported.document["materials"];
  CHECK(materials["grey"]["ior"] == 1.5);
  const json& flint = materials["flint"]["ior"];
  REQUIRE(flint.contains("values"));
  const std::vector<double> nm = flint["wavelengths_nm"], values = flint["values"];
  for (size_t i = 0; i < nm.size(); ++i) CHECK(values[i] == doctest::Approx(unbounded({1.60, 1.62, 1.66}, nm[i])));
  CHECK(materials["coat"]["coat_ior"].contains("values"));
  // With Rimu's upsampler instead: its reflectance shape of rgb/(2·max), on a 5 nm table.
  PbrtImportOptions rimu_upsampler;
  rimu_upsampler.rgb_upsampler = PbrtRgbUpsampler::rimu;
  const json rimu_flint = test::import_pbrt_test_text(kCamera + "MakeNamedMaterial \"flint\" \"string type\" \"dielectric\" "
                                                      "\"rgb eta\" [1.60 1.62 1.66]\n", "t.pbrt", rimu_upsampler)
                              .document["materials"]["flint"]["ior"];
  const std::vector<double> rimu_nm = rimu_flint["wavelengths_nm"], rimu_values = rimu_flint["values"];
  CHECK(rimu_nm[1] - rimu_nm[0] == 5.0);
  for (size_t i = 0; i < rimu_nm.size(); ++i) CHECK(rimu_values[i] == doctest::Approx(rimu_unbounded({1.60, 1.62, 1.66}, rimu_nm[i])));
  const auto scene = load_scene(imported.document, "t.pbrt", test::test_data("pbrt"), test::library());
  CHECK(scene->materials.size() >= 1);
  // Negative RGB is the parser's error (as for every RGB); a black index is an error at the parameter.
  CHECK_CONTAINS(test::pbrt_import_error(kCamera + "Material \"dielectric\" \"rgb eta\" [1.5 -1 1.5]"), "t.pbrt:4",
                 "RGB values must be >= 0");
  CHECK_CONTAINS(test::pbrt_import_error(kCamera + "Material \"dielectric\" \"rgb eta\" [0 0 0]"), "t.pbrt:4",
                 "must not be black");
  // A conductor's n = 0 with k > 0 is a meaningful complex index (pbrt-v4 takes it: pbrt-v3-scenes' dragon/f14-3);
  // Rimu's n > 0 gets 1e-3 in its place.
  const json metal = test::import_pbrt_test_text(kCamera + "MakeNamedMaterial \"m\" \"string type\" \"conductor\" "
                                                 "\"rgb eta\" [0 0 0] \"rgb k\" [1 1 1]\n")
                         .document["materials"]["m"];
  CHECK(metal["n"] == 1e-3);
}

}  // namespace pbrt_rgb_optical_constants_test
