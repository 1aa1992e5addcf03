// What the sweep of pbrt-v4-scenes (docs/pbrt-import.md, "Scenes of pbrt-v4-scenes") found the importer misread,
// each reduced to a few hand-written lines: a NamedMaterial before its MakeNamedMaterial, imagemap mappings, wrap.
#include <doctest/doctest.h>

#include <memory>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/image/alpha_mask.h"
#include "render/image/float_image_texture.h"
#include "test_image_files.h"
#include "transport/textures/spectral_texture_ops.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_scene_sweep_test {

const std::string kHeader = "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
const std::string kQuad =
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point3 P\" [0 0 1  1 0 1  1 1 1  0 1 1] "
    "\"point2 uv\" [0 0 1 0 1 1 0 1]\n";

// A spectral texture whose value at every wavelength is the u it is looked up at: shows which (s, t) a
// MappedSpectralTexture asks for.
class UTexture final : public SpectralTexture {
 public:
  SampledSpectrum evaluate(Vec2 uv, const SampledWavelengths&) const override { return SampledSpectrum(uv.x); }
};

TEST_CASE("pbrt NamedMaterial may come before its MakeNamedMaterial, as pbrt-v4 looks names up at the end") {
  // contemporary-bathroom names its lights' material "light" before Include "materials.pbrt" defines it.
  const PbrtImport imported = test::import_pbrt_test_text(
      kHeader + "AttributeBegin\nNamedMaterial \"late\"\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n" + kQuad +
      "AttributeEnd\nMakeNamedMaterial \"late\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.2 0.3 0.4]\n");
  const json& d = imported.document;
  REQUIRE(d["shapes"].size() == 1);
  CHECK(d["shapes"][0]["material"] == "late");
  CHECK(d["shapes"][0].contains("emission"));
  CHECK(d["materials"]["late"]["type"] == "diffuse");
  CHECK(imported.ignored.empty());
  CHECK_NOTHROW(load_scene(d, "t.pbrt", test::test_data("pbrt"), test::library()));

  // A name no MakeNamedMaterial ever defines is still an error, at the NamedMaterial that names it.
  CHECK_CONTAINS(test::pbrt_import_error(kHeader + "NamedMaterial \"nope\"\n" + kQuad +
                                         "MakeNamedMaterial \"other\" \"string type\" \"diffuse\"\n"),
                 "t.pbrt:5: NamedMaterial: no material named \"nope\"; defined: other");
  // What cannot be settled after the shape is written is refused with the reason, not misread: a late
  // "interface" material (its shapes are left out or index-matched) and a late boundary of a medium.
  CHECK_CONTAINS(test::pbrt_import_error(kHeader + "NamedMaterial \"gap\"\n" + kQuad +
                                         "MakeNamedMaterial \"gap\" \"string type\" \"interface\"\n"),
                 "t.pbrt:5: NamedMaterial: \"gap\" is an \"interface\" material defined after shapes use it");
  CHECK_CONTAINS(test::pbrt_import_error(kHeader + "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n"
                                                   "MediumInterface \"fog\" \"\"\nNamedMaterial \"glass\"\n" + kQuad +
                                         "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\"\n"),
                 "t.pbrt:8", "its material \"glass\" is defined after this shape, which begins the medium \"fog\"");
}

TEST_CASE("pbrt imagemap uscale, vscale, udelta, vdelta and mappings become the image texture's mapping") {
  test::ScratchFolder dir("pbrt_sweep_imagemap");
  const auto ppm = test::write_ppm("pbrt_sweep_imagemap", 2, 1, {0, 0, 0, 255, 255, 255});
  std::filesystem::copy_file(ppm, dir / "ramp.ppm", std::filesystem::copy_options::overwrite_existing);
  // villa's leaves (vscale −1) and bark (uscale 2, udelta −0.5); kroken's planar book covers and cylindrical cups,
  // the latter placed by the CTM of its Texture statement.
  const PbrtImport imported = import_pbrt_text(
      kHeader +
          "Texture \"leaf\" \"spectrum\" \"imagemap\" \"string filename\" \"ramp.ppm\" \"float uscale\" 1 \"float vscale\" -1 "
          "\"float udelta\" 0 \"float vdelta\" 0 \"string wrap\" \"repeat\" \"string mapping\" \"uv\"\n"
          "Texture \"bark\" \"float\" \"imagemap\" \"string filename\" \"ramp.ppm\" \"float uscale\" 2 \"float vscale\" -2 "
          "\"float udelta\" -0.5 \"float vdelta\" 0.5\n"
          "Texture \"cover\" \"spectrum\" \"imagemap\" \"string filename\" \"ramp.ppm\" \"string mapping\" \"planar\" "
          "\"vector3 v1\" [0 0.25 0] \"vector3 v2\" [-0.025 0 0] \"float udelta\" 0.55 \"float vdelta\" -0.2\n"
          "AttributeBegin\nTranslate 1 2 3\n"
          "Texture \"cup\" \"spectrum\" \"imagemap\" \"string filename\" \"ramp.ppm\" \"string mapping\" \"cylindrical\"\n"
          "AttributeEnd\n"
          "Texture \"plain\" \"spectrum\" \"imagemap\" \"string filename\" \"ramp.ppm\" \"string wrap\" \"clamp\"\n"
          "MakeNamedMaterial \"leaf\" \"string type\" \"diffuse\" \"texture reflectance\" \"leaf\"\n"
          "MakeNamedMaterial \"bark\" \"string type\" \"conductor\" \"texture roughness\" \"bark\" \"bool remaproughness\" false\n"
          "MakeNamedMaterial \"cover\" \"string type\" \"diffuse\" \"texture reflectance\" \"cover\"\n"
          "MakeNamedMaterial \"cup\" \"string type\" \"diffuse\" \"texture reflectance\" \"cup\"\n"
          "MakeNamedMaterial \"plain\" \"string type\" \"diffuse\" \"texture reflectance\" \"plain\"\n" + kQuad,
      "t.pbrt", dir.path, test::library());
  // Nothing listed but the wrap Rimu's images do not have (they repeat, as pbrt's default).
  REQUIRE(imported.ignored.size() == 1);
  CHECK(imported.ignored[0].what == "imagemap \"wrap\" \"clamp\" (Rimu's image textures repeat)");
  const json& m = imported.document["materials"];
  CHECK(m["leaf"]["reflectance"]["uv_scale"] == json({1.0, -1.0}));
  CHECK(m["leaf"]["reflectance"]["uv_offset"] == json({0.0, 0.0}));
  const json bark = m["bark"]["roughness"]["power"][0];
  CHECK(bark["uv_scale"] == json({2.0, -2.0}));
  CHECK(bark["uv_offset"] == json({-0.5, 0.5}));
  CHECK(m["cover"]["reflectance"]["mapping"] == "planar");
  CHECK(m["cover"]["reflectance"]["planar_axes"] == json({{0.0, 0.25, 0.0}, {-0.025, 0.0, 0.0}}));
  CHECK(m["cover"]["reflectance"]["uv_offset"] == json({0.55, -0.2}));
  CHECK(m["cup"]["reflectance"]["mapping"] == "cylindrical");
  CHECK(m["cup"]["reflectance"].contains("transform"));
  // Plain uv writes no mapping keys: documents of scenes without mappings are as before.
  CHECK_FALSE(m["plain"]["reflectance"].contains("uv_scale"));
  CHECK_FALSE(m["plain"]["reflectance"].contains("mapping"));
  // The loader takes the keys (an image texture refused them before).
  CHECK_NOTHROW(load_scene(imported.document, (dir.path / "t.pbrt").string(), dir.path, test::library()));
}

TEST_CASE("image textures read at their mapping's (s, t)") {
  // A 2×1 image, black left and white right: along u the bilinear value rises from 0 at the left texel's centre
  // (u = ¼) to 1 at the right one's (u = ¾).
  const auto ppm = test::write_ppm("mapped_image", 2, 1, {0, 0, 0, 255, 255, 255});
  auto values = std::make_shared<const AlphaMask>(AlphaMask::read(ppm, 0, false, false, false));
  const ImageFloatTexture plain(values, 1.0f, false);
  UvMapping doubled;
  doubled.su = 2.0f;
  doubled.du = -0.5f;
  const ImageFloatTexture mapped(values, 1.0f, false, TextureMapping(doubled));
  for (const float u : {0.3f, 0.45f, 0.6f}) {
    const MaterialContext c = MaterialContext::at_uv({u, 0.5f});
    const MaterialContext moved = MaterialContext::at_uv({2.0f * u - 0.5f, 0.5f});
    CHECK(mapped.evaluate(c) == doctest::Approx(plain.evaluate(moved)));
  }
  CHECK(plain.evaluate(MaterialContext::at_uv({0.375f, 0.5f})) == doctest::Approx(0.25f));

  // A spectral texture through a planar mapping reads s = ds + p·v₁ at the hit's world position.
  TextureMapping planar;
  planar.kind = TextureMapping::Kind::planar;
  planar.planar_s = {0.0f, 0.25f, 0.0f};
  planar.planar_offset = {0.55f, -0.2f};
  const MappedSpectralTexture cover(std::make_shared<UTexture>(), planar);
  MaterialContext hit = MaterialContext::at_uv({0.9f, 0.9f});
  hit.position = {3.0f, 2.0f, 1.0f};
  SampledWavelengths lambda = SampledWavelengths::sample_visible(0.5f);
  CHECK(cover.evaluate_at(hit, lambda)[0] == doctest::Approx(0.55f + 0.5f));
  // A mapping that overflows reads the texel at (0, 0) instead of indexing outside the image.
  UvMapping huge;
  huge.su = 3e38f;
  const ImageFloatTexture overflowing(values, 1.0f, false, TextureMapping(huge));
  CHECK(overflowing.evaluate(MaterialContext::at_uv({10.0f, 0.5f})) == doctest::Approx(plain.evaluate(MaterialContext::at_uv({0.0f, 0.5f}))));
  const MappedSpectralTexture far(std::make_shared<UTexture>(), TextureMapping(huge));
  CHECK(far.evaluate_at(MaterialContext::at_uv({10.0f, 0.5f}), lambda)[0] == 0.0f);
  CHECK(TextureMapping(doubled).is_identity_uv() == false);
  CHECK(TextureMapping().is_identity_uv());
}

TEST_CASE("pbrt shapes and instances under a singular transform are left out and listed, as pbrt-v4 renders them") {
  // transparent-machines' Cinema4D export scales hidden parts by 0 ("ConcatTransform [ -0 -0 0 0 ...]"); pbrt-v4
  // renders the scene (the flattened part has no volume), so Rimu must not refuse it.
  const PbrtImport imported = test::import_pbrt_test_text(
      kHeader + "ObjectBegin \"bolt\"\n" + kQuad + "ObjectEnd\n"
                "AttributeBegin\nConcatTransform [ -0 -0 0 0 0 1 0 0 -1.2246469e-16 0 -1 0 2637.5637 -70.63508 8.852083 1 ]\n" +
          kQuad + "ObjectInstance \"bolt\"\nAttributeEnd\n" + kQuad + "ObjectInstance \"bolt\"\n");
  const json& shapes = imported.document["shapes"];
  REQUIRE(shapes.size() == 2);  // the quad and the instance outside the singular block
  CHECK(shapes[1]["type"] == "instances");
  CHECK(shapes[1]["matrices"].size() == 1);
  REQUIRE(imported.ignored.size() == 2);
  CHECK(imported.ignored[0].what == "Shape \"trianglemesh\" under a singular transform (pbrt-v4 renders it flattened; left out)");
  CHECK(imported.ignored[0].first.line == 10);
  CHECK(imported.ignored[1].what == "ObjectInstance under a singular transform (pbrt-v4 renders it flattened; left out)");
  // Not finite is still an error (no picture can come of it).
  CHECK_CONTAINS(test::pbrt_import_error(kHeader + "Scale 1e300 1e300 1e300\nScale 1e300 1 1\n" + kQuad), "t.pbrt:7", "not finite");
}

TEST_CASE("pbrt area light with alpha 0: pbrt-v4's invisible emitter is listed as such, the light kept") {
  // kroken's lights.pbrt: an emissive sphere with "float alpha" 0. pbrt-v4 (DiffuseAreaLight's constructor) makes
  // it a light that emits but is never hit; checked with the pbrt-v4 binary: the floor under such a sphere is lit
  // (mean 0.73 against 3.43 with the sphere seen). Rimu keeps the light and says what differs.
  const std::string sun = "AttributeBegin\nAreaLightSource \"diffuse\" \"blackbody L\" 6500 \"float scale\" 50\n"
                          "Shape \"sphere\" \"float radius\" 0.5 \"float alpha\" ";
  const PbrtImport hidden = test::import_pbrt_test_text(kHeader + sun + "0\nAttributeEnd\n" + kQuad);
  REQUIRE(hidden.document["shapes"].size() == 2);
  CHECK(hidden.document["shapes"][0].contains("emission"));
  REQUIRE(hidden.ignored.size() == 1);
  CHECK(hidden.ignored[0].what == "\"alpha\" 0 on an area light (in pbrt-v4 an invisible emitter; Rimu's is seen: left solid)");
  const PbrtImport half = test::import_pbrt_test_text(kHeader + sun + "0.5\nAttributeEnd\n");
  REQUIRE(half.ignored.size() == 1);
  CHECK(half.ignored[0].what == "\"alpha\" on an area light (Rimu's lights are not cut out: left solid)");
}

}  // namespace pbrt_scene_sweep_test
