// The "hair" material of the scene format and pbrt-v4's Material "hair" on import: which absorption each input
// gives (σa, a colour through Chiang et al.'s inversion, melanin as pbrt-v4 upsamples it), the defaults, the
// errors, and the importer's mapping of pbrt's parameters.
#include <doctest/doctest.h>

#include <algorithm>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/scene/hair_absorption.h"

using namespace rimu;
using nlohmann::json;

namespace {

// A scene whose only shape wears `material` (a quad, so that the loader accepts it; nothing is rendered).
json scene_with(const json& material) {
  json scene = json::parse(R"({
    "camera": {"from": [0, 0, -4], "to": [0, 0, 0], "vertical_fov_deg": 20},
    "film": {"resolution": [4, 4]},
    "shapes": [{"type": "quad", "material": "fibre", "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]}]
  })");
  scene["materials"]["fibre"] = material;
  return scene;
}

const Material& fibre_of(const Scene& scene) { return test::material_named(scene, "fibre"); }

const SampledWavelengths kLambda(Float4(450.0f, 550.0f, 650.0f, 700.0f), Float4(1.0f / 470.0f));

// Σ Ap per lane for a fibre crossed at h = 0 by light perpendicular to it: what is left after absorption.
Float4 attenuation_of(const Material& material) {
  MaterialContext context;
  context.shading_normal = context.geometric_normal = {0.0f, 0.0f, 1.0f};
  context.dpdu = {1.0f, 0.0f, 0.0f};
  context.uv = {0.5f, 0.5f};
  const Bsdf bsdf = material.bsdf(context, kLambda);
  const auto ap = std::get<HairBsdf>(bsdf.variant()).attenuation({0.0f, 0.0f, 1.0f});
  return ap[0] + ap[1] + ap[2] + ap[3];
}

std::string load_error(const json& material) {
  try {
    test::scene_from_json(scene_with(material));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("hair material: pbrt-v4's defaults, and what σa, a colour and melanin make of the fibre") {
  const auto defaults = test::scene_from_json(scene_with({{"type", "hair"}}));
  const Material& brown = fibre_of(*defaults);
  const auto& hair = std::get<HairMaterial>(brown.variant());
  CHECK(hair.parameters().eta == 1.55f);
  CHECK(hair.parameters().beta_m == 0.3f);
  CHECK(hair.parameters().beta_n == 0.3f);
  CHECK(hair.parameters().alpha_deg == 2.0f);
  // The default is eumelanin 1.3, the same as given explicitly; it absorbs blue more than red (brown).
  const Float4 default_left = attenuation_of(brown);
  const auto explicit_melanin = test::scene_from_json(scene_with({{"type", "hair"}, {"eumelanin", 1.3}}));
  const Float4 melanin_left = attenuation_of(fibre_of(*explicit_melanin));
  for (int k = 0; k < 4; ++k) CHECK(default_left[k] == doctest::Approx(melanin_left[k]).epsilon(1e-6));
  CHECK(default_left[0] < default_left[2]);
  // pbrt-v4's eumelanin σa per unit concentration is the unbounded RGB (0.419, 0.697, 1.37): red absorbs least.
  const SpectrumPtr eumelanin = melanin_sigma_a(test::library(), 1.0, 0.0);
  CHECK(eumelanin->value(650) < eumelanin->value(550));
  CHECK(eumelanin->value(550) < eumelanin->value(450));
  CHECK(melanin_sigma_a(test::library(), 0.0, 0.0)->value(550) == 0.0);
  // σa = 0 leaves everything (Σ Ap = 1), and a colour of 1 means σa = 0 by Chiang et al.'s inversion.
  for (const json& white : {json{{"type", "hair"}, {"sigma_a", 0}}, json{{"type", "hair"}, {"reflectance", 1}}}) {
    const auto scene = test::scene_from_json(scene_with(white));
    const Float4 left = attenuation_of(fibre_of(*scene));
    for (int k = 0; k < 4; ++k) CHECK(left[k] == doctest::Approx(1.0).epsilon(1e-5));
  }
  // A darker colour absorbs more.
  const auto light = test::scene_from_json(scene_with({{"type", "hair"}, {"reflectance", 0.8}}));
  const auto dark = test::scene_from_json(scene_with({{"type", "hair"}, {"reflectance", 0.2}, {"beta_n", 0.5}}));
  CHECK(attenuation_of(fibre_of(*dark))[1] < attenuation_of(fibre_of(*light))[1]);
}

TEST_CASE("hair material: errors name the key and what was expected") {
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"sigma_a", 0.2}, {"reflectance", 0.5}}), "sigma_a",
                 "give one of sigma_a, reflectance or eumelanin/pheomelanin");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"reflectance", 0.5}, {"eumelanin", 1}}), "reflectance", "not several");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"beta_m", 0}}), "beta_m");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"beta_n", 2}}), "beta_n");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"eta", 0.8}}), "eta");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"alpha", 60}}), "alpha");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"eumelanin", -1}}), "eumelanin");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"sigma_a", {{"rgb", {0.1, 0.2, 0.3}}}}}), "sigma_a", "reflectance");
  CHECK_CONTAINS(load_error({{"type", "hair"}, {"roughness", 0.3}}), "roughness");
}

TEST_CASE("pbrt hair: Material \"hair\" becomes the scene format's hair, with pbrt-v4's parameter precedence") {
  using test::pbrt_t::import_text;
  const std::string camera = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  const PbrtImport imported = import_text(
      camera +
      "MakeNamedMaterial \"blond\" \"string type\" \"hair\" \"float eumelanin\" 0.3 \"float pheomelanin\" 0.1 \"float beta_m\" 0.25\n"
      "MakeNamedMaterial \"dyed\" \"string type\" \"hair\" \"rgb reflectance\" [0.8 0.2 0.1] \"float alpha\" 3 \"float eta\" 1.6\n"
      "MakeNamedMaterial \"absorbing\" \"string type\" \"hair\" \"rgb sigma_a\" [0.5 0.5 0.5] \"float beta_n\" 0.5\n"
      "Material \"hair\"\nShape \"sphere\"\n");
  const json& materials = imported.document["materials"];
  CHECK(materials["blond"] == json({{"type", "hair"}, {"eumelanin", 0.3}, {"pheomelanin", 0.1}, {"beta_m", 0.25}}));
  CHECK(materials["dyed"]["type"] == "hair");
  CHECK(materials["dyed"]["reflectance"] == test::pbrt_rgb_reflectance(0.8, 0.2, 0.1));
  CHECK(materials["dyed"]["alpha"] == 3.0);
  CHECK(materials["dyed"]["eta"] == doctest::Approx(1.6));
  CHECK(materials["absorbing"] == json({{"type", "hair"}, {"sigma_a", 0.5}, {"beta_n", 0.5}}));  // a grey is its constant
  // Nothing given: pbrt-v4's brown default, which the scene format's hair shares.
  const std::string anonymous = imported.document["shapes"][0]["material"];
  CHECK(materials[anonymous] == json({{"type", "hair"}}));
  CHECK(imported.ignored.empty());
  CHECK_NOTHROW(test::scene_from_json(imported.document));

  // pbrt-v4 uses sigma_a over reflectance over melanin, warning about the rest; β = 0 (a delta lobe) is raised
  // to the material's smallest.
  const PbrtImport both = import_text(camera +
                                      "Material \"hair\" \"rgb sigma_a\" [0.2 0.2 0.2] \"float eumelanin\" 2 \"float beta_m\" 0\n"
                                      "Shape \"sphere\"\n");
  const json& m = both.document["materials"][both.document["shapes"][0]["material"].get<std::string>()];
  CHECK(m == json({{"type", "hair"}, {"sigma_a", 0.2}, {"beta_m", 1e-3}}));
  CHECK(both.ignored.size() == 2);
  CHECK_NOTHROW(test::scene_from_json(both.document));
}
