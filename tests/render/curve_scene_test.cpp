// The "curves" shape of the JSON format, pbrt's Shape "curve" imported to it, and a fibre rendered: a flat diffuse
// fibre in a uniform environment reflects exactly albedo × radiance (no ray stops on the fibre it leaves).
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/scene/embree_scene.h"

using namespace rimu;
using namespace rimu::test;
using nlohmann::json;

namespace {

// A straight fibre along x (2 m, 2 cm wide) in a uniform environment of radiance 1, seen from +z; `curves` replaces
// keys of its shape (null removes one).
json fibre_scene(const json& curves) {
  json scene = json::parse(R"({
    "camera": {"from": [0, 0, 3], "to": [0, 0, 0]},
    "film": {"resolution": [8, 8], "filter": {"type": "box"}},
    "integrator": {"max_depth": 16},
    "materials": {"fibre": {"type": "diffuse", "reflectance": 0.5}},
    "lights": [{"type": "environment", "radiance": 1}]
  })");
  json shape = {{"type", "curves"}, {"material", "fibre"}, {"points", {-1, 0, 0, -1 / 3.0, 0, 0, 1 / 3.0, 0, 0, 1, 0, 0}},
               {"width", 0.02}};
  for (const auto& [key, value] : curves.items()) {
    if (value.is_null())
      shape.erase(key);  // null: leave the key out
    else
      shape[key] = value;
  }
  scene["shapes"] = json::array({shape});
  return scene;
}

std::string load_error(const json& scene) {
  try {
    scene_from_json(scene, "bad.json");
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return "(loaded)";
}

}  // namespace

TEST_CASE("curves shape: loads, with widths per point, counts and transforms") {
  SUBCASE("a single curve") {
    const auto scene = scene_from_json(fibre_scene(json::object()));
    const auto hit = scene->geometry.intersect(ray_between({0.5f, 0.005f, 1.0f}, {0.5f, 0.005f, 0.0f}));
    REQUIRE(hit);
    CHECK(hit->uv.x == doctest::Approx(0.75f).epsilon(1e-4));
    // y = 5 mm, r = 1 cm: h = −y/r, the offset along d × tangent = (0, −1, 0) over the radius.
    CHECK(2 * hit->uv.y - 1 == doctest::Approx(-0.5f).epsilon(1e-3));
    CHECK_FALSE(scene->geometry.intersect(ray_between({0.5f, 0.012f, 1.0f}, {0.5f, 0.012f, 0.0f})));
  }
  SUBCASE("two curves, widths per point, scaled by 2: positions and widths double") {
    const auto scene = scene_from_json(fibre_scene({{"width", nullptr},
                                                    {"points", {-1, 0, 0, -0.3, 0, 0, 0.3, 0, 0, 1, 0, 0, -1, 1, 0, -0.3, 1, 0, 0.3, 1, 0, 1, 1, 0}},
                                                    {"counts", {4, 4}},
                                                    {"widths", {0.02, 0.02, 0.02, 0.02, 0.04, 0.04, 0.04, 0.04}},
                                                    {"transform", {{{"scale", 2}}}}}));
    // The second curve lies at y = 2 after the scale, 8 cm wide: hit at 3.9 cm, missed at 4.1 cm.
    CHECK(scene->geometry.intersect(ray_between({0.0f, 2.039f, 1.0f}, {0.0f, 2.039f, 0.0f})));
    CHECK_FALSE(scene->geometry.intersect(ray_between({0.0f, 2.041f, 1.0f}, {0.0f, 2.041f, 0.0f})));
  }
  SUBCASE("a curve of one point and no width is left out with a warning, and nothing is hit") {
    const auto scene = scene_from_json(fibre_scene({{"points", {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1}}, {"width", 0}}));
    REQUIRE(scene->warnings.size() >= 1);
    CHECK(scene->warnings.back().find("/shapes/0: 1 curve segments of zero width or a single point were left out") != std::string::npos);
    CHECK_FALSE(scene->geometry.intersect(ray_between({1, 1, 3}, {1, 1, 1})));
  }
}

TEST_CASE("curves shape: errors name the key and what was expected") {
  CHECK_CONTAINS(load_error(fibre_scene({{"points", {0, 0, 0, 1, 0, 0, 2, 0, 0}}})), "/shapes/0/points",
                 "curve 0 has 3 points: a Bezier curve of degree 3 has 3n + 1 points");
  CHECK_CONTAINS(load_error(fibre_scene({{"points", {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0}}})), "has 5 points");
  CHECK_CONTAINS(load_error(fibre_scene({{"points", {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0}}})), "/shapes/0/points", "not a multiple of 3");
  CHECK_CONTAINS(load_error(fibre_scene({{"points", {0, 0, nullptr, 1, 0, 0, 2, 0, 0, 3, 0, 0}}})), "/shapes/0/points/2");
  CHECK_CONTAINS(load_error(fibre_scene({{"width", nullptr}, {"widths", {0.1, -0.1, 0.1, 0.1}}})), "/shapes/0/widths/1");
  CHECK_CONTAINS(load_error(fibre_scene({{"width", nullptr}, {"widths", {0.1, 0.1}}})), "/shapes/0/widths",
                 "one width per point: 2 widths for 4 points");
  CHECK_CONTAINS(load_error(fibre_scene({{"widths", {0.1, 0.1, 0.1, 0.1}}})), "not both or neither");
  CHECK_CONTAINS(load_error(fibre_scene({{"counts", {3}}})), "/shapes/0/counts", "add up to 3 points");
  CHECK_CONTAINS(load_error(fibre_scene({{"curve_type", "tube"}})), "/shapes/0/curve_type");
  CHECK_CONTAINS(load_error(fibre_scene({{"curve_type", "ribbon"}})), "/shapes/0", "normals");
  CHECK_CONTAINS(load_error(fibre_scene({{"curve_type", "ribbon"}, {"normals", {0, 0, 1}}})), "/shapes/0/normals",
                 "segments + 1 per curve");
  CHECK_CONTAINS(load_error(fibre_scene({{"emission", 1}})), "/shapes/0/emission", "curves cannot emit");
}

TEST_CASE("pbrt Shape \"curve\": imported as curves, widths linear from width0 to width1, statements merged") {
  const std::string head = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n";
  SUBCASE("one cubic Bezier curve") {
    const PbrtImport imported = import_pbrt_test_text(
        head + "Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0] \"float width0\" 0.3 \"float width1\" 0.0 \"integer splitdepth\" 5\n");
    CHECK(imported.ignored.empty());
    const json& shape = imported.document["shapes"][0];
    CHECK(shape["type"] == "curves");
    CHECK(shape["curve_type"] == "flat");
    CHECK(shape["counts"] == json::array({4}));
    REQUIRE(shape["widths"].size() == 4);
    for (int i = 0; i < 4; ++i) CHECK(shape["widths"][size_t(i)].get<double>() == doctest::Approx(0.3 * (1 - i / 3.0)));
  }
  SUBCASE("consecutive curves of one material and kind are one shape, a count and a line each") {
    std::string text = head;
    // Along y, which the importer's mirror (pbrt's image-right made Rimu's: x → −x) leaves in place.
    for (int k = 0; k < 3; ++k) text += "Shape \"curve\" \"point3 P\" [0 0 0  0 1 0  0 2 0  " + std::to_string(k) + " 3 0] \"float width\" 0.1\n";
    text += "Shape \"curve\" \"string type\" \"cylinder\" \"point3 P\" [0 0 0  0 1 0  0 2 0  0 3 0]\n";
    const PbrtImport imported = import_pbrt_test_text(text);
    const json& shapes = imported.document["shapes"];
    REQUIRE(shapes.size() == 2);
    CHECK(shapes[0]["counts"] == json::array({4, 4, 4}));
    CHECK(shapes[0]["points"].size() == 36);
    CHECK(shapes[1]["curve_type"] == "cylinder");
    const auto scene = scene_from_json(imported.document);
    CHECK(scene->geometry.intersect(ray_between({0.0f, 1.5f, 3.0f}, {0.0f, 1.5f, 0.0f})));
    // The curves' lines: the origin of shape 0 holds one per statement, so an error at /shapes/0/counts/2 names line 6.
    REQUIRE(imported.origins.size() >= 2);
    CHECK(imported.origins[0].pointer == "/shapes/0");
    CHECK(imported.origins[0].element_lines == std::vector<int>{4, 5, 6});
  }
  SUBCASE("a B-spline is written as the same curve in Bezier form; a bad point count is listed") {
    const PbrtImport imported = import_pbrt_test_text(
        head + "Shape \"curve\" \"string basis\" \"bspline\" \"point3 P\" [0 0 0  1 0 0  2 0 0  3 0 0  4 0 0]\n" +
        "Shape \"curve\" \"point3 P\" [0 0 0  1 0 0  2 0 0]\n");
    const json& shape = imported.document["shapes"][0];
    // Two B-spline segments → 7 Bezier points from (0 + 4·1 + 2)/6 = 1 to (2 + 4·3 + 4)/6 = 3.
    REQUIRE(shape["points"].size() == 21);
    CHECK(shape["points"][0].get<double>() == doctest::Approx(1.0));
    CHECK(shape["points"][18].get<double>() == doctest::Approx(3.0));
    REQUIRE(imported.ignored.size() == 1);
    CHECK(imported.ignored[0].what.find("makes no whole segments") != std::string::npos);
  }
}

TEST_CASE("curves render: a fibre in a uniform environment scatters albedo x radiance, without NaN") {
  // Every direction brings radiance 1, so one scattering off a Lambertian of albedo R + T = 0.5 (half reflected,
  // half transmitted) gives exactly 0.5. A ray that stopped on the fibre it left would scatter again and darken it
  // (×0.5 per extra event): a transmitted ray meets a tube's far side, and a flat fibre turns to face every ray.
  for (const char* kind : {"flat", "cylinder"}) {
    CAPTURE(kind);
    json document = fibre_scene({{"curve_type", kind}});
    document["materials"]["fibre"] = {{"type", "diffuse_transmission"}, {"reflectance", 0.25}, {"transmittance", 0.25}};
    const auto scene = scene_from_json(document);
    const auto lanes = lane_radiance(
        *scene,
        [](int i) {  // across the whole 2 cm width, not only the centreline
          return ray_between({0.0f, 0.0f, 3.0f}, {-0.8f + 1.6f * float(i % 97) / 96.0f, 0.0095f * std::sin(1.7f * float(i)), 0.0f});
        },
        2048);
    for (const Estimate& lane : lanes) {
      CHECK(std::isfinite(lane.mean));
      CHECK(std::fabs(lane.mean - 0.5) <= kSigmas * lane.standard_error + 1e-6);
    }
  }
  // The whole render loop over the image (the fibre crosses its middle row) stays finite.
  const auto scene = scene_from_json(fibre_scene({{"curve_type", "flat"}}));
  const RenderedFilm rendered = render_xyz(*scene, 4, 3);
  for (const double y : luminance_values(*rendered.film)) CHECK(std::isfinite(y));
}

TEST_CASE("curves: a long bent flat curve is hit along its true centreline (Embree's tessellation rate)") {
  // pbrt-v3-scenes' figures/f3-18 curve: one cubic Bézier 5 units long, bent into an S, 0.15-0.35 wide, seen from
  // +z. Embree cuts a flat curve into 4 linear pieces per segment by default, whose chords stray up to
  // max|B''|/(8·4²) ≈ 0.5 from the Bézier, more than the curve's half-width: a ray aimed at the centreline missed.
  // curve_tessellation_rate asks for 5 % of the radius: every centreline point is hit, within that of its depth.
  const Vec3 p[4] = {{-2, -1, -1}, {2, 2, 0}, {-2, -2, 0}, {2, 1, -1}};
  json points = json::array();
  for (const Vec3& q : p) points.insert(points.end(), {q.x, q.y, q.z});
  const auto scene = scene_from_json(
      fibre_scene({{"points", points}, {"width", nullptr}, {"widths", {0.35, 0.28, 0.22, 0.15}}, {"curve_type", "flat"}}));
  for (int i = 1; i < 40; ++i) {
    const float t = i / 40.0f, s = 1.0f - t;
    const Vec3 c = p[0] * (s * s * s) + p[1] * (3 * s * s * t) + p[2] * (3 * s * t * t) + p[3] * (t * t * t);
    CAPTURE(t);
    const auto hit = scene->geometry.intersect(ray_between({c.x, c.y, 5.0f}, {c.x, c.y, -5.0f}));
    REQUIRE(hit);
    CHECK(std::abs(hit->position.z - c.z) < 0.05f);
  }
  CurveSet straight;
  straight.points = {{{0, 0, 0}, 0.01f}, {{1, 0, 0}, 0.01f}, {{2, 0, 0}, 0.01f}, {{3, 0, 0}, 0.01f}};
  straight.first_point = {0};
  CHECK(curve_tessellation_rate(straight) == 4);  // straight: Embree's default
  CurveSet bent = straight;
  bent.points[1].position = {1, 1, 0};  // |P0 − 2P1 + P2| = 2: n = ⌈√(6·2 / (8·0.05·0.01))⌉ = 55
  CHECK(curve_tessellation_rate(bent) == 55);
  bent.points[1].position = {1, 10, 0};
  CHECK(curve_tessellation_rate(bent) == 64);  // the most
}
