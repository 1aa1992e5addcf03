// The measured material in scenes: JSON {"type": "measured", "file": ...}, pbrt-v4's `Material "measured"`, errors
// that name the key or line, one table per file, and a render of a tabulated GGX gold that matches the analytic gold.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "spectral/error.h"
#include "spectral/library/optical_constants.h"
#include "test_support.h"
#include "transport/bsdfs/measured_brdf_tabulation.h"

using namespace rimu;
using nlohmann::json;

namespace measured_material_test {

const float kAlpha = 0.3f;

// A GGX gold of α = 0.3 as a tensor file in `folder`, at 360–830 nm every 10 nm.
std::filesystem::path write_gold(const test::ScratchFolder& folder, const std::string& name) {
  const MicrofacetTabulation t = MicrofacetTabulation::conductor(conductor_ior(test::library(), "gold"), kAlpha);
  return folder.write(name, TensorFile::serialise(tabulate_microfacet_brdf(t)));
}

// A gold ball filling most of a 24 × 24 image under a uniform sky.
json ball_scene(const json& material) {
  json scene = json::parse(R"({
    "camera": {"from": [0, 0, 4], "to": [0, 0, 0], "up": [0, 1, 0], "vertical_fov_deg": 26},
    "film": {"resolution": [24, 24], "filter": {"type": "box", "radius": 0.5}},
    "integrator": {"spp": 64, "max_depth": 3},
    "lights": [{"type": "environment", "radiance": {"illuminant": "D65", "scale": 1}}],
    "shapes": [{"type": "sphere", "material": "ball", "center": [0, 0, 0], "radius": 0.85}]
  })");
  scene["materials"] = {{"ball", material}};
  return scene;
}

}  // namespace measured_material_test

using namespace measured_material_test;

TEST_CASE("measured material: a tabulated gold ball renders as the analytic gold ball") {
  test::ScratchFolder folder("measured_render");
  write_gold(folder, "gold.bsdf");
  const auto measured = load_scene(ball_scene({{"type", "measured"}, {"file", "gold.bsdf"}}), "m.json", folder.path, test::library());
  const auto analytic = load_scene(ball_scene({{"type", "conductor"}, {"metal", "gold"}, {"roughness", std::sqrt(kAlpha)}}),
                                   "a.json", folder.path, test::library());
  const std::vector<double> m = test::luminance_values(*test::render_xyz(*measured, 64, 1).film);
  const std::vector<double> a = test::luminance_values(*test::render_xyz(*analytic, 64, 2).film);
  // Both images are the sky reflected by gold: the means differ by the tabulation's error (the directional albedo
  // agrees within 2 %, tests/transport/measured_bsdf_test.cpp) and the noise (a paired difference's standard error).
  const test::Estimate difference = test::paired_difference(m, a);
  const double mean = test::mean_of(a);
  CAPTURE(test::mean_of(m));
  CAPTURE(mean);
  CAPTURE(difference.standard_error);
  CHECK(std::fabs(difference.mean) < 0.02 * mean + 3.0 * difference.standard_error);
  CHECK(test::finite_total(*test::render_xyz(*measured, 4, 3).film) > 0.0);
}

TEST_CASE("measured material: materials naming one file share its tables, a bad file is an error at the key") {
  test::ScratchFolder folder("measured_json");
  write_gold(folder, "gold.bsdf");
  json document = ball_scene({{"type", "measured"}, {"file", "gold.bsdf"}});
  document["materials"]["again"] = {{"type", "measured"}, {"file", "./gold.bsdf"}};
  const auto scene = load_scene(document, "m.json", folder.path, test::library());
  const auto& first = std::get<MeasuredMaterial>(test::material_named(*scene, "ball").variant());
  const auto& second = std::get<MeasuredMaterial>(test::material_named(*scene, "again").variant());
  CHECK(&first.brdf() == &second.brdf());

  document["materials"]["again"]["file"] = "absent.bsdf";
  CHECK_THROWS_WITH_AS(load_scene(document, "m.json", folder.path, test::library()),
                       doctest::Contains("/materials/again/file"), InputError);
  folder.write("broken.bsdf", "tensor_file");
  document["materials"]["again"]["file"] = "broken.bsdf";
  CHECK_THROWS_WITH_AS(load_scene(document, "m.json", folder.path, test::library()), doctest::Contains("broken.bsdf"),
                       InputError);
  document["materials"]["again"] = {{"type", "measured"}};
  CHECK_THROWS_WITH_AS(load_scene(document, "m.json", folder.path, test::library()),
                       doctest::Contains("/materials/again"), InputError);
}

TEST_CASE("pbrt measured: the file is imported and read, a missing filename or file is an error at its line") {
  test::ScratchFolder folder("measured_pbrt");
  write_gold(folder, "gold.bsdf");
  const std::string head = "LookAt 0 0 4  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  const PbrtImport imported =
      import_pbrt_text(head + "Material \"measured\" \"string filename\" \"gold.bsdf\"\nShape \"sphere\"\n", "test.pbrt",
                       folder.path, test::library());
  CHECK(imported.ignored.empty());
  const json& m = imported.document["materials"];
  REQUIRE(m.size() == 1);
  CHECK(m.begin().value()["type"] == "measured");
  const auto scene = load_scene(imported.document, "test.pbrt", folder.path, test::library());
  CHECK(std::holds_alternative<MeasuredMaterial>(scene->materials.at(0).variant()));

  CHECK_THROWS_WITH_AS(import_pbrt_text(head + "Material \"measured\"\n", "test.pbrt", folder.path, test::library()),
                       doctest::Contains("test.pbrt:4"), InputError);
  CHECK_THROWS_WITH_AS(import_pbrt_text(head + "Material \"measured\" \"string filename\" \"nope.bsdf\"\n", "test.pbrt",
                                        folder.path, test::library()),
                       doctest::Contains("cannot find the BRDF file"), InputError);
}
