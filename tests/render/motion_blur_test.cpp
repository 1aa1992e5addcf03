// Motion blur: shapes, instances and the camera move while the shutter is open ("transform_end", "from_end"); each
// camera sample draws a time and its rays see the scene as it is then. Checked against coverage fractions that follow
// from the geometry alone, through Embree directly and through whole renders.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "input_error_check.h"
#include "integration_support.h"
#include "render/camera/camera.h"
#include "render/scene/embree_scene.h"

using namespace rimu;
using nlohmann::json;

namespace {

constexpr double kPiMotion = 3.14159265358979323846;

// The unit square in z = 0, facing +z.
TriangleMesh unit_square() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// A bar from the z axis along +x: x in [0, 1.5], |y| ≤ 0.1, z in [−0.1, 0] (triangles facing +z on top).
TriangleMesh bar() {
  TriangleMesh m;
  m.positions = {{0, -0.1f, 0}, {1.5f, -0.1f, 0}, {1.5f, 0.1f, 0}, {0, 0.1f, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Ray down_at(float x, float y, float time) {
  Ray r;
  r.origin = {x, y, 5.0f};
  r.direction = {0, 0, -1};
  r.time = time;
  return r;
}

MotionTransform motion(const Transform& start, const Transform& end) {
  bool valid = false;
  MotionTransform m(start, end, valid);
  REQUIRE(valid);
  return m;
}

// The black slab of the render tests, seen from above by an orthographic camera against a white environment.
json sliding_slab_scene() {
  return json::parse(R"({
    "camera": {"type": "orthographic", "from": [0, 0, 5], "to": [0, 0, 0], "up": [0, 1, 0], "height": 2},
    "film": {"resolution": [32, 32], "filter": {"type": "box", "radius": 0.5}},
    "integrator": {"max_depth": 2},
    "materials": {"black": {"type": "diffuse", "reflectance": 0.0}},
    "shapes": [{"type": "box", "min": [-0.25, -2, -0.5], "max": [0.25, 2, 0], "material": "black",
                "transform": [{"translate": [-1, 0, 0]}], "transform_end": [{"translate": [1, 0, 0]}]}],
    "lights": [{"type": "environment", "radiance": 1.0}]
  })");
}

// The mean luminance over the columns [x0, x1) of a 32 × 32 film, with its standard error (pixels i.i.d. there).
test::Estimate column_mean(const Film& film, int x0, int x1) {
  std::vector<double> values;
  for (int y = 0; y < 32; ++y)
    for (int x = x0; x < x1; ++x) values.push_back(film.pixel_value(x, y)[1]);
  return test::estimate_of(values);
}

}  // namespace

TEST_CASE("motion blur: a moving instance is hit, and shaded, where it is at the ray's time") {
  EmbreeScene scene;
  std::vector<std::pair<TriangleMesh, int>> meshes;
  meshes.emplace_back(unit_square(), 0);
  const int prototype = scene.add_prototype(std::move(meshes));
  // A quarter turn about y: the square's normal goes from +z to +x.
  scene.add_instance(prototype, motion(Transform(), Transform::rotate(90, {0, 1, 0})));
  scene.commit();
  REQUIRE(scene.has_motion());
  for (const float time : {0.0f, 0.5f, 1.0f}) {
    const double angle = 0.5 * kPiMotion * double(time);
    const Vec3 normal{float(std::sin(angle)), 0.0f, float(std::cos(angle))};
    // The square's centre (½, ½, 0) turned by the angle, seen from 5 along the normal.
    const Vec3 centre{float(0.5 * std::cos(angle)), 0.5f, float(-0.5 * std::sin(angle))};
    Ray ray;
    ray.origin = centre + normal * 5.0f;
    ray.direction = normal * -1.0f;
    ray.time = time;
    const auto hit = scene.intersect(ray);
    CAPTURE(time);
    REQUIRE(hit);
    CHECK(hit->t == doctest::Approx(5.0).epsilon(1e-5));
    CHECK(length(hit->position - centre) < 1e-5f);
    CHECK(length(hit->geometric_normal - normal) < 1e-5f);
    CHECK(scene.occluded(ray));
  }
  // Straight down at x = 0.9: the square is there at time 0; half-way it has turned away (it would reach x = 0.9
  // only at 1.27 along its edge).
  CHECK(scene.intersect(down_at(0.9f, 0.5f, 0.0f)));
  CHECK_FALSE(scene.intersect(down_at(0.9f, 0.5f, 0.5f)));
  CHECK_FALSE(scene.occluded(down_at(0.9f, 0.5f, 0.5f)));
}

TEST_CASE("motion blur: a rotating bar covers a point for the share of the shutter its angular width says") {
  // The bar turns a quarter about z. A point at radius r and angle α (inside the sweep, away from its ends) is
  // covered while the bar's angle is within asin(0.1/r) of α: a share 2·asin(0.1/r)/(π/2) of the shutter. Times
  // are stratified (10⁴), so the share is exact to 1e-4 plus the keys' chord (1 − cos 1° of the radius).
  // Interpolating the two matrices instead would turn the bar unevenly (18.4° instead of 22.5° at a quarter time)
  // and narrow it by up to cos 45°: 30 % less cover at 45°.
  EmbreeScene scene;
  std::vector<std::pair<TriangleMesh, int>> meshes;
  meshes.emplace_back(bar(), 0);
  scene.add_instance(scene.add_prototype(std::move(meshes)), motion(Transform(), Transform::rotate(90, {0, 0, 1})));
  scene.commit();
  constexpr int kTimes = 10000;
  for (const double r : {0.6, 0.9, 1.3}) {
    for (const double alpha_deg : {20.0, 30.0, 45.0, 70.0}) {
      const double alpha = alpha_deg * kPiMotion / 180.0;
      int covered = 0;
      for (int i = 0; i < kTimes; ++i)
        covered += scene.occluded(down_at(float(r * std::cos(alpha)), float(r * std::sin(alpha)), (float(i) + 0.5f) / kTimes));
      const double expected = 2.0 * std::asin(0.1 / r) / (0.5 * kPiMotion);
      CAPTURE(r);
      CAPTURE(alpha_deg);
      CHECK(std::abs(double(covered) / kTimes - expected) <= 3e-4);
    }
  }
}

TEST_CASE("motion blur: a slab sliding across the view darkens what it passes over by the time it covers it") {
  // The slab, 0.5 wide, slides 2 to the right during the shutter: it covers any point of |x| ≤ 0.75 for a quarter of
  // the shutter, so the white environment there is seen for three quarters. Columns 6..25 have pixel centres
  // within |x| ≤ 0.66 (and pixel edges within 0.69).
  const auto moving = test::scene_from_json(sliding_slab_scene());
  json still_document = sliding_slab_scene();
  still_document["shapes"] = json::array();
  const auto still = test::scene_from_json(still_document);
  CHECK(moving->transport_view().has_motion);
  CHECK_FALSE(still->transport_view().has_motion);
  const auto blurred = test::render_xyz(*moving, 64, 3);
  const auto open = test::render_xyz(*still, 64, 4);
  const test::Estimate a = column_mean(*blurred.film, 6, 26), b = column_mean(*open.film, 6, 26);
  const double se = std::hypot(a.standard_error, 0.75 * b.standard_error);
  CHECK(std::abs(a.mean - 0.75 * b.mean) <= test::kSigmas * se);
  CHECK(se < 0.01 * b.mean);  // a test that can see a 5 % error
  // Without the motion (the slab at its start, off to the left), the same columns are open.
  json parked_document = sliding_slab_scene();
  parked_document["shapes"][0].erase("transform_end");
  const auto parked = test::render_xyz(*test::scene_from_json(parked_document), 64, 5);
  const test::Estimate c = column_mean(*parked.film, 6, 26);
  CHECK(std::abs(c.mean - b.mean) <= test::kSigmas * std::hypot(c.standard_error, b.standard_error));
}

TEST_CASE("motion blur: shadow rays see the occluder where their path's time puts it (surface and volume paths)") {
  // A slanted sun (45°, from −x) over a white floor and the sliding slab (0.5 wide, 0.1 thick, 1 above the floor):
  // the slab centred at c shades the floor over [c + 0.75, c + 1.35]. A floor point at x in [0.35, 0.75] is hidden
  // from the camera for a quarter of the shutter (c within 0.25 of x) and in shadow for 0.6/2 of it (c in
  // [x − 1.35, x − 0.75], inside the slab's travel [−1, 1]), at disjoint times: it shows 1 − 0.25 − 0.3 = 0.45 of
  // the light. Had the shadow rays been traced at shutter open (c = −1, the shadow over [−0.25, 0.35]) it would show
  // 0.75. Columns 23..26 span x in [0.44, 0.69]. With a medium elsewhere the volumetric integrator renders.
  for (const bool with_media : {false, true}) {
    CAPTURE(with_media);
    json document = sliding_slab_scene();
    document["integrator"]["max_depth"] = 1;
    document["materials"]["white"] = {{"type", "diffuse"}, {"reflectance", 1.0}};
    document["shapes"][0]["min"] = {-0.25, -2, 1.0};
    document["shapes"][0]["max"] = {0.25, 2, 1.1};
    document["shapes"].push_back(json::parse(R"({"type": "quad", "material": "white",
        "vertices": [[-3, -3, 0], [3, -3, 0], [3, 3, 0], [-3, 3, 0]]})"));
    document["lights"] = json::parse(R"([{"type": "distant", "direction": [-1, 0, 1], "irradiance": 1.0}])");
    if (with_media) {
      document["materials"]["fog boundary"] = {{"type", "dielectric"}, {"ior", 1.0}};
      document["media"] = json::parse(R"({"fog": {"type": "homogeneous", "sigma_a": 0.1, "sigma_s": 0.1,
                                                   "boundary_material": "fog boundary", "index_matched": true}})");
      document["shapes"].push_back(json::parse(R"({"type": "sphere", "center": [20, 0, 0], "radius": 0.5,
                                                    "material": "fog boundary"})"));
    }
    json still_document = document;
    still_document["shapes"].erase(0);
    const auto moving = test::scene_from_json(document);
    const auto still = test::scene_from_json(still_document);
    REQUIRE(moving->has_media() == with_media);
    const test::Estimate a = column_mean(*test::render_xyz(*moving, 64, 11).film, 23, 27);
    const test::Estimate b = column_mean(*test::render_xyz(*still, 64, 12).film, 23, 27);
    const double se = std::hypot(a.standard_error, 0.45 * b.standard_error);
    CHECK(std::abs(a.mean - 0.45 * b.mean) <= test::kSigmas * se);
    CHECK(se < 0.03 * b.mean);
  }
}

TEST_CASE("motion blur: a moving camera sees a still slab smeared as a moving slab would be") {
  // The camera slides 2 to the left past the slab at rest: relative to the camera the slab moves right as in the
  // test above, so the centre columns see the environment for three quarters of the shutter.
  json document = sliding_slab_scene();
  document["shapes"][0].erase("transform");
  document["shapes"][0].erase("transform_end");
  document["camera"]["from"] = {1, 0, 5};
  document["camera"]["to"] = {1, 0, 0};
  document["camera"]["from_end"] = {-1, 0, 5};
  document["camera"]["to_end"] = {-1, 0, 0};
  const auto scene = test::scene_from_json(document);
  CHECK(scene->transport_view().has_motion);
  json still_document = sliding_slab_scene();
  still_document["shapes"] = json::array();
  const auto still = test::scene_from_json(still_document);
  const test::Estimate a = column_mean(*test::render_xyz(*scene, 64, 6).film, 6, 26);
  const test::Estimate b = column_mean(*test::render_xyz(*still, 64, 7).film, 6, 26);
  CHECK(std::abs(a.mean - 0.75 * b.mean) <= test::kSigmas * std::hypot(a.standard_error, 0.75 * b.standard_error));

  // The camera itself: at each time its rays start where the camera then is, and carry the time.
  CameraSettings settings;
  settings.camera_to_world = Transform::look_at({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
  settings.camera_to_world_end = Transform::look_at({4, 0, 0}, {4, 0, -1}, {0, 1, 0});
  const Camera camera(settings, 16, 16);
  for (const float time : {0.0f, 0.25f, 1.0f}) {
    const Ray ray = camera.generate_ray(8, 8, {0.5f, 0.5f}, time);
    CHECK(ray.time == time);
    CHECK(length(ray.origin - Vec3{4 * time, 0, 0}) < 1e-6f);
    CHECK(length(ray.direction - Vec3{0, 0, -1}) < 1e-6f);
  }
}

TEST_CASE("motion blur: a scene where nothing moves draws no time, and a moving one renders the same on 1 or 2 threads") {
  // transform_end equal to transform is no motion: the image is the one without transform_end, bit for bit (the
  // sampler's dimensions are those of a still scene).
  json same_document = sliding_slab_scene();
  same_document["shapes"][0]["transform_end"] = same_document["shapes"][0]["transform"];
  json plain_document = sliding_slab_scene();
  plain_document["shapes"][0].erase("transform_end");
  const auto same = test::scene_from_json(same_document);
  CHECK_FALSE(same->transport_view().has_motion);
  CHECK(test::film_bits(*test::render_xyz(*same, 8, 9).film) ==
        test::film_bits(*test::render_xyz(*test::scene_from_json(plain_document), 8, 9).film));
  const auto moving = test::scene_from_json(sliding_slab_scene());
  CHECK(test::film_bits(*test::render_xyz(*moving, 8, 9, 1).film) == test::film_bits(*test::render_xyz(*moving, 8, 9, 2).film));
}

TEST_CASE("motion blur: what cannot move is refused with its key") {
  json emissive = sliding_slab_scene();
  emissive["shapes"][0]["emission"] = {{"radiance", 1.0}};
  test::input_error([&] { test::scene_from_json(emissive); }, {"/shapes/0/transform_end", "emissive shape cannot move"});
  json flip = sliding_slab_scene();
  flip["shapes"][0]["transform_end"] = json::parse(R"([{"scale": [-1, 1, 1]}])");
  test::input_error([&] { test::scene_from_json(flip); }, {"/shapes/0/transform_end", "mirrors"});
  json sphere = sliding_slab_scene();
  sphere["shapes"][0] = json::parse(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "black",
                                        "transform_end": [{"translate": [1, 0, 0]}]})");
  test::input_error([&] { test::scene_from_json(sphere); }, {"/shapes/0", "transform_end"});
  json camera = sliding_slab_scene();
  camera["camera"]["from_end"] = {0, 0, 0};
  test::input_error([&] { test::scene_from_json(camera); }, {"/camera/from_end", "no viewing direction"});
  json prototype = sliding_slab_scene();
  prototype["prototypes"] = {{"p", json::array({prototype["shapes"][0]})}};
  test::input_error([&] { test::scene_from_json(prototype); }, {"/prototypes/p/0", "transform_end"});
}
