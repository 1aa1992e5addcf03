// Radiometric closure: a Lambertian surface of albedo ρ receiving irradiance E reflects radiance ρE/π in every
// direction (the definition of a Lambertian BRDF f = ρ/π integrated against L cos θ). Two sources with known
// irradiance: a distant light (E cos θ on a plane tilted θ away from it, distant_light.h) and a point light of
// intensity I at distance r along a direction at angle θ to the normal (E = I cos θ / r², the inverse-square law).
// All spectra are constant (equal energy), so the film's Y equals the radiance (film.h normalisation).
//
// Both lights are delta lights reached only by next-event estimation, so every lane of every sample is exactly
// ρ E/π (BSDF-sampled continuations escape into black): the integrator's lanes are checked to float rounding, and
// the film's Y carries only the wavelength-sampling noise of Σ ȳ(λ)/p(λ), whose error bar comes from the pixels.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "integration_support.h"
#include "render/camera/camera.h"
#include "test_support.h"

using namespace rimu;
using namespace rimu::test;

namespace {

using rimu::test::kPi;

// A 20 m square of albedo `rho` at y = 0 (normal +y), seen from 45° above by a narrow camera (every pixel on it).
nlohmann::json plane_scene(double rho, const nlohmann::json& lights) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 2, -2], "to": [0, 0, 0], "vertical_fov_deg": 20},
    "film": {"resolution": [16, 16], "filter": {"type": "box"}},
    "integrator": {"max_depth": 8},
    "shapes": [{"type": "quad", "material": "plane",
                "vertices": [[-10, 0, -10], [-10, 0, 10], [10, 0, 10], [10, 0, -10]]}]
  })");
  scene["materials"]["plane"] = {{"type", "diffuse"}, {"reflectance", rho}};
  scene["lights"] = lights;
  return scene;
}

// Every lane of the integrator on rays at the plane's centre region equals `expected` to float rounding.
void check_lanes_exact(const Scene& scene, Vec3 from, double expected) {
  const auto lanes = lane_radiance(
      scene, [&](int i) { return ray_between(from, {0.05f * float(i % 7 - 3), 0.0f, 0.05f * float(i / 7 - 3)}); }, 49);
  for (int j = 0; j < 4; ++j) {
    CAPTURE(j);
    CHECK(lanes[size_t(j)].mean == doctest::Approx(expected).epsilon(1e-5));
    CHECK(lanes[size_t(j)].standard_error <= 1e-5 * expected);
  }
}

}  // namespace

TEST_CASE("closure: a Lambertian plane of albedo 0.5 under a distant light at 60 degrees shows rho E cos(theta)/pi") {
  const double rho = 0.5, irradiance = 2.0, theta = kPi / 3.0;
  const double expected = rho * irradiance * std::cos(theta) / kPi;  // 0.159155
  nlohmann::json light = {{"type", "distant"}, {"irradiance", irradiance},
                          {"direction", {std::sin(theta), std::cos(theta), 0.0}}};
  const auto scene = scene_from_json(plane_scene(rho, nlohmann::json::array({light})));
  check_lanes_exact(*scene, {0.0f, 2.0f, -2.0f}, expected);

  const RenderedFilm rendered = render_xyz(*scene, 16, 5);
  CHECK(rendered.film->sample_counts().discarded() == 0);
  const Estimate y = estimate_of(luminance_values(*rendered.film));
  CAPTURE(y.mean);
  CAPTURE(y.standard_error);
  CHECK(std::abs(y.mean - expected) <= kSigmas * y.standard_error);
  // Not trivially passing: the bound is a small fraction of the value.
  CHECK(kSigmas * y.standard_error < 0.02 * expected);
}

TEST_CASE("closure: a point light of intensity I at height d over a white plane gives I/(pi d^2) below it, I cos/(pi r^2) around") {
  // Radiance of a white Lambertian point at horizontal offset x: E/π with E = I cos θ / r² = I d / r³, r² = d² + x².
  const double intensity = 3.0, d = 0.5;
  nlohmann::json scene_json = plane_scene(1.0, nlohmann::json::array({nlohmann::json{
      {"type", "point"}, {"position", {0.0, d, 0.0}}, {"intensity", intensity}}}));
  // Straight down from above the light (point lights are not geometry: camera rays pass through them).
  scene_json["camera"] = {{"from", {0, 2, 0}}, {"to", {0, 0, 0}}, {"up", {0, 0, 1}}, {"vertical_fov_deg", 60}};
  scene_json["film"]["resolution"] = {15, 15};
  const auto scene = scene_from_json(scene_json);
  auto radiance_at = [&](double x, double z) {
    const double r = std::sqrt(d * d + x * x + z * z);
    return intensity * d / (kPi * r * r * r);
  };

  // The point right below the light: every lane exactly I/(π d²) = 3.8197.
  const auto lanes = lane_radiance(*scene, [](int) { return ray_between({0, 2, 0}, {0, 0, 0}); }, 16);
  for (int j = 0; j < 4; ++j) CHECK(lanes[size_t(j)].mean == doctest::Approx(intensity / (kPi * d * d)).epsilon(1e-5));

  // Each pixel's expected value: the box filter averages the radiance over the pixel's footprint on the plane
  // (16×16 midpoint quadrature of the camera's own rays; the integrand is smooth at this scale, so the quadrature
  // error is far below the noise). The ratio value/expected then has mean 1 in every pixel and the same
  // wavelength-sampling spread, so the pixels give i.i.d. ratios.
  const Camera camera(scene->camera, 15, 15);
  const RenderedFilm rendered = render_xyz(*scene, 16, 9);
  CHECK(rendered.film->sample_counts().discarded() == 0);
  std::vector<double> ratios;
  for (int py = 0; py < 15; ++py) {
    for (int px = 0; px < 15; ++px) {
      double sum = 0.0;
      for (int sy = 0; sy < 16; ++sy) {
        for (int sx = 0; sx < 16; ++sx) {
          const Ray ray = camera.generate_ray(float(px) + (float(sx) + 0.5f) / 16.0f, float(py) + (float(sy) + 0.5f) / 16.0f, {0.5f, 0.5f});
          const double t = -double(ray.origin.y) / double(ray.direction.y);
          sum += radiance_at(double(ray.origin.x) + t * double(ray.direction.x), double(ray.origin.z) + t * double(ray.direction.z));
        }
      }
      ratios.push_back(rendered.film->pixel_value(px, py)[1] / (sum / 256.0));
    }
  }
  const Estimate ratio = estimate_of(ratios);
  CAPTURE(ratio.mean);
  CAPTURE(ratio.standard_error);
  CHECK(std::abs(ratio.mean - 1.0) <= kSigmas * ratio.standard_error);
  CHECK(kSigmas * ratio.standard_error < 0.02);
}
