// The pbrt-v4 importer (src/render/pbrt, docs/pbrt-import.md): tokens, every parameter type, the graphics state
// against hand-computed matrices, unit conventions, bad input with file:line, the report of what is ignored, and a
// pbrt scene rendering the same image as the same scene written by hand in Rimu's JSON.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/scene/pbrt/pbrt_parser.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "render/scene/pbrt/pbrt_tokenizer.h"
#include "render/film/spectral_response.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_import_test {

std::vector<PbrtStatement> statements_of(const std::string& text) {
  std::vector<PbrtStatement> out;
  parse_pbrt_text(text, "test.pbrt", test::test_data("pbrt"), [&](const PbrtStatement& s) { out.push_back(s); });
  return out;
}

// The InputError's location and message for a pbrt text that must fail.
std::string error_of(const std::string& text, bool convert = false, bool strict = false) {
  try {
    if (convert) {
      import_pbrt_text(text, "test.pbrt", test::test_data("pbrt"), test::library(), {strict, {}});
    } else {
      statements_of(text);
    }
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

PbrtImport import_text(const std::string& text) {
  return import_pbrt_text(text, "test.pbrt", test::test_data("pbrt"), test::library());
}

// A camera whose image-right agrees with Rimu's (pbrt's usual "Scale -1 1 1" idiom), so the world is not mirrored.
const std::string kUnmirroredCamera = "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\n";

void check_rows(const json& transform, const std::array<double, 12>& expected) {
  REQUIRE(transform.is_array());
  REQUIRE(transform.size() == 1);
  const json& rows = transform[0]["matrix"];
  REQUIRE(rows.size() == 12);
  for (size_t i = 0; i < 12; ++i) CHECK(rows[i].get<double>() == doctest::Approx(expected[i]).epsilon(1e-12));
}

double nits_per_unit_y() { return SpectralResponse::cie_xyz(test::library()).luminance_nits_per_unit_y(); }

TEST_CASE("pbrt tokens: comments, both quotes, escapes, brackets and line numbers") {
  const auto tokens = tokenize_pbrt("Shape # a comment \"not a string\"\n 'single' \"a\\\"b\" [1 2]\n-3.5e2", "t.pbrt");
  REQUIRE(tokens.size() == 8);
  CHECK(tokens[0].text == "Shape");
  CHECK(tokens[1].text == "single");
  CHECK(tokens[1].quoted);
  CHECK(tokens[1].line == 2);
  CHECK(tokens[2].text == "a\"b");
  CHECK(tokens[3].text == "[");
  CHECK(tokens[5].text == "2");
  CHECK(tokens[6].text == "]");
  CHECK(tokens[7].text == "-3.5e2");
  CHECK(tokens[7].line == 3);
  CHECK_THROWS_WITH_AS(tokenize_pbrt("a\n\"open", "t.pbrt"), doctest::Contains("t.pbrt:2"), InputError);
}

TEST_CASE("pbrt parameters: every type is read and checked") {
  const auto s = statements_of(
      "Shape \"x\" \"integer a\" [ 1 -2 ] \"float b\" 1.5 \"point2 c\" [1 2] \"vector2 d\" [3 4] \"point3 e\" [1 2 3]\n"
      "\"vector3 f\" [4 5 6] \"normal g\" [0 0 1] \"normal3 g3\" [0 1 0] \"point p\" [7 8 9] \"bool h\" true \"bool h2\" \"false\"\n"
      "\"string i\" 'file name' \"rgb j\" [0.1 0.2 0.3] \"spectrum k\" [400 0.5 700 0.6] \"spectrum l\" \"metal-Cu-eta\"\n"
      "\"blackbody m\" 3000 \"texture n\" \"wood\"");
  REQUIRE(s.size() == 1);
  CHECK(s[0].keyword == "Shape");
  CHECK(s[0].strings == std::vector<std::string>{"x"});
  REQUIRE(s[0].params.size() == 17);
  CHECK(s[0].find("a")->type == PbrtParamType::integer);
  CHECK(s[0].find("a")->numbers == std::vector<double>{1, -2});
  CHECK(s[0].find("b")->numbers == std::vector<double>{1.5});
  CHECK(s[0].find("c")->type == PbrtParamType::point2);
  CHECK(s[0].find("d")->type == PbrtParamType::vector2);
  CHECK(s[0].find("e")->type == PbrtParamType::point3);
  CHECK(s[0].find("f")->type == PbrtParamType::vector3);
  CHECK(s[0].find("g")->type == PbrtParamType::normal);
  CHECK(s[0].find("g3")->type == PbrtParamType::normal);
  CHECK(s[0].find("p")->type == PbrtParamType::point3);
  CHECK(s[0].find("h")->bools == std::vector<bool>{true});
  CHECK(s[0].find("h2")->bools == std::vector<bool>{false});
  CHECK(s[0].find("i")->strings == std::vector<std::string>{"file name"});
  CHECK(s[0].find("j")->numbers == std::vector<double>{0.1, 0.2, 0.3});
  CHECK(s[0].find("k")->numbers == std::vector<double>{400, 0.5, 700, 0.6});
  CHECK(s[0].find("l")->strings == std::vector<std::string>{"metal-Cu-eta"});
  CHECK(s[0].find("m")->type == PbrtParamType::blackbody);
  CHECK(s[0].find("n")->type == PbrtParamType::texture);
  CHECK(s[0].find("h2")->where.line == 2);
  CHECK(s[0].find("n")->where.line == 4);
}

TEST_CASE("pbrt parameters: badly typed values are InputErrors with file and line") {
  CHECK_CONTAINS(error_of("Shape \"s\"\n \"integer n\" [ 1.5 ]"), "test.pbrt:2", "expected an integer");
  CHECK_CONTAINS(error_of("Shape \"s\" \"rgb c\" [1 2]"), "expected 3 numbers");
  CHECK_CONTAINS(error_of("Shape \"s\" \"point3 c\" [1 2]"), "multiple of 3");
  CHECK_CONTAINS(error_of("Shape \"s\" \"spectrum c\" [400 1 300 2]"), "wavelengths must increase");
  CHECK_CONTAINS(error_of("Shape \"s\" \"spectrum c\" [400 1 500]"), "even count");
  CHECK_CONTAINS(error_of("Shape \"s\" \"floot r\" 1"), "unknown parameter type 'floot'");
  CHECK_CONTAINS(error_of("Shape \"s\" \"float r\" \"x\""), "expected a number");
  CHECK_CONTAINS(error_of("Shape \"s\" \"float\" 1"), "\"type name\"");
  CHECK_CONTAINS(error_of("Shape \"s\" \"bool b\" 1"), "true or false");
  CHECK_CONTAINS(error_of("Shape \"s\" \"string b\" 1"), "quoted string");
  CHECK_CONTAINS(error_of("Shape \"s\" \"blackbody b\" [1 2]"), "temperature");
  CHECK_CONTAINS(error_of("Shape \"s\"\n\"float r\" [1"), "test.pbrt:2", "file ends");
  CHECK_CONTAINS(error_of("Translate 1 2"), "3 numbers after Translate");
  CHECK_CONTAINS(error_of("\n\nShpe \"sphere\""), "test.pbrt:3: unknown statement 'Shpe'");
  CHECK_CONTAINS(error_of("Translate 0 nan 0"), "expected a finite number, found 'nan'");
  CHECK_CONTAINS(error_of("Translate 0 1e400 0"), "expected a number");
  CHECK_CONTAINS(error_of("Include \"no_such_file.pbrt\""), "test.pbrt:1: Include: ", "no_such_file.pbrt': cannot open the file: it does not exist");
  // Types are checked again where the parameter is used.
  CHECK_CONTAINS(error_of(kUnmirroredCamera + "Shape \"sphere\" \"integer radius\" 2", true), "test.pbrt:5", "\"radius\" must be of type float, not integer");
}

TEST_CASE("pbrt graphics state: transforms match hand-computed matrices") {
  SUBCASE("Translate, Rotate, Scale compose by post-multiplication") {
    const json d = import_text(kUnmirroredCamera + "Translate 1 2 3\nRotate 90 0 0 1\nScale 2 3 4\n"
                                                   "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]").document;
    // T(1,2,3) · Rz(90°) · S(2,3,4): Rz maps x → y and y → −x.
    check_rows(d["shapes"][0]["transform"], {0, -3, 0, 1, 2, 0, 0, 2, 0, 0, 4, 3});
  }
  SUBCASE("Transform lists columns; ConcatTransform post-multiplies; named coordinate systems restore") {
    const json d = import_text(kUnmirroredCamera +
                               "Transform [1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1]\nConcatTransform [2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1]\n"
                               "CoordinateSystem \"mine\"\nIdentity\nCoordSysTransform \"mine\"\n"
                               "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]").document;
    check_rows(d["shapes"][0]["transform"], {2, 0, 0, 5, 0, 2, 0, 6, 0, 0, 2, 7});
  }
  SUBCASE("Rotate about (1,1,1) by 120° cycles the axes; LookAt moves the eye to the origin") {
    json d = import_text(kUnmirroredCamera + "Rotate 120 1 1 1\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]").document;
    check_rows(d["shapes"][0]["transform"], {0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0});
    d = import_text(kUnmirroredCamera + "LookAt 1 2 3  1 2 4  0 1 0\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]").document;
    check_rows(d["shapes"][0]["transform"], {1, 0, 0, -1, 0, 1, 0, -2, 0, 0, 1, -3});
  }
  SUBCASE("AttributeBegin/End and TransformBegin/End restore the transform; ReverseOrientation rewinds") {
    const json d = import_text(kUnmirroredCamera +
                               "AttributeBegin\nTranslate 1 0 0\nReverseOrientation\nAttributeEnd\n"
                               "TransformBegin\nTranslate 0 1 0\nTransformEnd\n"
                               "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n"
                               "ReverseOrientation\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]").document;
    CHECK_FALSE(d["shapes"][0].contains("transform"));
    CHECK(d["shapes"][0]["indices"] == json({0, 1, 2}));
    CHECK(d["shapes"][1]["indices"] == json({0, 2, 1}));
  }
  SUBCASE("pbrt's camera frame: the world is mirrored so the image shows what pbrt shows") {
    // LookAt along +z with y up: pbrt's image-right is +x (up × forward), Rimu's is −x (forward × up).
    const json d = import_text("LookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\nWorldBegin\nTranslate 1 0 0\nShape \"sphere\"").document;
    CHECK(d["shapes"][0]["center"] == json({-1.0, 0.0, 0.0}));
    CHECK(d["camera"]["from"] == json({0.0, 0.0, 0.0}));
    CHECK(d["camera"]["to"] == json({0.0, 0.0, 1.0}));
  }
  SUBCASE("a mismatched AttributeEnd, a NaN reaching a transform are errors with the line; a singular one is listed") {
    CHECK_CONTAINS(error_of(kUnmirroredCamera + "AttributeBegin\nAttributeEnd\nAttributeEnd", true), "test.pbrt:7: AttributeEnd without a matching AttributeBegin");
    CHECK_CONTAINS(error_of(kUnmirroredCamera + "TransformBegin\nAttributeEnd", true), "test.pbrt:6: AttributeEnd closes a TransformBegin");
    // pbrt-v4 renders a shape under a singular CTM flattened: Rimu leaves it out and lists it (an error with --strict).
    const PbrtImport flattened = import_text(kUnmirroredCamera + "Scale 1 0 1\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]");
    CHECK(flattened.document["shapes"].empty());
    REQUIRE(flattened.ignored.size() == 1);
    CHECK(flattened.ignored[0].what == "Shape \"trianglemesh\" under a singular transform (pbrt-v4 renders it flattened; left out)");
    CHECK(flattened.ignored[0].first.line == 6);
    CHECK_CONTAINS(error_of(kUnmirroredCamera + "Scale 1 0 1\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]", true, true), "test.pbrt:6", "singular");
    CHECK_CONTAINS(error_of(kUnmirroredCamera + "Scale 1e300 1e300 1e300\nScale 1e300 1 1\nShape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]", true), "test.pbrt:7", "not finite");
  }
}

TEST_CASE("pbrt camera and film: fov spans the shorter axis, resolution, samples and depth") {
  const json portrait = import_text("Film \"rgb\" \"integer xresolution\" 100 \"integer yresolution\" 200\n"
                                    "Sampler \"halton\" \"integer pixelsamples\" 64\nIntegrator \"path\" \"integer maxdepth\" 7\n"
                                    "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\" \"float fov\" 60\nWorldBegin").document;
  // Portrait: pbrt's 60° spans the width; the height spans 2 atan(tan 30° · 200/100) = 98.2132°.
  CHECK(portrait["camera"]["vertical_fov_deg"].get<double>() == doctest::Approx(2 * std::atan(std::tan(M_PI / 6) * 2) * 180 / M_PI));
  CHECK(portrait["film"]["resolution"] == json({100, 200}));
  CHECK(portrait["integrator"]["spp"] == 64);
  CHECK(portrait["integrator"]["max_depth"] == 7);
  const json landscape = import_text("Film \"rgb\" \"integer xresolution\" 200 \"integer yresolution\" 100\n"
                                     "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\" \"float fov\" 60 \"float lensradius\" 0.1 \"float focaldistance\" 3\nWorldBegin").document;
  CHECK(landscape["camera"]["vertical_fov_deg"].get<double>() == doctest::Approx(60));
  CHECK(landscape["camera"]["type"] == "thin_lens");
  CHECK(landscape["camera"]["focus_distance"] == 3.0);
  CHECK(landscape["integrator"]["max_depth"] == 5);  // pbrt's default
  CHECK_CONTAINS(error_of("WorldBegin\nShape \"sphere\"", true), "no Camera");
}

TEST_CASE("pbrt bdpt is bidirectional, sppm vertex connection and merging, lightpath light-traces its caustics") {
  const std::string camera = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin";
  const PbrtImport bdpt = import_text("Integrator \"bdpt\" \"integer maxdepth\" 7\n" + camera);
  CHECK(bdpt.document["integrator"]["method"] == "bidirectional");
  CHECK(bdpt.document["integrator"]["caustics"] == "light_tracing");  // where bidirectional cannot run
  CHECK(bdpt.document["integrator"]["max_depth"] == 7);
  CHECK(bdpt.ignored.empty());
  const PbrtImport sppm = import_text("Integrator \"sppm\" \"float radius\" 0.01\n" + camera);
  CHECK(sppm.document["integrator"]["method"] == "vcm");
  CHECK(sppm.document["integrator"]["merge_radius"].get<double>() == doctest::Approx(0.01));
  CHECK(sppm.document["integrator"]["caustics"] == "light_tracing");  // where it cannot run
  CHECK(sppm.ignored.empty());
  CHECK(import_text("Integrator \"sppm\"\n" + camera).document["integrator"]["merge_radius"] == 1.0);  // pbrt's default
  const PbrtImport lightpath = import_text("Integrator \"lightpath\"\n" + camera);
  CHECK(lightpath.document["integrator"]["caustics"] == "light_tracing");
  REQUIRE(lightpath.ignored.size() == 1);
  CHECK(lightpath.ignored[0].what.find("caustics light-traced") != std::string::npos);
  for (const char* type : {"path", "volpath"}) {
    CAPTURE(type);
    const PbrtImport imported = import_text(std::string("Integrator \"") + type + "\"\n" + camera);
    CHECK_FALSE(imported.document["integrator"].contains("caustics"));
    CHECK_FALSE(imported.document["integrator"].contains("method"));
    CHECK(imported.ignored.empty());
  }
}

TEST_CASE("pbrt mlt is Metropolis light transport with pbrt's chains, sigma, large steps, bootstrap and mutations") {
  const std::string camera = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin";
  // The Sampler's count is pbrt's path count elsewhere; mlt renders its mutations per pixel instead, before or after.
  const PbrtImport mlt = import_text("Film \"rgb\" \"integer xresolution\" 200 \"integer yresolution\" 100\n"
                                     "Integrator \"mlt\" \"integer mutationsperpixel\" 512 \"integer chains\" 64 "
                                     "\"float sigma\" 0.02 \"float largestepprobability\" 0.4 "
                                     "\"integer bootstrapsamples\" 40000\nSampler \"zsobol\" \"integer pixelsamples\" 8\n" +
                                     camera);
  const json& integrator = mlt.document["integrator"];
  CHECK(integrator["method"] == "metropolis");
  CHECK(integrator["spp"] == 512);
  CHECK(integrator["metropolis"]["chains"] == 64);
  CHECK(integrator["metropolis"]["sigma"].get<double>() == doctest::Approx(0.02));
  CHECK(integrator["metropolis"]["large_step_probability"].get<double>() == doctest::Approx(0.4));
  CHECK(integrator["metropolis"]["bootstrap_per_pixel"].get<double>() == doctest::Approx(2.0));  // 40,000 over 200 × 100
  CHECK(mlt.ignored.empty());
  const json defaults = import_text("Integrator \"mlt\"\n" + camera).document["integrator"];
  CHECK(defaults["spp"] == 100);  // pbrt's defaults
  CHECK(defaults["metropolis"]["chains"] == 1000);
  CHECK(defaults["metropolis"]["bootstrap_per_pixel"].get<double>() == doctest::Approx(100000.0 / (1280.0 * 720.0)));
  CHECK_CONTAINS(error_of("Integrator \"mlt\" \"float sigma\" -1\n" + camera, true), "sigma");
  CHECK_CONTAINS(error_of("Integrator \"mlt\" \"integer mutationsperpixel\" 0\n" + camera, true), "mutationsperpixel");
}

TEST_CASE("pbrt pixel filters: box, gaussian and triangle with pbrt-v4's default radii, others listed") {
  const std::string camera = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\"\nWorldBegin";
  const PbrtImport triangle = import_text("PixelFilter \"triangle\"\n" + camera);
  CHECK(triangle.ignored.empty());
  CHECK(triangle.document["film"]["filter"] == json({{"type", "triangle"}, {"radius", 2.0}}));
  const json wide = import_text("PixelFilter \"triangle\" \"float xradius\" 1 \"float yradius\" 1\n" + camera).document;
  CHECK(wide["film"]["filter"]["radius"] == 1.0);
  CHECK(import_text("PixelFilter \"box\"\n" + camera).document["film"]["filter"]["radius"] == 0.5);
  const json gaussian = import_text("PixelFilter \"gaussian\"\n" + camera).document;
  CHECK(gaussian["film"]["filter"] == json({{"type", "gaussian"}, {"radius", 1.5}, {"sigma", 0.5}}));
  const PbrtImport mitchell = import_text("PixelFilter \"mitchell\"\n" + camera);
  REQUIRE(mitchell.ignored.size() == 1);
  CHECK(mitchell.ignored[0].what.find("mitchell") != std::string::npos);
}

TEST_CASE("pbrt lights: pbrt's luminance-normalised amounts become Rimu's photometric keys") {
  const double k = nits_per_unit_y();
  const PbrtImport imported = import_text(
      kUnmirroredCamera +
      "LightSource \"point\" \"blackbody I\" [3000] \"float scale\" 2 \"point3 from\" [0 1 0]\n"
      "LightSource \"point\" \"rgb I\" [1 0.5 0.25] \"float scale\" 3\n"
      "LightSource \"spot\" \"float coneangle\" 20 \"float conedeltaangle\" 8 \"float power\" 100 \"point3 from\" [0 2 0] \"point3 to\" [0 0 0]\n"
      "LightSource \"distant\" \"point3 from\" [0 1 0] \"point3 to\" [0 0 0] \"blackbody L\" [5500] \"float illuminance\" 1000\n"
      "LightSource \"infinite\" \"spectrum L\" \"stdillum-D50\" \"float scale\" 0.5\n"
      "AttributeBegin\nAreaLightSource \"diffuse\" \"float power\" 10 \"bool twosided\" true\n"
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0 2 0 0 2 1 0 0 1 0] \"integer indices\" [0 1 2 0 2 3]\nAttributeEnd\n"
      "Shape \"trianglemesh\" \"point3 P\" [-5 -1 -5  5 -1 -5  5 -1 5] \"integer indices\" [0 2 1]\n");
  CHECK(imported.ignored.empty());
  const json& lights = imported.document["lights"];
  REQUIRE(lights.size() == 5);
  CHECK(lights[0]["position"] == json({0.0, 1.0, 0.0}));
  CHECK(lights[0]["spectrum"] == json({{"blackbody", 3000.0}}));
  CHECK(lights[0]["luminous_intensity_cd"].get<double>() == doctest::Approx(2 * k));
  // An RGB light: pbrt's spectrum of the RGB at its own luminance (pbrt_rgb_spectra_test.cpp has the spectrum).
  CHECK(lights[1]["spectrum"].contains("wavelengths_nm"));
  CHECK(lights[1]["luminous_intensity_cd"].get<double>() ==
        doctest::Approx(3 * k * RgbColourSpace::named("srgb-linear").to_xyz({1.0, 0.5, 0.25}).y));
  CHECK(lights[2]["cone_angle_deg"] == 40.0);
  CHECK(lights[2]["falloff_start_deg"] == 24.0);  // 2·(20 − 8): pbrt-v4 names the delta "conedeltaangle"
  CHECK(lights[2]["direction"] == json({0.0, -2.0, 0.0}));
  CHECK(lights[2]["luminous_power_lm"].get<double>() == doctest::Approx(100 * k));
  CHECK(lights[3]["direction"] == json({0.0, 1.0, 0.0}));
  CHECK(lights[3]["illuminance_lx"].get<double>() == doctest::Approx(1000 * k));
  CHECK(lights[4]["type"] == "environment");
  CHECK(lights[4]["spectrum"] == json({{"illuminant", "D50"}}));
  CHECK(lights[4]["luminance_nt"].get<double>() == doctest::Approx(0.5 * k));
  // pbrt gives "power" to each triangle of a mesh (two here, of equal area).
  const json& panel = imported.document["shapes"][0];
  CHECK(panel["two_sided"] == true);
  CHECK(panel["emission"]["luminous_power_lm"].get<double>() == doctest::Approx(2 * 10 * k));
  // Rimu's own loader accepts the result.
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt materials: named metals and glasses, remapped roughness, plastics") {
  const json d = import_text(kUnmirroredCamera +
                             "MakeNamedMaterial \"gold\" \"string type\" \"conductor\" \"spectrum eta\" \"metal-Au-eta\" "
                             "\"spectrum k\" \"metal-Au-k\" \"float roughness\" 0.0625\n"
                             "MakeNamedMaterial \"raw\" \"string type\" \"conductor\" \"float roughness\" 0.25 \"bool remaproughness\" false\n"
                             "MakeNamedMaterial \"bk7\" \"string type\" \"dielectric\" \"spectrum eta\" \"glass-BK7\"\n"
                             "MakeNamedMaterial \"water\" \"string type\" \"dielectric\" \"float eta\" 1.33\n"
                             "MakeNamedMaterial \"plastic\" \"string type\" \"coateddiffuse\" \"rgb reflectance\" [0.5 0.2 0.1]\n")
                     .document;
  // remaproughness: α = √roughness, and Rimu's r = √α: 0.0625 → 0.5. Without it α = roughness: 0.25 → 0.5.
  CHECK(d["materials"]["gold"] == json({{"type", "conductor"}, {"metal", "pbrt-au"}, {"roughness", 0.5}}));
  CHECK(d["materials"]["raw"] == json({{"type", "conductor"}, {"metal", "pbrt-cu"}, {"roughness", 0.5}}));
  CHECK(d["materials"]["bk7"] == json({{"type", "dielectric"}, {"glass", "pbrt-bk7"}}));
  CHECK(d["materials"]["water"] == json({{"type", "dielectric"}, {"ior", 1.33}}));
  CHECK(d["materials"]["plastic"]["type"] == "coated_diffuse");
  CHECK_CONTAINS(error_of(kUnmirroredCamera + "NamedMaterial \"nope\"", true), "test.pbrt:5: NamedMaterial: no material named \"nope\"");
}

TEST_CASE("pbrt thindielectric: a thin sheet with the dielectric's eta, not listed as ignored") {
  const PbrtImport imported = import_text(kUnmirroredCamera +
                                          "MakeNamedMaterial \"pane\" \"string type\" \"thindielectric\" \"spectrum eta\" \"glass-BK7\"\n"
                                          "MakeNamedMaterial \"film\" \"string type\" \"thindielectric\" \"float eta\" 1.33\n"
                                          "Material \"thindielectric\"\nShape \"sphere\"\n");
  const json& d = imported.document;
  CHECK(d["materials"]["pane"] == json({{"type", "thin_dielectric"}, {"glass", "pbrt-bk7"}}));
  CHECK(d["materials"]["film"] == json({{"type", "thin_dielectric"}, {"ior", 1.33}}));
  CHECK(d["materials"][d["shapes"][0]["material"].get<std::string>()] == json({{"type", "thin_dielectric"}, {"ior", 1.5}}));
  CHECK(imported.ignored.empty());
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt diffusetransmission: reflectance, transmittance and scale, with pbrt's defaults") {
  const PbrtImport imported = import_text(kUnmirroredCamera +
                                          "MakeNamedMaterial \"paper\" \"string type\" \"diffusetransmission\" \"rgb transmittance\" [0.5 0.5 0.5] \"float scale\" 1.5\n"
                                          "Material \"diffusetransmission\"\nShape \"sphere\"\n");
  const json& d = imported.document;
  const json& paper = d["materials"]["paper"];
  CHECK(paper["type"] == "diffuse_transmission");
  CHECK(paper["reflectance"] == 0.25);
  CHECK(paper["scale"] == 1.5);
  CHECK(paper["transmittance"] == 0.5);  // a grey RGB is its constant
  CHECK(d["materials"][d["shapes"][0]["material"].get<std::string>()] ==
        json({{"type", "diffuse_transmission"}, {"reflectance", 0.25}, {"transmittance", 0.25}}));
  CHECK(imported.ignored.empty());
  CHECK_NOTHROW(load_scene(imported.document, "test.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt mix: Rimu's stochastic mix of the two named materials, amount clamped to [0, 1]") {
  const std::string defs = kUnmirroredCamera +
                           "MakeNamedMaterial \"red\" \"string type\" \"diffuse\" \"float reflectance\" 0.2\n"
                           "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\"\n";
  const PbrtImport imported = import_text(defs +
                                          "MakeNamedMaterial \"mostly glass\" \"string type\" \"mix\" \"string materials\" [\"red\" \"glass\"] \"float amount\" 0.7\n"
                                          "MakeNamedMaterial \"all glass\" \"string type\" \"mix\" \"string materials\" [\"red\" \"glass\"] \"float amount\" 3\n"
                                          "MakeNamedMaterial \"half\" \"string type\" \"mix\" \"string materials\" [\"red\" \"glass\"]\n");
  const json& d = imported.document;
  CHECK(d["materials"]["mostly glass"] == json({{"type", "mix"}, {"materials", {"red", "glass"}}, {"amount", 0.7}}));
  CHECK(d["materials"]["all glass"]["amount"] == 1.0);
  CHECK(d["materials"]["half"]["amount"] == 0.5);  // pbrt-v4's default
  CHECK(imported.ignored.empty());
  CHECK_NOTHROW(load_scene(d, "test.pbrt", test::test_data("pbrt"), test::library()));
  CHECK_CONTAINS(error_of(defs + "MakeNamedMaterial \"m\" \"string type\" \"mix\" \"string materials\" [\"red\" \"nope\"] \"float amount\" 1", true),
                 "test.pbrt:7", "no material named \"nope\"");
}

TEST_CASE("pbrt meshes: PLY files by path, missing ones are errors with the line") {
  const json d = import_text(kUnmirroredCamera + "Shape \"plymesh\" \"string filename\" \"quad.ply\"").document;
  CHECK(d["shapes"][0]["type"] == "mesh");
  CHECK(d["shapes"][0]["file"] == "quad.ply");
  CHECK_CONTAINS(error_of(kUnmirroredCamera + "\nShape \"plymesh\" \"string filename\" \"no_such.ply\"", true), "test.pbrt:6", "cannot find the PLY file");
  // An emissive PLY stays a file; its emitting side follows pbrt's rule, which the loader applies ("front").
  const json e = import_text(kUnmirroredCamera + "AreaLightSource \"diffuse\"\nShape \"plymesh\" \"string filename\" \"quad.ply\"").document;
  CHECK(e["shapes"][0]["type"] == "mesh");
  CHECK(e["shapes"][0]["front"] == "pbrt");
  CHECK(e["shapes"][0]["reversed"] == false);
}

TEST_CASE("pbrt meshes: a PLY whose sides matter stays a file and renders as the same mesh written inline") {
  // Emissive, ReverseOrientation'd and medium-bounding PLY meshes used to be written inline (triangle by triangle)
  // so that their sides could follow pbrt's rule; the loader now applies the rule to the file (TriangleMesh::
  // turn_to_pbrt_front). The same quad as a "trianglemesh" (still inline) must give the same image, bit for bit.
  const std::string quad_inline =
      "Shape \"trianglemesh\" \"point3 P\" [0 0 0  1 0 0  1 1 0  0 1 0] \"integer indices\" [0 1 2  0 2 3]\n";
  const std::string quad_file = "Shape \"plymesh\" \"string filename\" \"quad.ply\"\n";
  const std::string camera = "LookAt 0.5 0.5 2  0.5 0.5 0  0 1 0\nCamera \"perspective\" \"float fov\" 60\n"
                             "Film \"rgb\" \"integer xresolution\" 12 \"integer yresolution\" 12\nWorldBegin\n"
                             "LightSource \"infinite\" \"rgb L\" [0.3 0.3 0.3]\n";
  for (const std::string& setup :
       {std::string("AreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\n"),
        std::string("ReverseOrientation\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\n"),
        std::string("ReverseOrientation\nMaterial \"diffuse\"\n"),
        std::string("Scale 1 -1 1\nAreaLightSource \"diffuse\" \"rgb L\" [2 2 2] \"bool twosided\" false\n")}) {
    CAPTURE(setup);
    const auto render = [&](const std::string& shape) {
      const PbrtImport imported = import_text(camera + "AttributeBegin\n" + setup + shape + "AttributeEnd\n");
      const auto scene = load_scene(imported.document, "test.pbrt", test::test_data("pbrt"), test::library());
      return test::luminance_values(*test::render_xyz(*scene, 4, 1).film);
    };
    const std::vector<double> from_file = render(quad_file), inline_quad = render(quad_inline);
    CHECK(from_file == inline_quad);
    CHECK(*std::max_element(from_file.begin(), from_file.end()) > 0.0);
  }
}

TEST_CASE("pbrt: what is not imported is listed once with a count and the first line, --strict refuses it") {
  const std::filesystem::path file = test::test_data("pbrt/unsupported.pbrt");
  const PbrtImport imported = import_pbrt(file, test::library());
  const std::string report = describe_ignored(imported.ignored);
  CHECK_CONTAINS(report, "ignored: Material \"fourier\" (pbrt-v3's tabulated BSDF, which pbrt-v4 no longer reads; a grey diffuse of reflectance 0.5 stands in) (2 times), first at " +
                             file.string() + ":7\n");
  CHECK_CONTAINS(report, "ignored: parameter \"vector3 S\" of Shape \"trianglemesh\" (1 time), first at " + file.string() + ":10");
  CHECK(imported.ignored.size() == 2);  // line 9's partial sphere is imported (a mesh)
  CHECK_THROWS_WITH_AS(import_pbrt(file, test::library(), {true, {}}),
                       doctest::Contains("unsupported.pbrt:7: not supported (--strict): Material \"fourier\""), InputError);
}

TEST_CASE("pbrt Cornell box renders the same image as the same scene written in Rimu's JSON") {
  const std::filesystem::path pbrt_file = test::test_data("pbrt/cornell.pbrt");
  const PbrtImport imported = import_pbrt(pbrt_file, test::library());
  CHECK(imported.ignored.empty());
  const auto from_pbrt = load_scene(imported.document, pbrt_file.string(), pbrt_file.parent_path(), test::library());
  std::ifstream in(test::test_data("pbrt/cornell_equivalent.json"));
  const json hand_written = json::parse(in);
  const auto from_json = load_scene(hand_written, "cornell_equivalent.json", pbrt_file.parent_path(), test::library());
  REQUIRE(from_pbrt->settings.width == 32);
  REQUIRE(from_pbrt->settings.height == 32);

  // 8×8 blocks: the mean difference of the two renders (different seeds) against its standard error.
  for (double deviation : test::render_block_deviations(*from_pbrt, *from_json)) CHECK(deviation <= test::kSigmas);

  // The comparison can fail: the same JSON with the walls' colours swapped (pbrt's image mirrored) is caught.
  json swapped = hand_written;
  std::swap(swapped["materials"]["red"], swapped["materials"]["green"]);
  const auto mirrored = load_scene(swapped, "swapped.json", pbrt_file.parent_path(), test::library());
  CHECK(test::worst_deviation(test::render_block_deviations(*from_pbrt, *mirrored)) > test::kSigmas);
}

TEST_CASE("pbrt loopsubdiv: subdivided to \"levels\" with limit normals, meshes Loop's rules refuse are listed") {
  const PbrtImport imported = import_text(kUnmirroredCamera + "Shape \"loopsubdiv\" \"integer levels\" 2 \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]");
  CHECK(imported.ignored.empty());
  const json& mesh = imported.document["shapes"][0];
  CHECK(mesh["type"] == "triangles");
  CHECK(mesh["indices"].size() == 3 * 16);    // 4^2 triangles
  CHECK(mesh["positions"].size() == 15);      // a triangle's level-2 refinement
  CHECK(mesh["normals"].size() == 15);
  // pbrt's default is 3 levels.
  const PbrtImport by_default = import_text(kUnmirroredCamera + "Shape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]");
  CHECK(by_default.document["shapes"][0]["indices"].size() == 3 * 64);
  // Three triangles on one edge: the control mesh stands in, listed with the reason.
  const PbrtImport fin = import_text(kUnmirroredCamera + "Shape \"loopsubdiv\" \"point3 P\" [0 0 0 1 0 0 0 1 0 0 -1 0 0 0 1]\n"
                                                         "  \"integer indices\" [0 1 2 1 0 3 0 1 4]");
  CHECK(fin.document["shapes"][0]["indices"].size() == 9);
  REQUIRE(fin.ignored.size() == 1);
  CHECK_CONTAINS(fin.ignored[0].what, "Shape \"loopsubdiv\" that Loop's rules do not apply to, not subdivided: the edge 0-1 belongs to more than two triangles");
  CHECK_CONTAINS(error_of(kUnmirroredCamera + "Shape \"loopsubdiv\" \"integer levels\" 11 \"point3 P\" [0 0 0 1 0 0 0 1 0]", true),
                 "test.pbrt:5: Shape \"loopsubdiv\": \"levels\" must be 0-10, not 11");
}

TEST_CASE("pbrt interface material: without a medium inside, its shapes are left out and listed") {
  const PbrtImport imported = import_text(kUnmirroredCamera + "Material \"interface\"\nShape \"sphere\"\nMaterial \"diffuse\"\nShape \"sphere\"");
  CHECK(imported.document["shapes"].size() == 1);
  REQUIRE(imported.ignored.size() == 1);
  CHECK(imported.ignored[0].what == "Shape \"sphere\" with the \"interface\" material and no medium inside it (left out)");
  CHECK(imported.ignored[0].first.line == 6);
}

TEST_CASE("pbrt --strict: an unused parameter is an error at its line") {
  CHECK_CONTAINS(error_of(kUnmirroredCamera + "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\n  \"vector3 S\" [1 0 0 1 0 0 1 0 0]", true, true),
                 "test.pbrt:6: not supported (--strict): parameter \"vector3 S\" of Shape \"trianglemesh\"");
}

TEST_CASE("pbrt ColorSpace, Attribute defaults, disks and imagemap textures") {
  const PbrtImport imported = import_text(
      kUnmirroredCamera +
      "ColorSpace \"rec2020\"\n"
      "Texture \"grid\" \"spectrum\" \"imagemap\" \"string filename\" \"../../../data/scenes/textured/colour_bars.png\"\n"
      "  \"string encoding\" \"linear\"\n"
      "Material \"diffuse\" \"rgb reflectance\" [0.2 0.3 0.4]\n"
      "Attribute \"shape\" \"float radius\" 2\n"
      "Shape \"sphere\"\n"
      "Material \"diffuse\" \"texture reflectance\" \"grid\"\n"
      "Shape \"disk\" \"float radius\" 1 \"float innerradius\" 0.5 \"float height\" 0.25\n");
  CHECK(imported.ignored.empty());
  const json& d = imported.document;
  CHECK(d["shapes"][0]["radius"] == 2.0);  // from the Attribute
  const json& first = d["materials"][d["shapes"][0]["material"].get<std::string>()];
  CHECK(first["reflectance"].contains("wavelengths_nm"));  // fitted in rec2020 (pbrt_rgb_spectra_test.cpp)
  const json& disk = d["shapes"][1];
  CHECK(d["materials"][disk["material"].get<std::string>()]["reflectance"] == json({{"texture", "../../../data/scenes/textured/colour_bars.png"}, {"encoding", "linear"}}));
  // An annulus of 96 segments: two triangles each, all at z = 0.25, facing +z, between radii 0.5 and 1.
  REQUIRE(disk["indices"].size() == 96 * 6);
  double area = 0.0;
  for (size_t t = 0; t < disk["indices"].size(); t += 3) {
    const auto p = [&](size_t k) { return disk["positions"][disk["indices"][t + k].get<size_t>()].get<std::array<double, 3>>(); };
    const auto a = p(0), b = p(1), c = p(2);
    const double z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    CHECK(z > 0);
    CHECK(a[2] == 0.25);
    area += 0.5 * z;
  }
  // The inscribed 96-gon annulus: (n/2) sin(2π/n) (R² − r²), 0.07 % below π (R² − r²).
  CHECK(area == doctest::Approx(48 * std::sin(2 * M_PI / 96) * (1 - 0.25)).epsilon(1e-9));
  CHECK_NOTHROW(load_scene(d, "test.pbrt", test::test_data("pbrt"), test::library()));
}

TEST_CASE("pbrt: a problem inside a file or value the pbrt scene names is reported at the pbrt line that names it") {
  // A truncated PLY: the loader's error names the PLY's line and the document's key; moved to the Shape statement.
  const std::filesystem::path file = test::test_data("pbrt/bad_truncated_ply.pbrt");
  const PbrtImport imported = import_pbrt(file, test::library());
  std::string moved = "no error";
  try {
    load_scene(imported.document, file.string(), file.parent_path(), test::library());
  } catch (const InputError& e) {
    const std::optional<InputError> at_pbrt = at_pbrt_origin(e, imported.origins);
    REQUIRE(at_pbrt);
    moved = at_pbrt->what();
  }
  CHECK_CONTAINS(moved, file.string() + ":4: Shape \"plymesh\": ", "truncated.ply:13: vertex 2: the file ends inside this record",
                 "(the converted scene's /shapes/0/file)");
  // A value Rimu refuses that pbrt accepted (a reflectance above 1) is reported at its Material statement.
  const PbrtImport bright = import_text(kUnmirroredCamera + "\nMaterial \"diffuse\" \"spectrum reflectance\" [400 0.5 700 1.5]\nShape \"sphere\"");
  try {
    load_scene(bright.document, "test.pbrt", test::test_data("pbrt"), test::library());
    FAIL("a reflectance of 1.5 loaded");
  } catch (const InputError& e) {
    const std::optional<InputError> at_pbrt = at_pbrt_origin(e, bright.origins);
    REQUIRE(at_pbrt);
    CHECK_CONTAINS(at_pbrt->what(), "test.pbrt:6: Material \"diffuse\": ", "a reflectance cannot exceed 1");
  }
  // Pointers match whole steps only: an error under /shapes/10 is not /shapes/1's.
  const std::vector<PbrtOrigin> origins = {{"/shapes/1", {"a.pbrt", 3, ""}, "Shape \"sphere\"", {}},
                                           {"/shapes/10", {"a.pbrt", 30, ""}, "Shape \"disk\"", {}}};
  const std::optional<InputError> tenth = at_pbrt_origin(InputError({"a.pbrt", 0, "/shapes/10/radius"}, "too small"), origins);
  REQUIRE(tenth);
  CHECK(std::string(tenth->what()) == "a.pbrt:30: Shape \"disk\": too small (the converted scene's /shapes/10/radius)");
  CHECK_FALSE(at_pbrt_origin(InputError({"a.pbrt", 0, "/shapes/2"}, "x"), origins));
  CHECK_FALSE(at_pbrt_origin(InputError({"a.pbrt", 0, "/film/resolution"}, "x"), origins));
}

}  // namespace pbrt_import_test
