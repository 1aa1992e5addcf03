// The stochastic "mix" material through the whole renderer: a 50/50 mix renders as the average of its two
// materials' images, and a pbrt-v4 "mix" renders as the same scene written in Rimu's JSON.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"

using namespace rimu;
using nlohmann::json;

namespace {

// A floor lit by a small black-backed emitter: the floor's material is met only at the camera ray's first hit
// (the floor cannot see itself and the emitter reflects nothing), so the expected image is linear in the floor's
// BSDF and a per-point 50/50 choice must average the two materials' images exactly.
json floor_scene(const json& floor_material) {
  json scene = json::parse(R"({
    "camera": {"from": [0, 1.2, -2.2], "to": [0, 0, 0.2], "vertical_fov_deg": 40},
    "film": {"resolution": [32, 32], "filter": {"type": "box"}},
    "integrator": {"max_depth": 8},
    "materials": {
      "matte": {"type": "diffuse", "reflectance": 0.7},
      "glossy": {"type": "conductor", "metal": "gold", "roughness": 0.3},
      "black": {"type": "diffuse", "reflectance": 0}
    },
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]]},
      {"type": "quad", "material": "black", "emission": 4,
       "vertices": [[-0.3, 1, -0.3], [0.3, 1, -0.3], [0.3, 1, 0.3], [-0.3, 1, 0.3]]}
    ]
  })");
  scene["materials"]["floor"] = floor_material;
  return scene;
}

std::vector<double> luminance_of(const json& scene, int spp, uint64_t seed) {
  return test::luminance_values(*test::render_xyz(*test::scene_from_json(scene), spp, seed).film);
}


}  // namespace

TEST_CASE("mix material: a 50/50 mix renders as the average of its two materials' images") {
  const std::vector<double> matte = luminance_of(floor_scene({{"type", "diffuse"}, {"reflectance", 0.7}}), 32, 1);
  const std::vector<double> glossy =
      luminance_of(floor_scene({{"type", "conductor"}, {"metal", "gold"}, {"roughness", 0.3}}), 32, 2);
  const std::vector<double> mixed =
      luminance_of(floor_scene({{"type", "mix"}, {"materials", {"matte", "glossy"}}, {"amount", 0.5}}), 32, 3);
  // The average of two independent renders has the per-pixel variance (σ_a² + σ_b²)/4, which paired_difference
  // estimates from the data together with the mix's own.
  std::vector<double> average(matte.size());
  for (size_t i = 0; i < matte.size(); ++i) average[i] = 0.5 * (matte[i] + glossy[i]);
  for (double deviation : test::block_deviations(mixed, average)) CHECK(deviation <= test::kSigmas);
  // The check can fail: a 20/80 mix is told apart from the 50/50 average, and so are the two materials.
  const std::vector<double> mostly_glossy =
      luminance_of(floor_scene({{"type", "mix"}, {"materials", {"matte", "glossy"}}, {"amount", 0.8}}), 32, 4);
  CHECK(test::worst_deviation(test::block_deviations(mostly_glossy, average)) > test::kSigmas);
  CHECK(test::worst_deviation(test::block_deviations(matte, glossy)) > test::kSigmas);
}

TEST_CASE("mix material: JSON errors name the key") {
  const auto error_of = [](const json& scene) -> std::string {
    try {
      test::scene_from_json(scene);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  json missing = floor_scene({{"type", "mix"}, {"materials", {"matte", "nope"}}});
  CHECK(error_of(missing).find("/materials/floor/materials/1") != std::string::npos);
  CHECK(error_of(missing).find("no material named \"nope\"") != std::string::npos);
  json loop = floor_scene({{"type", "mix"}, {"materials", {"matte", "other"}}});
  loop["materials"]["other"] = {{"type", "mix"}, {"materials", {"floor", "glossy"}}};
  CHECK(error_of(loop).find("refer to each other in a loop") != std::string::npos);
  json one = floor_scene({{"type", "mix"}, {"materials", {"matte"}}});
  CHECK(error_of(one).find("expected an array of two material names") != std::string::npos);
  json amount = floor_scene({{"type", "mix"}, {"materials", {"matte", "glossy"}}, {"amount", 1.5}});
  CHECK(error_of(amount).find("/materials/floor/amount") != std::string::npos);
  // Nested mixes load (a mix of a mix).
  json nested = floor_scene({{"type", "mix"}, {"materials", {"inner", "glossy"}}, {"amount", 0.5}});
  nested["materials"]["inner"] = {{"type", "mix"}, {"materials", {"matte", "black"}}, {"amount", 0.25}};
  CHECK(error_of(nested) == "no error");
}

TEST_CASE("pbrt mix renders as the same scene written in Rimu's JSON") {
  // cornell.pbrt and its hand-written JSON twin with the ball made of a 50/50 red/green mix.
  const std::filesystem::path pbrt_file = test::test_data("pbrt/cornell.pbrt");
  std::stringstream text;
  text << std::ifstream(pbrt_file).rdbuf();
  std::string pbrt = text.str();
  const std::string walls = "Include \"cornell_walls.pbrt\"";
  REQUIRE(pbrt.find(walls) != std::string::npos);
  pbrt.insert(pbrt.find(walls),
              "MakeNamedMaterial \"mixed\" \"string type\" \"mix\" \"string materials\" [ \"red\" \"green\" ] \"float amount\" 0.5\n");
  const std::string ball = "NamedMaterial \"white\"\n  Translate 0.45";
  REQUIRE(pbrt.find(ball) != std::string::npos);
  pbrt.replace(pbrt.find(ball), ball.size(), "NamedMaterial \"mixed\"\n  Translate 0.45");
  const PbrtImport imported = import_pbrt_text(pbrt, pbrt_file.string(), pbrt_file.parent_path(), test::library());
  CHECK(imported.ignored.empty());
  CHECK(imported.document["materials"]["mixed"] ==
        json({{"type", "mix"}, {"materials", {"red", "green"}}, {"amount", 0.5}}));
  const auto from_pbrt = load_scene(imported.document, pbrt_file.string(), pbrt_file.parent_path(), test::library());

  std::ifstream in(test::test_data("pbrt/cornell_equivalent.json"));
  json hand_written = json::parse(in);
  // The ball (the only sphere) is made of the mix.
  hand_written["materials"]["mixed"] = {{"type", "mix"}, {"materials", {"red", "green"}}, {"amount", 0.5}};
  for (json& shape : hand_written["shapes"])
    if (shape["type"] == "sphere") shape["material"] = "mixed";
  const auto from_json = load_scene(hand_written, "cornell_equivalent.json", pbrt_file.parent_path(), test::library());
  const std::vector<double> a = test::luminance_values(*test::render_xyz(*from_pbrt, 128, 1).film);
  const std::vector<double> b = test::luminance_values(*test::render_xyz(*from_json, 128, 2).film);
  for (double deviation : test::block_deviations(a, b)) CHECK(deviation <= test::kSigmas);

  // The comparison can fail: the ball all red.
  json red_ball = hand_written;
  red_ball["materials"]["mixed"]["amount"] = 0.0;
  const auto all_red = load_scene(red_ball, "red_ball.json", pbrt_file.parent_path(), test::library());
  const std::vector<double> c = test::luminance_values(*test::render_xyz(*all_red, 128, 3).film);
  CHECK(test::worst_deviation(test::block_deviations(a, c)) > test::kSigmas);
}
