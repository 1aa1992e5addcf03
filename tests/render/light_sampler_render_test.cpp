// The light samplers converge to the same image: the BVH sampler against the power sampler on the Cornell box, on a
// spot + D65 environment + floor, and under 1,000 emissive triangles of different spectra. Each pair of renders
// uses different seeds; the mean pixel difference is compared with its standard error estimated from the pixel
// differences themselves (test::paired_difference), at test::kSigmas. Also: the load-time coverage warning names
// the spot the power sampler starves, and is silent under the BVH sampler.
#include <doctest/doctest.h>

#include <random>
#include <string>

#include "integration_support.h"
#include "render/scene/json_cursor.h"
#include "render/scene/light_coverage.h"

using namespace rimu;

namespace {

struct Comparison {
  test::Estimate difference;
  double mean_power = 0.0;
};

Comparison bvh_against_power(nlohmann::json document, int spp,
                             const std::filesystem::path& directory = test::library().root(),
                             const char* tree = "bvh") {
  document["integrator"]["light_sampler"] = tree;
  const auto bvh = load_scene(document, "bvh.json", directory, test::library());
  document["integrator"]["light_sampler"] = "power";
  const auto power = load_scene(document, "power.json", directory, test::library());
  const auto a = test::luminance_values(*test::render_xyz(*bvh, spp, 101).film);
  const auto b = test::luminance_values(*test::render_xyz(*power, spp, 202).film);
  return {test::paired_difference(a, b), test::mean_of(b)};
}

// `scene` is a std::string: doctest's INFO prints a const char* as a pointer.
void check_same_mean(const Comparison& c, const std::string& scene) {
  INFO(scene << ": mean Y (power) " << c.mean_power << ", bvh − power " << c.difference.mean << " ± "
             << c.difference.standard_error);
  CHECK(c.mean_power > 0.0);
  CHECK(std::fabs(c.difference.mean) <= test::kSigmas * c.difference.standard_error);
}

nlohmann::json spot_environment_floor(double floor_half_size_m) {
  nlohmann::json d = nlohmann::json::parse(R"({
    "camera": {"from": [0, 3.5, 4.5], "to": [0, 0, 0], "vertical_fov_deg": 50},
    "film": {"resolution": [24, 24], "filter": {"type": "box"}},
    "integrator": {"max_depth": 4},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5},
                  "copper": {"type": "conductor", "metal": "copper", "roughness": 0.2}},
    "lights": [
      {"type": "spot", "name": "key", "position": [0, 2, 0], "direction": [0, -1, 0], "cone_angle_deg": 40,
       "falloff_start_deg": 30, "luminous_power_lm": 800, "power_convention": "cone", "spectrum": {"blackbody": 2700}},
      {"type": "environment", "name": "sky", "radiance": {"illuminant": "D65", "scale": 0.0001}}
    ],
    "shapes": [
      {"type": "sphere", "material": "copper", "center": [0.6, 0.4, 0.2], "radius": 0.4}
    ]
  })");
  const double h = floor_half_size_m;
  d["shapes"].push_back({{"type", "quad"},
                         {"material", "grey"},
                         {"vertices", {{-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}}}});
  return d;
}

// 1,000 one-sided emissive triangles, each its own light with its own blackbody (1,500-10,000 K), most under a
// 10 m ceiling facing down, a tenth at random orientations, above a grey floor.
nlohmann::json thousand_triangles() {
  nlohmann::json d = nlohmann::json::parse(R"({
    "camera": {"from": [0, 2.5, 7], "to": [0, 0.5, 0], "vertical_fov_deg": 60},
    "film": {"resolution": [24, 24], "filter": {"type": "box"}},
    "integrator": {"max_depth": 3},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}, "black": {"type": "diffuse", "reflectance": 0}},
    "shapes": [
      {"type": "quad", "material": "grey", "vertices": [[-8, 0, 8], [8, 0, 8], [8, 0, -8], [-8, 0, -8]]}
    ]
  })");
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    const double x = -5 + 10 * u(rng), y = k % 10 == 0 ? 0.5 + 2.0 * u(rng) : 3.0, z = -5 + 10 * u(rng);
    const double s = 0.08 + 0.1 * u(rng);
    nlohmann::json positions;
    if (k % 10 == 0) {  // a random orientation
      for (int j = 0; j < 3; ++j) positions.push_back({x + s * (2 * u(rng) - 1), y + s * (2 * u(rng) - 1), z + s * (2 * u(rng) - 1)});
    } else {  // facing down: (v1 − v0) × (v2 − v0) = −y
      positions = {{x, y, z}, {x + s, y, z}, {x, y, z + s}};
    }
    d["shapes"].push_back({{"type", "triangles"},
                           {"material", "black"},
                           {"positions", positions},
                           {"indices", {0, 1, 2}},
                           {"emission", {{"blackbody", 1500.0 + 8.5 * k}, {"scale", 2.0 + 3.0 * u(rng)}}}});
  }
  return d;
}

// A red and a blue point light (narrow Gaussian-like tables around 630 and 460 nm) and a low-pressure sodium line
// at 589 nm over a white floor, with a white D65 panel: the coloured-light case wavelength-aware choice is for.
nlohmann::json coloured_lights() {
  nlohmann::json d = nlohmann::json::parse(R"({
    "camera": {"from": [0, 3, 4], "to": [0, 0, 0], "vertical_fov_deg": 55},
    "film": {"resolution": [24, 24], "filter": {"type": "box"}},
    "integrator": {"max_depth": 3},
    "materials": {"white": {"type": "diffuse", "reflectance": 0.8}},
    "lights": [
      {"type": "point", "name": "red", "position": [-1, 1, 0], "radiant_power_w": 20,
       "spectrum": {"wavelengths_nm": [600, 615, 630, 645, 660], "values": [0, 0.5, 1, 0.5, 0]}},
      {"type": "point", "name": "blue", "position": [1, 1, 0], "radiant_power_w": 20,
       "spectrum": {"wavelengths_nm": [430, 445, 460, 475, 490], "values": [0, 0.5, 1, 0.5, 0]}},
      {"type": "spot", "name": "sodium", "position": [0, 1.5, -1], "direction": [0, -1, 0.3], "cone_angle_deg": 60,
       "falloff_start_deg": 45, "radiant_power_w": 5, "power_convention": "cone", "spectrum": {"wavelengths_nm": [587, 589.3, 591.6], "values": [0, 1, 0]}}
    ],
    "shapes": [
      {"type": "quad", "material": "white", "vertices": [[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]]},
      {"type": "quad", "material": "white", "vertices": [[-0.3, 2, -0.3], [0.3, 2, -0.3], [0.3, 2, 0.3], [-0.3, 2, 0.3]],
       "emission": {"illuminant": "D65", "scale": 0.05}}
    ]
  })");
  return d;
}

}  // namespace

TEST_CASE("light samplers agree: bvh-spectral against power under red, blue and sodium lights, in X, Y and Z") {
  // Each film channel separately: a choice that favoured one light at the wrong wavelengths would bias the colour.
  nlohmann::json document = coloured_lights();
  document["integrator"]["light_sampler"] = "bvh-spectral";
  const auto spectral = load_scene(document, "spectral.json", test::library().root(), test::library());
  document["integrator"]["light_sampler"] = "power";
  const auto power = load_scene(document, "power.json", test::library().root(), test::library());
  const auto a = test::render_xyz(*spectral, 32, 303);
  const auto b = test::render_xyz(*power, 32, 404);
  for (int channel = 0; channel < 3; ++channel) {
    const auto values = [channel](const Film& film) {
      std::vector<double> v;
      const PixelBounds& bounds = film.pixel_bounds();
      for (int py = bounds.y0; py < bounds.y1; ++py)
        for (int px = bounds.x0; px < bounds.x1; ++px) v.push_back(film.pixel_value(px, py)[size_t(channel)]);
      return v;
    };
    const std::vector<double> vb = values(*b.film);
    INFO("channel " << "XYZ"[channel]);
    check_same_mean({test::paired_difference(values(*a.film), vb), test::mean_of(vb)}, "coloured lights, bvh-spectral");
  }
}

TEST_CASE("light samplers agree: bvh-spectral against power on the Cornell box and 1,000 triangles") {
  const std::filesystem::path path = test::library().root() / "scenes" / "cornell_box" / "scene.json";
  nlohmann::json document = parse_json_file(path);
  document["film"]["resolution"] = {24, 24};
  document["film"]["filter"] = {{"type", "box"}};
  document["integrator"]["max_depth"] = 5;
  check_same_mean(bvh_against_power(document, 32, path.parent_path(), "bvh-spectral"), "Cornell box, bvh-spectral");
  check_same_mean(bvh_against_power(thousand_triangles(), 16, test::library().root(), "bvh-spectral"),
                  "1,000 triangles, bvh-spectral");
}

TEST_CASE("light samplers agree: the Cornell box") {
  const std::filesystem::path path = test::library().root() / "scenes" / "cornell_box" / "scene.json";
  nlohmann::json document = parse_json_file(path);
  document["film"]["resolution"] = {24, 24};
  document["film"]["filter"] = {{"type", "box"}};
  document["integrator"]["max_depth"] = 5;
  check_same_mean(bvh_against_power(document, 32, path.parent_path()), "Cornell box");
}

TEST_CASE("light samplers agree: a spot, a D65 environment and a floor") {
  check_same_mean(bvh_against_power(spot_environment_floor(3.0), 32), "spot + environment, 6 m floor");
}

TEST_CASE("light samplers agree: 1,000 emissive triangles of different spectra") {
  check_same_mean(bvh_against_power(thousand_triangles(), 16), "1,000 triangles");
}

TEST_CASE("load-time warning: a spot starved by the power sampler is named, none under the BVH sampler") {
  nlohmann::json document = spot_environment_floor(50.0);  // a 100 m floor: the environment's power weight is huge
  // An overcast CIE sky in place of the uniform one: light sampling leaves a constant environment to BSDF sampling
  // (docs/transport.md), so the power sampler never weighs it against the spot. 50 lx on the ground, against the
  // spot's ~140 lx under it.
  document["lights"][1] = {{"type", "cie_sky"}, {"name", "sky"}, {"sky_type", 1}, {"diffuse_horizontal_illuminance_lx", 50}};
  document["integrator"]["light_sampler"] = "power";
  const auto power = test::scene_from_json(document);
  REQUIRE(power->warnings.size() == 1);
  CHECK(power->warnings[0].find("'key' (/lights/0)") != std::string::npos);
  const std::vector<LightCoverage> coverage = light_coverage(*power);
  REQUIRE(coverage.size() == 1);
  CAPTURE(coverage[0].sample_share);
  CAPTURE(coverage[0].irradiance_share);
  MESSAGE("power sampler: the spot's share of samples ", coverage[0].sample_share, ", of the light under it ",
          coverage[0].irradiance_share);
  CHECK(coverage[0].sample_share < 0.01);
  CHECK(coverage[0].irradiance_share > 0.1);  // under the spot, the spot gives a good part of the light
  document["integrator"]["light_sampler"] = "bvh";
  const auto bvh = test::scene_from_json(document);
  CHECK(bvh->warnings.empty());
  CHECK(light_coverage(*bvh)[0].sample_share > 0.4);
}
