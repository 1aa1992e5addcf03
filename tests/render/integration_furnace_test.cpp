// White furnace: an object that neither absorbs nor emits, inside a uniform environment of radiance 1, is
// invisible. Every camera ray must see radiance 1 at every wavelength, whatever the object scatters, because in a
// world where every direction brings radiance 1, L = ∫ f L cos dω = albedo, so L ≡ 1 exactly when the albedo is 1.
// The only allowed departure is physical: single-scattering microfacet models lose the light that would bounce
// between facets (Kulla & Conty, "Revisiting Physically Based Shading at Imageworks", SIGGRAPH 2017 course), so
// rough surfaces render below 1 (never above: that would create energy). For those, the expected value including
// the loss is computed independently, by a plain BSDF random walk in the test (reference_walk below: analytic
// sphere, BSDF sampling only, no NEE, MIS, Russian roulette or spectral MIS), and the renderer must match it: the
// renderer may not add a loss (or gain) of its own on top of the BSDF's.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include "integration_support.h"
#include "render/camera/camera.h"
#include "transport/geometry/frame.h"

using namespace rimu;
using namespace rimu::test;

namespace {

constexpr int kSpp = 16;  // 16×16 pixels × 16 spp = 4096 camera samples per material

// A unit sphere filling a 16×16 image (the corner rays pass 14.0° off axis, inside the sphere's 14.5° silhouette),
// in a constant environment of radiance 1 (equal-energy: Y = 1 on the film).
nlohmann::json furnace(const nlohmann::json& material) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 0, -4], "to": [0, 0, 0], "vertical_fov_deg": 20},
    "film": {"resolution": [16, 16], "filter": {"type": "box"}},
    "integrator": {"max_depth": 64, "russian_roulette_depth": 3},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "object"}],
    "lights": [{"type": "environment", "radiance": 1}]
  })");
  scene["materials"]["object"] = material;
  return scene;
}

// Camera rays from the camera's position over a 64×64 grid of directions inside the sphere's silhouette.
Ray furnace_ray(int i) {
  const float u = float(i % 64) / 63.0f - 0.5f, v = float((i / 64) % 64) / 63.0f - 0.5f;
  return ray_between({0.0f, 0.0f, -4.0f}, {0.9f * u, 0.9f * v, 0.0f});
}

// Nearest t > 0 where the ray meets the unit sphere at the origin (from outside or inside), or −1.
float unit_sphere_hit(const Ray& ray) {
  const float b = dot(ray.origin, ray.direction), c = dot(ray.origin, ray.origin) - 1.0f;
  const float discriminant = b * b - c;
  if (discriminant < 0.0f) return -1.0f;
  const float root = std::sqrt(discriminant);
  if (-b - root > 0.0f) return -b - root;
  return -b + root > 0.0f ? -b + root : -1.0f;
}

// The furnace radiance along `ray` by the simplest estimator there is: follow BSDF samples (hero lane weight
// f·|cos|/pdf) until the path leaves the unit sphere, where the environment gives 1. Up to 64 bounces, as the
// scene's max_depth. Independent of the renderer's NEE, MIS, roulette, ray offsets and wavelength handling.
double reference_walk(const Material& material, Ray ray, std::mt19937_64& rng) {
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  double weight = 1.0;
  for (int depth = 0; depth <= 64; ++depth) {
    const float t = unit_sphere_hit(ray);
    if (t < 0.0f) return weight;
    if (depth == 64) return 0.0;
    const Vec3 p = ray.origin + ray.direction * t;
    const Frame frame = Frame::from_normal(normalize(p));
    const Bsdf bsdf = material.bsdf({}, fixed_wavelengths());
    const float u_lobe = uniform(rng), u1 = uniform(rng), u2 = uniform(rng);
    const auto s = bsdf.sample(frame.to_local(-ray.direction), u_lobe, {u1, u2});
    if (!s || !(s->pdf[0] > 0.0f)) return 0.0;
    weight *= double(s->hero_weight()[0]);
    ray.direction = frame.to_world(s->wi);
    // Step off the surface to the side the new direction leaves on.
    ray.origin = p + normalize(p) * (dot(ray.direction, p) > 0.0f ? 1e-4f : -1e-4f);
  }
  return 0.0;
}

// The reference's mean over `count` rays drawn by `ray_of`, with its standard error.
Estimate reference_radiance(const Scene& scene, const std::function<Ray(int)>& ray_of, int count) {
  std::mt19937_64 rng(5);
  std::vector<double> values;
  for (int i = 0; i < count; ++i) values.push_back(reference_walk(scene.materials[0], ray_of(i), rng));
  return estimate_of(values);
}

// |a − b| within kSigmas combined standard errors (plus float rounding for zero-variance estimators).
void check_same(const Estimate& a, const Estimate& b, const char* what) {
  CAPTURE(what);
  CAPTURE(a.mean);
  CAPTURE(a.standard_error);
  CAPTURE(b.mean);
  CAPTURE(b.standard_error);
  CHECK(std::abs(a.mean - b.mean) <= kSigmas * std::hypot(a.standard_error, b.standard_error) + 1e-5);
}

// Checks the film's Y over all pixels, and each lane of the integrator on furnace_ray(), against the expected
// radiance. `exact`: the material conserves energy exactly, so the expectation is 1; otherwise it is the reference
// walk's, which must itself be ≤ 1 (the BSDF may lose energy, never create it). Returns the film's estimate.
Estimate check_furnace(const nlohmann::json& material, bool exact) {
  const auto scene = scene_from_json(furnace(material));
  const RenderedFilm rendered = render_xyz(*scene, kSpp, 3);
  CHECK(rendered.film->sample_counts().discarded() == 0);
  const Estimate y = estimate_of(luminance_values(*rendered.film));
  const std::array<Estimate, 4> lanes = lane_radiance(*scene, furnace_ray, 4096);

  // The film's expectation: camera rays uniform over the image (box filter: uniform in every pixel).
  const Camera camera(scene->camera, 16, 16);
  std::mt19937_64 film_rng(8);
  std::uniform_real_distribution<float> uniform(0.0f, 16.0f);
  const auto film_ray = [&](int) { return camera.generate_ray(uniform(film_rng), uniform(film_rng), {0.5f, 0.5f}); };
  const Estimate film_expected = exact ? Estimate{1.0, 0.0} : reference_radiance(*scene, film_ray, 16384);
  const Estimate lane_expected = exact ? Estimate{1.0, 0.0} : reference_radiance(*scene, furnace_ray, 16384);
  check_same(y, film_expected, "film Y");
  for (int j = 0; j < 4; ++j) {
    CAPTURE(j);
    check_same(lanes[size_t(j)], lane_expected, "integrator lane");
  }
  if (!exact) {
    CHECK(film_expected.mean <= 1.0 + kSigmas * film_expected.standard_error);
    CHECK(lane_expected.mean <= 1.0 + kSigmas * lane_expected.standard_error);
  }
  return y;
}

}  // namespace

TEST_CASE("furnace: a white Lambertian sphere is invisible, on the film and in every lane") {
  check_furnace(nlohmann::json::parse(R"({"type": "diffuse", "reflectance": 1})"), true);
}

TEST_CASE("furnace: a smooth conductor with F = 1 is invisible, exactly in every lane") {
  // The issue asks for "a conductor with k = 0 and n = 1": that is vacuum, whose Fresnel reflectance is
  // ((n−1)² + k²)/((n+1)² + k²) = 0 at normal incidence, so it reflects nothing (a black sphere, not a furnace
  // test). A perfect mirror needs |n + ik| → ∞: n = 1, k = 1e4 gives R = 1 − 4n/((n+1)² + k²) = 1 − 4e-8.
  check_furnace(nlohmann::json::parse(R"({"type": "conductor", "n": 1, "k": 10000})"), true);
}

TEST_CASE("furnace: a smooth dielectric sphere of index 1.5 is invisible") {
  // R + T = 1 at every interface (radiance scaled by 1/η² in and η² out), so every escaping path carries 1; paths
  // still inside after 64 bounces (total internal reflection cannot trap light in a sphere) are negligible.
  check_furnace(nlohmann::json::parse(R"({"type": "dielectric", "ior": 1.5})"), true);
}

TEST_CASE("furnace: a thin BK7 sheet shaped as a sphere is invisible: R + T = 1, straight through") {
  // Through the JSON type, the loader and the integrator: a transmissive delta BSDF that changes no medium.
  check_furnace(nlohmann::json::parse(R"({"type": "thin_dielectric", "glass": "bk7"})"), true);
}

TEST_CASE("furnace: a diffuse transmitter with R + T = 1 is invisible, and pbrt's scaled-up one is normalised to 1") {
  // Albedo R + T = 1 on both faces: every path escapes with weight 1 (light entering bounces inside until it
  // is transmitted out). scale 2 on R = 0.3, T = 0.4 would scatter 1.4: the material divides by R + T.
  check_furnace(nlohmann::json::parse(R"({"type": "diffuse_transmission", "reflectance": 0.3, "transmittance": 0.7})"), true);
  check_furnace(nlohmann::json::parse(R"({"type": "diffuse_transmission", "reflectance": 0.3, "transmittance": 0.4, "scale": 2})"), true);
}

TEST_CASE("furnace: a white hair material (σa = 0) on a sphere is invisible, whatever its roughness and tilt") {
  // Σ Ap = 1 for every wo and h, so every path escapes with weight 1. On a sphere the fibre runs along ∂p/∂u
  // (the parallels) and h = 2v − 1 sweeps the latitudes: every fibre geometry is met, through both the
  // reflection and the transmission lobes (the path crosses the sphere through TT).
  check_furnace(nlohmann::json::parse(R"({"type": "hair", "sigma_a": 0})"), true);
  check_furnace(nlohmann::json::parse(R"({"type": "hair", "sigma_a": 0, "beta_m": 0.1, "beta_n": 0.9, "alpha": 10})"), true);
}

TEST_CASE("furnace: nearly smooth rough conductor and dielectric (roughness 0.1, alpha 0.01) are invisible within the MC bound") {
  // At α = 0.01 the single-scattering loss is far below the ≈0.5 % error bars (it vanishes as α → 0, Kulla &
  // Conty 2017; bsdf_energy_test bounds it below 1 % already at α = 0.05), so the expectation 1 is used as is.
  check_furnace(nlohmann::json::parse(R"({"type": "conductor", "n": 1, "k": 10000, "roughness": 0.1})"), true);
  check_furnace(nlohmann::json::parse(R"({"type": "dielectric", "ior": 1.5, "roughness": 0.1})"), true);
}

TEST_CASE("furnace: rough conductor and dielectric (roughness 0.3, alpha 0.09) render their BSDF's own energy loss") {
  // Measured with this seed: the film sees 1.3 % less than 1 for the conductor (F = 1) and 3 % less for the
  // dielectric sphere: the multiple-scattering energy missing from single-scattering GGX (larger at the
  // sphere's grazing rim; the dielectric loses it at every one of its ≥ 2 interface crossings). The renderer
  // must reproduce exactly that loss: the reference walk's value, not 1.
  const Estimate conductor =
      check_furnace(nlohmann::json::parse(R"({"type": "conductor", "n": 1, "k": 10000, "roughness": 0.3})"), false);
  const Estimate dielectric =
      check_furnace(nlohmann::json::parse(R"({"type": "dielectric", "ior": 1.5, "roughness": 0.3})"), false);
  // The loss is real (detectable), and small: below 5 % for both at α = 0.09.
  CHECK(conductor.mean < 1.0 - kSigmas * conductor.standard_error);
  CHECK(conductor.mean > 0.95);
  CHECK(dielectric.mean > 0.95);
}
