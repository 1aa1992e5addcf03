// Glazing (docs/transport.md, "Glazing: shadow rays through panes"): shadow rays pass thin dielectrics weighted by
// their straight-through transmittance, and the MIS of paths through panes stays exact.
//
// The direct-light checks render a floor under horizontal panes lit by a delta sun (max_depth 1: only next-event
// estimation can see the sun, and every lane's estimate is deterministic), so each lane must equal the closed form
// ρ/π · E cos θ · ∏ T(θ, λ) to float precision. The MIS check compares the default estimator with BSDF sampling
// alone on a small glazed room (pixel means within kSigmas standard errors).
#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <fstream>

#include "integration_support.h"
#include "render/reports/light_meter.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "transport/integrators/shadow_passage.h"
#include "test_support.h"

using namespace rimu;
using namespace rimu::test;
using nlohmann::json;

namespace {

using rimu::test::kPi;
constexpr double kSunTiltDeg = 40.0;
constexpr double kFloorReflectance = 0.5;

// The Fresnel reflectances r_s², r_p² of one face (air → glass of index n) at incidence cos θ.
std::pair<double, double> fresnel_sp(double cos_i, double n) {
  const double sin2_t = (1.0 - cos_i * cos_i) / (n * n);
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double rs = (cos_i - n * cos_t) / (cos_i + n * cos_t), rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  return {rs * rs, rp * rp};
}

// A thin sheet's straight-through transmittance for unpolarised light: T₀²τ/(1 − R₀²τ²) for each polarisation
// (R₀ = r_s² or r_p², T₀ = 1 − R₀), averaged; τ = τₙ^(1/cos θt) (τₙ = 1: clear glass).
double sheet_transmittance(double cos_i, double n, double tau_n = 1.0) {
  const double cos_t = std::sqrt(1.0 - (1.0 - cos_i * cos_i) / (n * n));
  const double tau = std::pow(tau_n, 1.0 / cos_t);
  const auto [rs, rp] = fresnel_sp(cos_i, n);
  const auto series = [&](double r0) { return (1.0 - r0) * (1.0 - r0) * tau / (1.0 - r0 * r0 * tau * tau); };
  return 0.5 * (series(rs) + series(rp));
}

// A 100 m floor at y = 0, `panes` (materials) at y = 1, 1.2, ..., and a delta sun 40° from the zenith with E = 1.
json sun_over_panes(const std::vector<json>& panes) {
  const double tilt = kSunTiltDeg * kPi / 180.0;
  json scene = json::parse(R"({
    "camera": {"from": [0, 0.5, -2], "to": [0, 0, 0], "vertical_fov_deg": 30},
    "film": {"resolution": [8, 8], "filter": {"type": "box"}},
    "integrator": {"max_depth": 1},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-50, 0, 50], [50, 0, 50], [50, 0, -50], [-50, 0, -50]]}]
  })");
  scene["lights"] = json::array({{{"type", "distant"}, {"direction", {std::sin(tilt), std::cos(tilt), 0.0}}, {"irradiance", 1.0}}});
  for (size_t i = 0; i < panes.size(); ++i) {
    const std::string name = "pane" + std::to_string(i);
    scene["materials"][name] = panes[i];
    const double y = 1.0 + 0.2 * double(i);
    scene["shapes"].push_back({{"type", "quad"}, {"material", name},
                               {"vertices", {{-50, y, -50}, {50, y, -50}, {50, y, 50}, {-50, y, 50}}}});
  }
  return scene;
}

// Each lane's radiance of the floor seen from below the panes (16 rays), and the direct-light closed form's factor.
std::array<Estimate, 4> floor_radiance(const json& document) {
  const auto scene = scene_from_json(document);
  return lane_radiance(*scene, [](int i) { return ray_between({0.1f * float(i), 0.5f, 0}, {0.1f * float(i), 0, 0.3f}); }, 16);
}

double unshaded_floor_radiance() { return kFloorReflectance / kPi * std::cos(kSunTiltDeg * kPi / 180.0); }

}  // namespace

TEST_CASE("glazing: a shadow ray through two clear panes carries the product of their transmittances") {
  const json clear = {{"type", "thin_dielectric"}, {"ior", 1.5}};
  const double cos_i = std::cos(kSunTiltDeg * kPi / 180.0);
  const double t = sheet_transmittance(cos_i, 1.5);
  // Lossless: each polarisation's T is (1 − R₀)/(1 + R₀).
  const auto [rs, rp] = fresnel_sp(cos_i, 1.5);
  CHECK(t == doctest::Approx(0.5 * ((1.0 - rs) / (1.0 + rs) + (1.0 - rp) / (1.0 + rp))));
  const std::array<Estimate, 4> one = floor_radiance(sun_over_panes({clear}));
  const std::array<Estimate, 4> two = floor_radiance(sun_over_panes({clear, clear}));
  for (int j = 0; j < 4; ++j) {
    CAPTURE(j);
    CHECK(one[size_t(j)].standard_error < 1e-6 * one[size_t(j)].mean);  // deterministic: a delta sun, one light
    CHECK(one[size_t(j)].mean == doctest::Approx(unshaded_floor_radiance() * t).epsilon(1e-5));
    CHECK(two[size_t(j)].mean == doctest::Approx(unshaded_floor_radiance() * t * t).epsilon(1e-5));
  }
}

TEST_CASE("glazing: a tinted pane transmits the closed form at each wavelength") {
  // τₙ(λ) at the four fixed wavelengths (400, 500, 600, 700 nm) of lane_radiance: a green glass.
  const std::array<double, 4> tau_n = {0.2, 0.9, 0.5, 0.1};
  const json green = {{"type", "thin_dielectric"}, {"ior", 1.5},
                      {"transmittance", {{"wavelengths_nm", {400, 500, 600, 700}}, {"values", tau_n}}}};
  const std::array<Estimate, 4> tinted = floor_radiance(sun_over_panes({green}));
  const double cos_i = std::cos(kSunTiltDeg * kPi / 180.0);
  for (int j = 0; j < 4; ++j) {
    CAPTURE(j);
    CHECK(tinted[size_t(j)].mean ==
          doctest::Approx(unshaded_floor_radiance() * sheet_transmittance(cos_i, 1.5, tau_n[size_t(j)])).epsilon(1e-5));
  }
}

TEST_CASE("glazing: refracting glass still blocks shadow rays, alpha cut-outs pass where alpha is 0") {
  const double open = unshaded_floor_radiance();
  const std::array<Estimate, 4> refracting = floor_radiance(sun_over_panes({{{"type", "dielectric"}, {"ior", 1.5}}}));
  const std::array<Estimate, 4> rough = floor_radiance(sun_over_panes({{{"type", "dielectric"}, {"ior", 1.5}, {"roughness", 0.2}}}));
  for (int j = 0; j < 4; ++j) {
    CHECK(refracting[size_t(j)].mean == 0.0);
    CHECK(rough[size_t(j)].mean == 0.0);
  }
  json holes = sun_over_panes({{{"type", "diffuse"}, {"reflectance", 0.5}}});
  holes["shapes"][1]["alpha"] = 0.0;
  json solid = holes;
  solid["shapes"][1]["alpha"] = 1.0;
  const std::array<Estimate, 4> through = floor_radiance(holes), blocked = floor_radiance(solid);
  for (int j = 0; j < 4; ++j) {
    CHECK(through[size_t(j)].mean == doctest::Approx(open).epsilon(1e-5));
    CHECK(blocked[size_t(j)].mean == 0.0);
  }
}

TEST_CASE("glazing: more than kMaxShadowPassages panes block the shadow ray") {
  const json clear = {{"type", "thin_dielectric"}, {"ior", 1.5}};
  const std::array<Estimate, 4> at_cap = floor_radiance(sun_over_panes(std::vector<json>(size_t(kMaxShadowPassages), clear)));
  const std::array<Estimate, 4> beyond = floor_radiance(sun_over_panes(std::vector<json>(size_t(kMaxShadowPassages) + 1, clear)));
  CHECK(at_cap[0].mean > 0.0);
  CHECK(beyond[0].mean == 0.0);
}

namespace {

// A 2 m box room, its +x wall open on a 1 m window glazed with two clear panes; outside, a 3 m emissive wall and a
// sky through the window as a portal. Camera inside. `medium`: fill the world with a thin absorbing medium, so that
// the volumetric integrator renders it.
json glazed_box(bool medium) {
  json scene = json::parse(R"({
    "camera": {"from": [0.3, 1.0, 1.0], "to": [2, 0.6, 1.0], "vertical_fov_deg": 80},
    "film": {"resolution": [24, 24], "filter": {"type": "box"}},
    "integrator": {"max_depth": 4},
    "materials": {"wall": {"type": "diffuse", "reflectance": 0.6}, "glass": {"type": "thin_dielectric", "ior": 1.5},
                  "black": {"type": "diffuse", "reflectance": 0}},
    "lights": [{"type": "environment", "radiance": 0.5, "portals": [[[2, 0.5, 0.5], [2, 0.5, 1.5], [2, 1.5, 1.5], [2, 1.5, 0.5]]]}],
    "shapes": [
      {"type": "quad", "material": "wall", "vertices": [[0, 0, 0], [2, 0, 0], [2, 0, 2], [0, 0, 2]]},
      {"type": "quad", "material": "wall", "vertices": [[0, 2, 0], [0, 2, 2], [2, 2, 2], [2, 2, 0]]},
      {"type": "quad", "material": "wall", "vertices": [[0, 0, 0], [0, 2, 0], [2, 2, 0], [2, 0, 0]]},
      {"type": "quad", "material": "wall", "vertices": [[0, 0, 2], [2, 0, 2], [2, 2, 2], [0, 2, 2]]},
      {"type": "quad", "material": "wall", "vertices": [[0, 0, 0], [0, 0, 2], [0, 2, 2], [0, 2, 0]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 0, 0], [2, 2, 0], [2, 2, 0.5], [2, 0, 0.5]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 0, 1.5], [2, 2, 1.5], [2, 2, 2], [2, 0, 2]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 0, 0.5], [2, 0.5, 0.5], [2, 0.5, 1.5], [2, 0, 1.5]]},
      {"type": "quad", "material": "wall", "vertices": [[2, 1.5, 0.5], [2, 2, 0.5], [2, 2, 1.5], [2, 1.5, 1.5]]},
      {"type": "quad", "material": "glass", "vertices": [[2, 0.5, 0.5], [2, 1.5, 0.5], [2, 1.5, 1.5], [2, 0.5, 1.5]]},
      {"type": "quad", "material": "glass", "vertices": [[2.02, 0.5, 0.5], [2.02, 1.5, 0.5], [2.02, 1.5, 1.5], [2.02, 0.5, 1.5]]},
      {"type": "quad", "material": "black", "emission": 2, "vertices": [[3, -0.5, -0.5], [3, -0.5, 2.5], [3, 2.5, 2.5], [3, 2.5, -0.5]]}
    ]
  })");
  if (medium)
    scene["media"] = {{"air", {{"type", "homogeneous"}, {"sigma_a", 0.05}, {"sigma_s", 0}, {"contains_camera", true}}}};
  return scene;
}

void check_matches_bsdf_only(bool medium) {
  json document = glazed_box(medium);
  const auto mis_scene = scene_from_json(document);
  document["integrator"]["direct_lighting"] = "bsdf_only";
  const auto reference_scene = scene_from_json(document);
  const std::vector<double> mis = luminance_values(*render_xyz(*mis_scene, 32, 3).film);
  const std::vector<double> reference = luminance_values(*render_xyz(*reference_scene, 128, 4).film);
  const Estimate difference = paired_difference(mis, reference);
  double image_mean = 0;
  for (double v : mis) image_mean += v / double(mis.size());
  CAPTURE(medium);
  CAPTURE(image_mean);
  CAPTURE(difference.mean);
  CAPTURE(difference.standard_error);
  CHECK(std::abs(difference.mean) <= kSigmas * difference.standard_error);
  CHECK(kSigmas * difference.standard_error < 0.05 * image_mean);  // the check resolves a 5 % bias
}

}  // namespace

TEST_CASE("glazing: a double-glazed room equals its BSDF-only reference (surfaces, and in a medium)") {
  check_matches_bsdf_only(false);
  check_matches_bsdf_only(true);
}

TEST_CASE("glazing: a sky seen only through refracting glass warns at load, through panes, or past a glass ball, not") {
  auto warns = [](const json& document) {
    const auto scene = scene_from_json(document);
    for (const std::string& w : scene->warnings)
      if (w.find("only through refracting glass") != std::string::npos) return true;
    return false;
  };
  json refracting = glazed_box(false);
  refracting["materials"]["glass"] = {{"type", "dielectric"}, {"ior", 1.5}};
  CHECK(warns(refracting));
  refracting["materials"]["glass"]["roughness"] = 0.3;
  CHECK(warns(refracting));
  CHECK_FALSE(warns(glazed_box(false)));
  // The daylit room with its panes made refracting: the sky through the window warns (a probe beside the window sees
  // a little sky past the panes' edges, which must not clear it).
  json room = json::parse(std::ifstream(library().root() / "scenes" / "interiors" / "daylit_room_glazed.json"));
  CHECK_FALSE(warns(room));
  room["materials"]["glass"] = {{"type", "dielectric"}, {"ior", 1.52}};
  CHECK(warns(room));
  // A glass ball in an open scene under the sky: most of the sky is reached directly.
  const json ball = json::parse(R"({
    "camera": {"from": [0, 1, -4], "to": [0, 0.5, 0]},
    "film": {"resolution": [8, 8]},
    "materials": {"floor": {"type": "diffuse", "reflectance": 0.5}, "glass": {"type": "dielectric", "ior": 1.5}},
    "lights": [{"type": "environment", "radiance": 1}, {"type": "distant", "direction": [0.3, 1, 0.2], "irradiance": 1, "angular_diameter_deg": 0.53}],
    "shapes": [{"type": "quad", "material": "floor", "vertices": [[-5, 0, 5], [5, 0, 5], [5, 0, -5], [-5, 0, -5]]},
               {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "glass"}]
  })");
  CHECK_FALSE(warns(ball));
}

TEST_CASE("glazing: the light meter reads through panes as the render does: the open value times T(theta)") {
  // The floor point under the panes, lit by the delta sun 40° from the zenith: without panes every sample reads
  // K_m Σ V(λ)·E cos θ / p(λ); behind a clear pane (T independent of λ) the same samples times T(40°), to float
  // precision (the same seed draws the same wavelengths).
  const auto read = [](const json& document) {
    const auto scene = scene_from_json(document);
    return measure_illuminance_lx(scene->transport_view(), {0, 0, 0}, {0, 1, 0}, library().photopic_v(), 256, 11);
  };
  const json clear = {{"type", "thin_dielectric"}, {"ior", 1.5}};
  const double cos_i = std::cos(kSunTiltDeg * kPi / 180.0);
  const MeterReading open = read(sun_over_panes({}));
  const MeterReading one = read(sun_over_panes({clear}));
  const MeterReading two = read(sun_over_panes({clear, clear}));
  CHECK(open.value > 0.0);
  CHECK(one.value == doctest::Approx(open.value * sheet_transmittance(cos_i, 1.5)).epsilon(1e-5));
  CHECK(two.value == doctest::Approx(open.value * std::pow(sheet_transmittance(cos_i, 1.5), 2)).epsilon(1e-5));

  // A tinted pane: T(λ) varies, so the reading is a Monte Carlo estimate over the wavelengths of
  // K_m ∫ V(λ) E cos θ T(θ, λ) dλ, checked against that integral (1 nm sums; τₙ linear between its points, constant
  // outside) within kSigmas standard errors, as the open reading against K_m E cos θ ∫ V dλ.
  const std::vector<double> nm = {400, 500, 600, 700}, tau_n = {0.2, 0.9, 0.5, 0.1};
  const json green = {{"type", "thin_dielectric"}, {"ior", 1.5},
                      {"transmittance", {{"wavelengths_nm", nm}, {"values", tau_n}}}};
  const MeterReading tinted = read(sun_over_panes({green}));
  double v_integral = 0.0, vt_integral = 0.0;
  for (double l = 360.0; l <= 830.0; l += 1.0) {
    double tau = tau_n.front();
    if (l >= nm.back()) tau = tau_n.back();
    else if (l > nm.front())
      for (size_t k = 0; k + 1 < nm.size(); ++k)
        if (l >= nm[k] && l <= nm[k + 1]) tau = tau_n[k] + (tau_n[k + 1] - tau_n[k]) * (l - nm[k]) / (nm[k + 1] - nm[k]);
    const double v = library().photopic_v().value(l);
    v_integral += v;
    vt_integral += v * sheet_transmittance(cos_i, 1.5, tau);
  }
  // E = 1 W/(m²·nm) normal to the sun.
  const double expected = kMaxLuminousEfficacy_lm_W * cos_i * vt_integral;
  CHECK(std::abs(open.value - kMaxLuminousEfficacy_lm_W * cos_i * v_integral) <= kSigmas * open.standard_error);
  CAPTURE(tinted.value);
  CAPTURE(tinted.standard_error);
  CAPTURE(expected);
  CHECK(std::abs(tinted.value - expected) <= kSigmas * tinted.standard_error);
  CHECK(kSigmas * tinted.standard_error <= 0.05 * expected);
}
