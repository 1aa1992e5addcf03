// pbrt-v4 media in the importer (src/render/scene/pbrt/pbrt_media.cpp, docs/pbrt-import.md "Media"):
// MakeNamedMedium "homogeneous" with its scale, the MediumInterface of shapes, the "interface" material as an
// index-matched boundary, what is listed (grids, Le, presets, a camera or scene-wide medium), bad input with
// file:line, and a pbrt scene with two media rendering the same image as the same scene written in Rimu's JSON.
#include <doctest/doctest.h>

#include <fstream>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "test_support.h"
#include "pbrt_test_support.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_media_test {

// A camera whose image-right agrees with Rimu's (pbrt's usual "Scale -1 1 1" idiom), so the world is not mirrored.
const std::string kCamera = "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\n";

PbrtImport import_text(const std::string& text) { return test::import_pbrt_test_text(text, "media.pbrt"); }

std::string error_of(const std::string& text) { return test::pbrt_import_error(text, "media.pbrt"); }

std::string ignored_list(const PbrtImport& imported) { return describe_ignored(imported.ignored); }

TEST_CASE("pbrt media: a homogeneous medium becomes a Rimu medium bounded by a copy of the shape's material") {
  const PbrtImport imported = import_text(
      kCamera +
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [0.5 0.5 0.5] \"spectrum sigma_s\" [300 2 900 2]\n"
      "  \"float scale\" 3 \"float g\" -0.4\n"
      "MakeNamedMedium \"thin\" \"string type\" \"homogeneous\"\n"
      "WorldBegin\n"
      "AttributeBegin\n MediumInterface \"fog\" \"\"\n Material \"interface\"\n Shape \"sphere\"\nAttributeEnd\n"
      "AttributeBegin\n MediumInterface \"fog\"\n Material \"diffuse\"\n Shape \"sphere\"\nAttributeEnd\n"
      "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\"\n"
      "AttributeBegin\n MediumInterface \"thin\" \"fog\"\n NamedMaterial \"glass\"\n Shape \"sphere\"\n Shape \"sphere\"\nAttributeEnd\n");
  CHECK_MESSAGE(imported.ignored.empty(), ignored_list(imported));
  const json& d = imported.document;
  REQUIRE(d["media"].size() == 2);
  // fog: sigma × scale; the interface sphere is index-matched. Its shape and material are named after the medium.
  const json& fog = d["media"]["fog"];
  CHECK(fog["type"] == "homogeneous");
  CHECK(fog["sigma_a"].get<double>() == doctest::Approx(1.5));
  CHECK(fog["sigma_s"].get<double>() == doctest::Approx(6.0));
  CHECK(fog["g"].get<double>() == doctest::Approx(-0.4));
  CHECK(fog["index_matched"] == true);
  CHECK(d["shapes"][0]["material"] == fog["boundary_material"]);
  // inside == outside: no medium begins at the diffuse sphere, which keeps its own material.
  CHECK(d["shapes"][1]["material"] != fog["boundary_material"]);
  CHECK(d["materials"].contains(d["shapes"][1]["material"].get<std::string>()));
  // thin: pbrt's defaults (sigma_a = sigma_s = 1), bounded by a copy of "glass" that both its spheres share.
  const json& thin = d["media"]["thin"];
  CHECK(thin["sigma_a"] == 1.0);
  CHECK(thin["sigma_s"] == 1.0);
  CHECK_FALSE(thin.contains("index_matched"));
  CHECK(d["shapes"][2]["material"] == thin["boundary_material"]);
  CHECK(d["shapes"][3]["material"] == thin["boundary_material"]);
  CHECK(d["materials"][thin["boundary_material"].get<std::string>()] == d["materials"]["glass"]);
  // The document loads: Rimu's loader accepts every key written.
  CHECK_NOTHROW(load_scene(d, "media.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt media: an unbounded RGB coefficient becomes a smooth spectrum of that colour's shape and size") {
  const PbrtImport imported = import_text(kCamera +
                                          "MakeNamedMedium \"red\" \"string type\" \"homogeneous\" \"rgb sigma_a\" [4 1 0.5]\n"
                                          "WorldBegin\nMediumInterface \"red\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n");
  const json& table = imported.document["media"]["red"]["sigma_a"];
  REQUIRE(table["wavelengths_nm"].size() == 471);  // 360-830 nm every 1 nm (pbrt's sigmoid fit)
  std::vector<double> v = table["values"].get<std::vector<double>>();
  const auto at = [&](int nm) { return v[size_t(nm - 360)]; };
  // pbrt's RGBUnboundedSpectrum: a reflectance-like shape of rgb / (2·max) scaled by 2·max = 8, so every value is
  // at most 8, and a red coefficient absorbs more at 650 nm than at 450 nm.
  for (double x : v) CHECK((x >= 0 && x <= 8.0 + 1e-9));
  CHECK(at(650) > 2.0 * at(450));
  CHECK_NOTHROW(load_scene(imported.document, "media.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt media: a named preset gives pbrt's measured coefficients (Jensen et al. 2001, Narasimhan et al. 2006)") {
  const PbrtImport imported = import_text(
      kCamera + "MakeNamedMedium \"k\" \"string type\" \"homogeneous\" \"string preset\" \"Ketchup\" \"float scale\" 10\n"
                "MakeNamedMedium \"s\" \"string type\" \"homogeneous\" \"string preset\" \"Spectralon\" \"rgb sigma_a\" [1 1 1]\n"
                "WorldBegin\nMediumInterface \"k\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n"
                "MediumInterface \"s\" \"\"\nShape \"sphere\"\n");
  // sigma_a given beside a preset is overridden (pbrt-v4 does the same) and listed.
  CHECK(ignored_list(imported).find("MakeNamedMedium \"sigma_a\" beside a \"preset\"") != std::string::npos);
  CHECK_MESSAGE(imported.ignored.size() == 1, ignored_list(imported));
  const json& ketchup = imported.document["media"]["k"];
  // Ketchup, per mm: σ'_s (0.18, 0.07, 0.03), σ_a (0.061, 0.97, 1.45), times "scale" 10: at most 2·max·10 per
  // channel shape, red absorbs least and scatters most.
  const auto at = [](const json& table, int nm) { return table["values"][size_t(nm - 360)].get<double>(); };  // 1 nm
  const json& a = ketchup["sigma_a"];
  CHECK(a["scale"].get<double>() == doctest::Approx(10.0));
  CHECK(at(a, 650) < 0.3 * at(a, 450));
  CHECK(at(ketchup["sigma_s"], 650) > 3.0 * at(ketchup["sigma_s"], 450));
  for (double v : a["values"].get<std::vector<double>>()) CHECK((v >= 0 && v <= 2.9 + 1e-9));
  // Spectralon absorbs nothing (σ_a = 0 in every channel: a grey constant 0).
  CHECK(imported.document["media"]["s"]["sigma_a"] == 0.0);
  CHECK_NOTHROW(load_scene(imported.document, "media.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt media: RGB grids, emission and unknown presets are listed, the camera's medium surrounds everything") {
  const PbrtImport imported = import_text(
      "MakeNamedMedium \"air\" \"string type\" \"homogeneous\" \"rgb Le\" [1 1 1] \"float Lescale\" 2 \"string preset\" \"Skin9\"\n"
      "MakeNamedMedium \"cloud\" \"string type\" \"rgbgrid\" \"rgb sigma_a\" [1 1 1]\n"
      "MediumInterface \"\" \"air\"\n" + kCamera +
      "WorldBegin\n"
      "MediumInterface \"cloud\" \"air\"\nMaterial \"interface\"\nShape \"sphere\"\n"
      "Material \"diffuse\"\nShape \"sphere\"\n"
      "MediumInterface \"\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n");
  const std::string list = ignored_list(imported);
  CHECK(list.find("MakeNamedMedium \"preset\" \"Skin9\" (not one of pbrt-v4's names") != std::string::npos);
  CHECK(list.find("MakeNamedMedium \"rgbgrid\" (not imported") != std::string::npos);
  CHECK(list.find("with the \"interface\" material and no medium inside it (left out) (2 times), first at media.pbrt:10") !=
        std::string::npos);
  CHECK_MESSAGE(imported.ignored.size() == 3, list);
  CHECK(imported.document["shapes"].size() == 1);  // the diffuse sphere; both interface spheres are left out
  // The camera's medium, which no shape has inside: a medium around everything that the camera starts in.
  const json& media = imported.document["media"];
  REQUIRE(media.size() == 1);
  CHECK(media["air"]["contains_camera"] == true);
  // "Le" × "Lescale", normalised by pbrt-v4 as a light's "L": the RGB's luminance (1) × 2 in pbrt's units, 72 983 nt
  // each (as an area light's), with pbrt's spectral shape for the RGB.
  CHECK(media["air"]["emission"]["luminance_nt"].get<double>() == doctest::Approx(2.0 * 72983.3).epsilon(1e-4));
  CHECK(media["air"]["emission"].contains("spectrum"));
  CHECK_FALSE(media["air"].contains("boundary_material"));
  const auto scene = load_scene(imported.document, "media.pbrt", test::test_data("pbrt"), test::library());
  CHECK(scene->camera_medium == 0);
}

TEST_CASE("pbrt media: a camera inside a bounded medium starts in it, vacuum inside glass in a medium is listed") {
  const PbrtImport imported = import_text(
      "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n"
      "MediumInterface \"\" \"fog\"\n" + kCamera +
      "WorldBegin\n"
      "AttributeBegin\nMediumInterface \"fog\" \"\"\nMaterial \"interface\"\nShape \"sphere\" \"float radius\" 10\nAttributeEnd\n"
      "MediumInterface \"\" \"fog\"\nMaterial \"dielectric\"\nShape \"sphere\"\n");
  CHECK(imported.document["media"]["fog"]["contains_camera"] == true);
  CHECK(imported.document["media"]["fog"].contains("boundary_material"));
  CHECK(ignored_list(imported).find("Shape \"sphere\": vacuum inside a transmitting shape that has a medium outside (in Rimu the "
                                    "outside medium continues inside it) (1 time), first at media.pbrt:14") != std::string::npos);
  CHECK(error_of("MediumInterface \"\" \"smog\"\n" + kCamera + "WorldBegin\n") ==
        "media.pbrt:4: Camera: the MediumInterface in effect names the medium \"smog\", which no MakeNamedMedium defines");
}

TEST_CASE("pbrt media: bad media input is an error at its file and line") {
  const std::string world = kCamera + "WorldBegin\n";
  CHECK(error_of(world + "MediumInterface \"nothing\"\nShape \"sphere\"") ==
        "media.pbrt:6: Shape \"sphere\": the MediumInterface at media.pbrt:5 names the medium \"nothing\", which no "
        "MakeNamedMedium before this shape defines");
  CHECK(error_of("MakeNamedMedium \"m\" \"rgb sigma_a\" [1 1 1]\n" + world) ==
        "media.pbrt:1: MakeNamedMedium \"m\": needs \"string type\"");
  CHECK(error_of("MakeNamedMedium \"m\" \"string type\" \"foggy\"\n" + world).find("media.pbrt:1: MakeNamedMedium \"m\" (foggy): unknown medium type") == 0);
  CHECK(error_of("MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n\n \"rgb sigma_s\" [1 -1 1]\n" + world) ==
        "media.pbrt:3: MakeNamedMedium \"rgb sigma_s\": RGB values must be >= 0");
  CHECK(error_of("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float scale\" -2\n" + world) ==
        "media.pbrt:1: MakeNamedMedium \"m\" (homogeneous): \"scale\" must be >= 0");
  CHECK(error_of("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float sigma_a\" 1\n" + world) ==
        "media.pbrt:1: MakeNamedMedium \"m\" (homogeneous): parameter \"sigma_a\" must be of type rgb or spectrum or blackbody, not float");
  CHECK(error_of("MakeNamedMedium \"m\" \"string type\" \"homogeneous\" \"float g\" 1\n" + world) ==
        "media.pbrt:1: MakeNamedMedium \"m\" (homogeneous): \"g\" must be in (-1, 1)");
  CHECK(error_of("MakeNamedMedium \"m\" \"string type\" \"homogeneous\"\nMakeNamedMedium \"m\" \"string type\" \"homogeneous\"\n" + world) ==
        "media.pbrt:2: MakeNamedMedium: \"m\" is already defined");
}

TEST_CASE("pbrt media: two media spheres render the same image as the same scene written in Rimu's JSON") {
  const std::filesystem::path pbrt_file = test::test_data("pbrt/media_spheres.pbrt");
  const PbrtImport imported = import_pbrt(pbrt_file, test::library());
  CHECK_MESSAGE(imported.ignored.empty(), describe_ignored(imported.ignored));
  const auto from_pbrt = load_scene(imported.document, pbrt_file.string(), pbrt_file.parent_path(), test::library());
  std::ifstream in(test::test_data("pbrt/media_spheres_equivalent.json"));
  const json hand_written = json::parse(in);
  const auto from_json = load_scene(hand_written, "media_spheres_equivalent.json", pbrt_file.parent_path(), test::library());
  for (double deviation : test::render_block_deviations(*from_pbrt, *from_json)) CHECK(deviation <= test::kSigmas);

  // The comparison can fail: the smoke without pbrt's "scale" 2 (half as dense) is caught.
  json thinner = hand_written;
  thinner["media"]["smoke"]["sigma_s"] = 3;
  thinner["media"]["smoke"]["sigma_a"]["values"] = {0.5, 2};
  const auto wrong = load_scene(thinner, "thinner.json", pbrt_file.parent_path(), test::library());
  CHECK(test::worst_deviation(test::render_block_deviations(*from_pbrt, *wrong)) > test::kSigmas);
}

TEST_CASE("pbrt media: a scene with media counts scattering in them towards max_depth, as pbrt-v4's volpath") {
  const std::string medium = "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n";
  const std::string sphere = "AttributeBegin\n MediumInterface \"fog\" \"\"\n Material \"interface\"\n Shape \"sphere\"\nAttributeEnd\n";
  const PbrtImport with = import_text(kCamera + "Integrator \"volpath\" \"integer maxdepth\" 3\n" + medium + "WorldBegin\n" + sphere);
  CHECK(with.document["integrator"]["max_depth"] == 3);
  CHECK(with.document["integrator"]["max_depth_includes_media"] == true);
  const PbrtImport without = import_text(kCamera + "Integrator \"volpath\" \"integer maxdepth\" 3\nWorldBegin\nShape \"sphere\"\n");
  CHECK_FALSE(without.document["integrator"].contains("max_depth_includes_media"));
}

TEST_CASE("pbrt subsurface: a dielectric around its own medium, whose walk does not count towards max_depth") {
  // sssdragon's material (pbrt-v4-scenes): a named measured medium per mm, times "scale", g = 0.
  const PbrtImport named = import_text(
      kCamera + "WorldBegin\nMakeNamedMaterial \"skin\" \"string type\" \"subsurface\" \"string name\" \"Skin1\"\n"
                "  \"float scale\" 50 \"float eta\" 1.5 \"float roughness\" 0.1\nNamedMaterial \"skin\"\nShape \"sphere\"\n");
  CHECK_MESSAGE(named.ignored.empty(), ignored_list(named));
  const json& d = named.document;
  CHECK(d["materials"]["skin"]["type"] == "dielectric");
  CHECK(d["materials"]["skin"]["ior"] == 1.5);
  CHECK(d["materials"]["skin"].contains("roughness"));
  CHECK(d["shapes"][0]["material"] == "skin");
  REQUIRE(d["media"].size() == 1);
  const json& skin = d["media"]["subsurface of skin"];
  CHECK(skin["boundary_material"] == "skin");
  CHECK(skin["counts_towards_max_depth"] == false);
  CHECK(skin["g"] == 0.0);
  // Skin1 per mm: σ_a (0.032, 0.17, 0.48), σ'_s (0.74, 0.88, 1.01): red absorbs least, both scaled by 50.
  const auto at = [](const json& table, int nm) { return table["values"][size_t(nm - 360)].get<double>(); };  // 1 nm
  CHECK(skin["sigma_a"]["scale"].get<double>() == doctest::Approx(50.0));
  CHECK(skin["sigma_s"]["scale"].get<double>() == doctest::Approx(50.0));
  CHECK(at(skin["sigma_a"], 650) < 0.3 * at(skin["sigma_a"], 450));
  CHECK(d["integrator"]["max_depth_includes_media"] == true);
  const auto scene = load_scene(d, "media.pbrt", test::test_data("pbrt"), test::library());
  REQUIRE(scene->media.size() == 1);
  CHECK_FALSE(scene->media[0].counts_towards_max_depth());

  // σ_a and σ_s given (unbounded RGB) with g; reflectance with a coloured mean free path (its shape and its largest
  // component × scale in metres); nothing given: pbrt-v4's defaults. Each a dielectric of pbrt's eta 1.33.
  const PbrtImport given = import_text(
      kCamera + "WorldBegin\n"
                "Material \"subsurface\" \"rgb sigma_a\" [0.1 0.2 0.3] \"rgb sigma_s\" [2 2 2] \"float g\" 0.3 \"float scale\" 4\nShape \"sphere\"\n"
                "Material \"subsurface\" \"rgb reflectance\" [0.8 0.5 0.3] \"rgb mfp\" [0.5 1 2] \"float scale\" 0.1\nShape \"sphere\"\n"
                "Material \"subsurface\"\nShape \"sphere\"\n");
  CHECK_MESSAGE(given.ignored.empty(), ignored_list(given));
  REQUIRE(given.document["media"].size() == 3);
  std::vector<json> media;
  for (const auto& [name, medium] : given.document["media"].items()) {
    CHECK(given.document["materials"][medium["boundary_material"].get<std::string>()]["ior"] == 1.33);
    media.push_back(medium);
  }
  std::sort(media.begin(), media.end(), [](const json& a, const json& b) { return a["boundary_material"] < b["boundary_material"]; });
  // Material names carry their line: 6, 8, 10.
  CHECK(media[0]["sigma_a"]["scale"].get<double>() == doctest::Approx(4.0));
  CHECK(media[0]["sigma_s"].get<double>() == doctest::Approx(8.0));
  CHECK(media[0]["g"].get<double>() == doctest::Approx(0.3));
  CHECK(media[1]["mean_free_path_scale_m"].get<double>() == doctest::Approx(0.2));
  CHECK(media[1].contains("albedo"));
  CHECK_FALSE(media[1].contains("sigma_a"));
  CHECK(media[2]["sigma_s"].is_object());  // (2.55, 3.21, 3.77): a coloured spectrum
  CHECK_NOTHROW(load_scene(given.document, "media.pbrt", test::test_data("pbrt"), test::library()));

  // What pbrt-v4 also refuses, and g beside a name (pbrt warns and uses 0).
  const std::string world = kCamera + "WorldBegin\n";
  CHECK(error_of(world + "Material \"subsurface\" \"rgb sigma_a\" [1 1 1]\n") ==
        "media.pbrt:5: Material \"subsurface\" (subsurface): give \"sigma_a\" and \"sigma_s\" together (pbrt-v4 refuses one without the other)");
  CHECK(error_of(world + "Material \"subsurface\" \"string name\" \"Skin9\"\n").find("\"name\" \"Skin9\" is not one of pbrt-v4's named media") !=
        std::string::npos);
  const PbrtImport g = import_text(world + "Material \"subsurface\" \"string name\" \"Apple\" \"float g\" 0.5\nShape \"sphere\"\n");
  CHECK(ignored_list(g).find("\"g\" beside \"name\"") != std::string::npos);
  const PbrtImport forward = import_text(world + "Material \"subsurface\" \"rgb sigma_a\" [1 1 1] \"rgb sigma_s\" [1 1 1] \"float g\" 0.995\nShape \"sphere\"\n");
  CHECK(ignored_list(forward).find("\"g\" beyond ±0.99 (clamped") != std::string::npos);

  // Light enters diffusely, as through pbrt-v4's BSSRDF exit lobe, so a smooth surface beside a light no path can
  // hit (a distant one) lets it in by next-event estimation: nothing to list, smooth or rough.
  const std::string sun = "LightSource \"distant\" \"point3 to\" [0 0 1]\n";
  for (const std::string roughness : {"", "\"float roughness\" 0.2"}) {
    const PbrtImport lit = import_text(world + sun + "Material \"subsurface\" " + roughness + "\nShape \"sphere\"\n");
    CHECK_MESSAGE(lit.ignored.empty(), ignored_list(lit));
    for (const auto& [name, material] : lit.document["materials"].items()) CHECK(material["diffuse_entry"] == true);
  }
  CHECK(d["materials"]["skin"]["diffuse_entry"] == true);

  // Without diffuse entry a smooth boundary leaves the walk unlit by the distant light: said at load. Not with it, nor
  // with a rough boundary (crossed by NEE), nor without such a light (only an environment).
  const auto unlit_warning = [](const json& document) {
    const auto scene = load_scene(document, "media.pbrt", test::test_data("pbrt"), test::library());
    for (const std::string& w : scene->warnings)
      if (w.find("is a smooth refracting dielectric") != std::string::npos) return true;
    return false;
  };
  json lit = import_text(world + sun + "Material \"subsurface\"\nShape \"sphere\"\n").document;
  CHECK_FALSE(unlit_warning(lit));
  const std::string material = lit["media"].begin().value()["boundary_material"];
  lit["materials"][material].erase("diffuse_entry");
  CHECK(unlit_warning(lit));
  lit["materials"][material]["roughness"] = 0.2;
  CHECK_FALSE(unlit_warning(lit));
  json sky_only = import_text(world + "LightSource \"infinite\"\nMaterial \"subsurface\"\nShape \"sphere\"\n").document;
  sky_only["materials"][sky_only["media"].begin().value()["boundary_material"].get<std::string>()].erase("diffuse_entry");
  CHECK_FALSE(unlit_warning(sky_only));
}

TEST_CASE("pbrt subsurface: a textured reflectance becomes a textured albedo of the medium, JSON refuses it on a grid") {
  // pbrt-v4's head: "texture reflectance" with an mfp. The texture stays a texture (TexturedAlbedo scales σ_s where a
  // path enters), no longer listed with a grey stand-in.
  const PbrtImport textured = import_text(
      kCamera + "WorldBegin\nTexture \"checks\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [0.9 0.6 0.4] \"rgb tex2\" [0.2 0.2 0.2]\n"
                "Material \"subsurface\" \"texture reflectance\" \"checks\" \"rgb mfp\" [1 0.5 0.25] \"float scale\" 0.01\n"
                "Shape \"sphere\"\n");
  CHECK_MESSAGE(textured.ignored.empty(), ignored_list(textured));
  REQUIRE(textured.document["media"].size() == 1);
  const json& medium = textured.document["media"].begin().value();
  CHECK(medium["albedo"].contains("checkerboard"));
  const auto scene = load_scene(textured.document, "media.pbrt", test::test_data("pbrt"), test::library());
  REQUIRE(scene->media.size() == 1);
  CHECK(scene->media[0].textured_albedo() != nullptr);
  // A uniform albedo is no texture.
  const PbrtImport uniform = import_text(kCamera + "WorldBegin\nMaterial \"subsurface\" \"rgb reflectance\" [0.9 0.6 0.4]\nShape \"sphere\"\n");
  CHECK(load_scene(uniform.document, "media.pbrt", test::test_data("pbrt"), test::library())->media[0].textured_albedo() == nullptr);
  // A grid medium has no single σ_t per path for the texture to keep: refused at its key.
  json grid = textured.document;
  json& g = grid["media"].begin().value();
  g["type"] = "grid";
  g["procedural"] = "cloud";
  g["resolution"] = {4, 4, 4};
  std::string error;
  try {
    load_scene(grid, "media.pbrt", test::test_data("pbrt"), test::library());
  } catch (const InputError& e) {
    error = e.what();
  }
  CHECK(error.find("a textured albedo needs a homogeneous medium") != std::string::npos);
}

TEST_CASE("pbrt media: a \"cloud\" medium imports as a noise cloud, with pbrt's defaults, box and placement") {
  // clouds.pbrt of mmp/pbrt-v4-scenes: the cloud inside a sphere of material "" (pbrt's old spelling of
  // "interface"), here with a box and a placement of its own.
  const PbrtImport imported = import_text(
      kCamera +
      "WorldBegin\n"
      "AttributeBegin\n Translate 1 2 3\n"
      " MakeNamedMedium \"c\" \"string type\" \"cloud\" \"spectrum sigma_s\" [200 10 900 10]\n"
      "   \"spectrum sigma_a\" [200 .01 900 .01] \"float density\" 2 \"point3 p0\" [1 0 -1] \"point3 p1\" [0 2 1]\n"
      "AttributeEnd\n"
      "MakeNamedMedium \"plain\" \"string type\" \"cloud\"\n"
      "AttributeBegin\n MediumInterface \"c\" \"\"\n Material \"\"\n Shape \"sphere\" \"float radius\" 1\nAttributeEnd\n"
      "AttributeBegin\n MediumInterface \"plain\" \"\"\n Material \"none\"\n Shape \"sphere\" \"float radius\" 1\nAttributeEnd\n");
  CHECK_MESSAGE(imported.ignored.empty(), ignored_list(imported));
  const json& media = imported.document["media"];
  REQUIRE(media.size() == 2);
  const json& c = media["c"];
  CHECK(c["type"] == "noise_cloud");
  CHECK(c["density_scale"].get<double>() == 2.0);
  CHECK(c["wispiness"].get<double>() == 1.0);
  CHECK(c["frequency"].get<double>() == 5.0);
  CHECK(c["bounds_min"] == json::array({0.0, 0.0, -1.0}));  // pbrt's Bounds3f(p0, p1): componentwise min and max
  CHECK(c["bounds_max"] == json::array({1.0, 2.0, 1.0}));
  CHECK(c.contains("transform"));  // the CTM at MakeNamedMedium
  CHECK(c["index_matched"] == true);  // Material "" is the interface: no surface, only the medium's boundary
  const json& plain = media["plain"];
  CHECK(plain["sigma_a"] == 1.0);
  CHECK(plain["sigma_s"] == 1.0);
  CHECK(plain["density_scale"].get<double>() == 1.0);
  CHECK(plain["bounds_min"] == json::array({0.0, 0.0, 0.0}));
  CHECK(plain["bounds_max"] == json::array({1.0, 1.0, 1.0}));
  CHECK_FALSE(plain.contains("transform"));
  CHECK(plain["index_matched"] == true);
  CHECK_NOTHROW(load_scene(imported.document, "media.pbrt", test::test_data("pbrt"), test::library()));
  // pbrt's cloud reads no "scale" (pbrt-v4 stops at it as unused): listed, not applied.
  const PbrtImport scaled = import_text(kCamera + "MakeNamedMedium \"c\" \"string type\" \"cloud\" \"float scale\" 3\nWorldBegin\n");
  CHECK(ignored_list(scaled).find("scale") != std::string::npos);
  CHECK(error_of(kCamera + "MakeNamedMedium \"c\" \"string type\" \"cloud\" \"float frequency\" -1\nWorldBegin\n")
            .find("media.pbrt:4: MakeNamedMedium \"c\" (cloud): \"frequency\" must be in [0, 1e6]") != std::string::npos);
}

}  // namespace pbrt_media_test
