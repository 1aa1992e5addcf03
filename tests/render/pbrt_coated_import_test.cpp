// pbrt-v4's coated materials (coateddiffuse, coatedconductor) → Rimu's coated_diffuse / coated_conductor: pbrt's
// parameter names and defaults, remapped roughness, nothing listed as ignored, and the JSON loader's errors.
#include <doctest/doctest.h>

#include <variant>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_coated_import_test {

const std::string kCamera = "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

PbrtImport import_text(const std::string& text) {
  return import_pbrt_text(text, "test.pbrt", test::test_data("pbrt"), test::library());
}

/// The BSDF alternative a loaded material gives at 550 nm.
size_t bsdf_kind(const Scene& scene, const std::string& name) {
  return test::material_named(scene, name)
      .bsdf(MaterialContext::at_uv({0.5f, 0.5f}), SampledWavelengths(Float4(550.0f), Float4(1.0f)))
      .variant()
      .index();
}

TEST_CASE("pbrt coateddiffuse: pbrt's defaults become an absorbing smooth coat, rough and scattering coats are kept") {
  const PbrtImport imported = import_text(
      kCamera +
      "MakeNamedMaterial \"plain\" \"string type\" \"coateddiffuse\" \"rgb reflectance\" [0.5 0.2 0.1]\n"
      "MakeNamedMaterial \"satin\" \"string type\" \"coateddiffuse\" \"float roughness\" 0.0625 \"float eta\" 1.4\n"
      "MakeNamedMaterial \"milky\" \"string type\" \"coateddiffuse\" \"float thickness\" 0.2 \"rgb albedo\" [0.8 0.8 0.8] "
      "\"float g\" 0.3 \"integer maxdepth\" 20 \"integer nsamples\" 2\n"
      "MakeNamedMaterial \"aniso\" \"string type\" \"coateddiffuse\" \"float uroughness\" 0.01 \"float vroughness\" 0.09 "
      "\"bool remaproughness\" false\n"
      "NamedMaterial \"plain\"\nShape \"sphere\"\n");
  const json& m = imported.document["materials"];
  // pbrt-v4's defaults: thickness 0.01, albedo 0, g 0, maxdepth 10, nsamples 1, eta 1.5.
  CHECK(m["plain"] == json({{"type", "coated_diffuse"}, {"reflectance", m["plain"]["reflectance"]}, {"thickness", 0.01}}));
  // remaproughness: α = √0.0625 = 0.25, Rimu's r = √α = 0.5.
  CHECK(m["satin"]["roughness"] == doctest::Approx(0.5));
  CHECK(m["satin"]["coat_ior"] == 1.4);
  CHECK(m["milky"]["thickness"] == 0.2);
  CHECK(m["milky"]["albedo"] == 0.8);  // a grey RGB is its constant
  CHECK(m["milky"]["g"] == 0.3);
  CHECK(m["milky"]["max_depth"] == 20);
  CHECK(m["milky"]["samples"] == 2);
  // Anisotropic coat: the mean (0.05 without remapping: α = 0.05, r = √0.05), listed.
  CHECK(m["aniso"]["roughness"] == doctest::Approx(std::sqrt(0.05)));
  REQUIRE(imported.ignored.size() == 1);
  CHECK(imported.ignored[0].what.find("anisotropic coat roughness") != std::string::npos);

  const auto scene = load_scene(imported.document, "test.pbrt", test::test_data("pbrt"), test::library());
  const size_t closed = Bsdf::Variant(CoatedDiffuseBsdf(Float4(0.5f), Float4(1.5f), Float4(0.09f))).index();
  const size_t walk = Bsdf::Variant(LayeredBsdf(1.5f, TrowbridgeReitz(0, 0), DiffuseBsdf(Float4(0.5f)), {}, {})).index();
  CHECK(bsdf_kind(*scene, "plain") == closed);
  CHECK(bsdf_kind(*scene, "satin") == walk);
  CHECK(bsdf_kind(*scene, "milky") == walk);
}

TEST_CASE("pbrt coatedconductor: interface.* and conductor.* parameters, copper by default") {
  const PbrtImport imported = import_text(
      kCamera +
      "MakeNamedMaterial \"copper\" \"string type\" \"coatedconductor\"\n"
      "MakeNamedMaterial \"gold\" \"string type\" \"coatedconductor\" \"spectrum conductor.eta\" \"metal-Au-eta\" "
      "\"spectrum conductor.k\" \"metal-Au-k\" \"float conductor.roughness\" 0.0625 \"float interface.roughness\" 0.0016 "
      "\"float interface.eta\" 1.6 \"float thickness\" 0.05\n"
      "MakeNamedMaterial \"brushed\" \"string type\" \"coatedconductor\" \"float conductor.uroughness\" 0.0625 "
      "\"float conductor.vroughness\" 0.0016 \"float conductor.eta\" 1.2 \"float conductor.k\" 3.5\n"
      "MakeNamedMaterial \"artist\" \"string type\" \"coatedconductor\" \"rgb reflectance\" [0.9 0.6 0.3]\n"
      "NamedMaterial \"gold\"\nShape \"sphere\"\n");
  const json& m = imported.document["materials"];
  CHECK(m["copper"] == json({{"type", "coated_conductor"}, {"metal", "pbrt-cu"}, {"thickness", 0.01}}));
  CHECK(m["gold"]["metal"] == "pbrt-au");
  CHECK(m["gold"]["conductor_roughness"] == doctest::Approx(0.5));
  CHECK(m["gold"]["roughness"] == doctest::Approx(0.2));  // √√0.0016
  CHECK(m["gold"]["coat_ior"] == 1.6);
  CHECK(m["gold"]["thickness"] == 0.05);
  CHECK(m["brushed"]["n"] == 1.2);
  CHECK(m["brushed"]["k"] == 3.5);
  CHECK(m["brushed"]["conductor_roughness_u"] == doctest::Approx(0.5));
  CHECK(m["brushed"]["conductor_roughness_v"] == doctest::Approx(0.2));
  // pbrt's artist-friendly reflectance: the coated conductor's own "reflectance" (it was listed, copper in its place).
  CHECK(m["artist"]["reflectance"] == test::pbrt_rgb_reflectance(0.9, 0.6, 0.3));
  CHECK(!m["artist"].contains("metal"));
  CHECK(imported.ignored.empty());

  const auto scene = load_scene(imported.document, "test.pbrt", test::test_data("pbrt"), test::library());
  const size_t walk = Bsdf::Variant(LayeredBsdf(1.5f, TrowbridgeReitz(0, 0), DiffuseBsdf(Float4(0.5f)), {}, {})).index();
  CHECK(bsdf_kind(*scene, "gold") == walk);
  CHECK(bsdf_kind(*scene, "brushed") == walk);
}

TEST_CASE("pbrt coated materials: textured coat and metal roughness become Rimu float textures, nothing listed") {
  // zero-day's materials texture "uroughness" of 22 coated materials; these were listed and made smooth.
  const PbrtImport imported = import_text(
      kCamera +
      "Texture \"rough\" \"float\" \"checkerboard\" \"float tex1\" 0 \"float tex2\" 0.0625 \"float uscale\" 4 "
      "\"float vscale\" 4\n"
      "MakeNamedMaterial \"varnish\" \"string type\" \"coateddiffuse\" \"texture roughness\" \"rough\"\n"
      "MakeNamedMaterial \"satin\" \"string type\" \"coateddiffuse\" \"texture uroughness\" \"rough\" "
      "\"texture vroughness\" \"rough\" \"bool remaproughness\" false\n"
      "MakeNamedMaterial \"metal\" \"string type\" \"coatedconductor\" \"texture interface.roughness\" \"rough\" "
      "\"texture conductor.roughness\" \"rough\"\n"
      "NamedMaterial \"varnish\"\nShape \"sphere\"\n");
  const json& m = imported.document["materials"];
  // pbrt's α = √roughness (remapped), Rimu's r = √α: the texture to the power ¼ (½ without remapping).
  REQUIRE(m["varnish"]["roughness"].is_object());
  CHECK(m["varnish"]["roughness"]["power"][1] == 0.25);
  CHECK(m["varnish"]["roughness"]["power"][0].contains("checkerboard"));
  CHECK(m["satin"]["roughness"]["power"][1] == 0.5);
  CHECK(m["metal"]["roughness"]["power"][1] == 0.25);
  CHECK(m["metal"]["conductor_roughness"]["power"][1] == 0.25);
  CHECK(imported.ignored.empty());

  // Loaded: the smooth squares get the closed form, the rough ones the walk.
  const auto scene = load_scene(imported.document, "test.pbrt", test::test_data("pbrt"), test::library());
  const size_t closed = Bsdf::Variant(CoatedDiffuseBsdf(Float4(0.5f), Float4(1.5f), Float4(0.09f))).index();
  const size_t walk = Bsdf::Variant(LayeredBsdf(1.5f, TrowbridgeReitz(0, 0), DiffuseBsdf(Float4(0.5f)), {}, {})).index();
  const Material& varnish = test::material_named(*scene, "varnish");
  int closed_count = 0, walk_count = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const MaterialContext at = MaterialContext::at_uv({(i + 0.5f) / 8, (j + 0.5f) / 8});
      const size_t kind = varnish.bsdf(at, SampledWavelengths(Float4(550.0f), Float4(1.0f))).variant().index();
      closed_count += kind == closed;
      walk_count += kind == walk;
    }
  CHECK(closed_count == 32);  // a 4×4 checkerboard sampled at 8×8 points: half of each
  CHECK(walk_count == 32);
}

TEST_CASE("scene format: coated materials refuse bad layer parameters with their JSON key") {
  const auto error_of = [](const json& material) -> std::string {
    json scene = {{"camera", {{"from", {0, 0, 5}}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 40}}},
                  {"materials", {{"m", material}}},
                  {"shapes", json::array({{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", 1}, {"material", "m"}}})}};
    try {
      load_scene(scene, "test.json", test::test_data("pbrt"), test::library());
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  CHECK(error_of({{"type", "coated_diffuse"}, {"reflectance", 0.5}, {"thickness", -1}}).find("thickness") != std::string::npos);
  CHECK(error_of({{"type", "coated_diffuse"}, {"reflectance", 0.5}, {"g", 1.5}}).find("g") != std::string::npos);
  CHECK(error_of({{"type", "coated_diffuse"}, {"reflectance", 0.5}, {"samples", 2.5}}).find("whole number") != std::string::npos);
  CHECK(error_of({{"type", "coated_conductor"}, {"metal", "gold"}, {"n", 1.0}}).find("either metal or n and k") != std::string::npos);
  CHECK(error_of({{"type", "coated_conductor"}, {"metal", "gold"}, {"conductor_roughness", 2}}).find("conductor_roughness") !=
        std::string::npos);
  CHECK(error_of({{"type", "coated_conductor"}, {"metal", "gold"}, {"reflectance", 0.5}}).find("reflectance") != std::string::npos);
  CHECK(error_of({{"type", "coated_conductor"}, {"metal", "gold"}, {"roughness", 0.2}, {"albedo", 0.5}, {"thickness", 0.1}}) ==
        "no error");
  // Textured roughness: a float texture, checked like any other.
  CHECK(error_of({{"type", "coated_diffuse"}, {"reflectance", 0.5}, {"roughness", {{"checkerboard", {0.0, 0.3}}, {"uv_scale", {4, 4}}}}}) ==
        "no error");
  CHECK(error_of({{"type", "coated_diffuse"}, {"reflectance", 0.5}, {"roughness", {{"bogus", 1}}}}).find("roughness") !=
        std::string::npos);
  CHECK(error_of({{"type", "coated_conductor"}, {"metal", "gold"}, {"conductor_roughness_u", {{"bogus", 1}}}}).find(
            "conductor_roughness_u") != std::string::npos);
}

}  // namespace pbrt_coated_import_test
