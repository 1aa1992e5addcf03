// The independent and rgb wavelength modes (issue 7): finite images, unbiasedness against the hero estimator and an
// analytic furnace, and rgb transport's agreement with spectral transport where no spectral effect exists.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <vector>

#include "integration_support.h"
#include "render/scene/rgb_transport_inputs.h"
#include "render/scene/json_cursor.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "test_image_files.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu::test {
namespace {

// Renders into the film each mode needs: XYZ response curves, or rgb transport's sRGB matrix.
RenderedFilm render_mode(const Scene& scene, int spp, uint64_t seed) {
  const bool rgb = scene.settings.integrator.wavelengths == WavelengthMode::rgb;
  FilmOptions options{scene.settings.width, scene.settings.height, std::nullopt, 0};
  RenderedFilm out;
  out.film = std::make_unique<Film>(options, rgb ? SpectralResponse::rgb_transport(library())
                                                 : SpectralResponse::cie_xyz(library()));
  RenderOptions render_options;
  render_options.samples_per_pixel = spp;
  render_options.seed = seed;
  render_options.threads = 2;
  out.statistics = render(scene, filter_of(scene), *out.film, render_options);
  return out;
}

// A small closed room (grey floor, ceiling, left wall and sphere; the other walls as given) with a ceiling light.
nlohmann::json room(const std::string& mode, const nlohmann::json& emission, const nlohmann::json& wall_reflectance) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "camera": {"from": [0.5, 0.5, -1.2], "to": [0.5, 0.5, 0.5], "vertical_fov_deg": 45},
    "film": {"resolution": [24, 24], "filter": {"type": "box", "radius": 0.5}},
    "integrator": {"max_depth": 8, "seed": 1},
    "materials": {"light grey": {"type": "diffuse", "reflectance": 0.7}},
    "shapes": [
      {"type": "quad", "material": "light grey", "vertices": [[0,0,0],[1,0,0],[1,0,1],[0,0,1]]},
      {"type": "quad", "material": "light grey", "vertices": [[0,1,0],[0,1,1],[1,1,1],[1,1,0]]},
      {"type": "quad", "material": "walls", "vertices": [[1,0,0],[1,1,0],[1,1,1],[1,0,1]]},
      {"type": "quad", "material": "light grey", "vertices": [[0,0,0],[0,0,1],[0,1,1],[0,1,0]]},
      {"type": "quad", "material": "walls", "vertices": [[0,0,1],[1,0,1],[1,1,1],[0,1,1]]},
      {"type": "sphere", "material": "light grey", "center": [0.4, 0.2, 0.5], "radius": 0.2}
    ]})");
  s["materials"]["walls"] = {{"type", "diffuse"}, {"reflectance", wall_reflectance}};
  s["shapes"].push_back({{"type", "quad"}, {"material", "light grey"}, {"name", "light"}, {"emission", emission},
                         {"vertices", {{0.65, 0.999, 0.35}, {0.65, 0.999, 0.65}, {0.35, 0.999, 0.65}, {0.35, 0.999, 0.35}}}});
  s["integrator"]["wavelengths"] = mode;
  return s;
}

// A dispersive furnace: an N-SF11 glass sphere inside a uniform environment. A dielectric only redirects light
// (R + T = 1 at every interface), so every pixel's expected value is the environment's own film XYZ, whatever the
// dispersion: paths through the sphere must still average to it (up to the energy left inside after max_depth
// bounces, < 1e-6 of it at depth 100 since each internal bounce keeps at most the Fresnel reflectance).
nlohmann::json dispersive_furnace(const std::string& mode) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "vertical_fov_deg": 30},
    "film": {"resolution": [16, 16], "filter": {"type": "box", "radius": 0.5}},
    "integrator": {"max_depth": 100, "seed": 1},
    "materials": {"flint": {"type": "dielectric", "glass": "sf11"}},
    "lights": [{"type": "environment", "radiance": {"illuminant": "F11", "scale": 0.01}}],
    "shapes": [{"type": "sphere", "material": "flint", "center": [0, 0, 0], "radius": 0.7}]})");
  s["integrator"]["wavelengths"] = mode;
  return s;
}

}  // namespace

TEST_CASE("independent and rgb modes render finite, non-black images of a spectral scene") {
  // The Cornell box's measured (spectral) reflectances and light, at a tiny resolution.
  for (const char* mode : {"independent", "rgb"}) {
    CAPTURE(mode);
    nlohmann::json document = parse_json_file(default_scene_path(library()));
    document["integrator"]["wavelengths"] = mode;
    document["film"]["resolution"] = {16, 16};
    const auto scene = load_scene(document, "cornell.json", default_scene_path(library()).parent_path(), library());
    const RenderedFilm r = render_mode(*scene, 4, 1);
    CHECK(r.film->sample_counts().discarded() == 0);
    double y_sum = 0.0;
    for (int c = 0; c < 3; ++c)
      for (double v : channel_values(*r.film, c)) {
        REQUIRE(std::isfinite(v));
        if (c == 1) y_sum += v;
      }
    CHECK(y_sum > 0.0);
  }
}

TEST_CASE("independent mode is unbiased: dispersive furnace against its analytic value, and against hero mode") {
  // Expected: the environment's film XYZ, ∫ 0.01·F11(λ) c_k(λ) dλ with the film's normalised curves (1 nm sum; the
  // film integrates the same piecewise-linear curves exactly, a difference of < 1e-4 relative, far below the
  // statistical error bar).
  const SpectralResponse film = SpectralResponse::cie_xyz(library());
  const SpectrumPtr f11 = library().illuminant("F11");
  const auto hero = render_mode(*scene_from_json(dispersive_furnace("hero")), 16, 1);
  const auto independent = render_mode(*scene_from_json(dispersive_furnace("independent")), 16, 2);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const double expected =
        integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) { return 0.01 * f11->value(l) * film.value(c, l); });
    const Estimate e = estimate_of(channel_values(*independent.film, c));
    CHECK(std::fabs(e.mean - expected) <= kSigmas * e.standard_error + 1e-4 * expected);
    // The sphere's pixels do vary (dispersion), so the error bar is not zero and the check has power.
    CHECK(e.standard_error > 0.0);
    const Estimate d = paired_difference(channel_values(*independent.film, c), channel_values(*hero.film, c));
    CHECK(std::fabs(d.mean) <= kSigmas * d.standard_error + 1e-4 * expected);
  }
}

TEST_CASE("independent mode agrees with hero mode in a room with spectral reflectances") {
  const nlohmann::json red = {{"csv", "spectra/reflectances/colorchecker_classic_babelcolor_avg_10nm.csv"}, {"column", "red"}};
  const nlohmann::json f11 = {{"illuminant", "F11"}, {"scale", 0.2}};
  const auto hero = render_mode(*scene_from_json(room("hero", f11, red)), 16, 1);
  const auto independent = render_mode(*scene_from_json(room("independent", f11, red)), 16, 2);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const Estimate d = paired_difference(channel_values(*independent.film, c), channel_values(*hero.film, c));
    CHECK(std::fabs(d.mean) <= kSigmas * d.standard_error);
  }
}

TEST_CASE("rgb transport equals spectral transport on a grey-only scene under D65") {
  // Grey reflectances scale every wavelength alike and D65 is the sRGB white, so RGB (1,1,1)·k carries exactly the
  // light's film XYZ through every bounce: rgb and hero estimate the same image (only the noise differs).
  const nlohmann::json d65 = {{"illuminant", "D65"}, {"scale", 0.2}};
  const auto hero = render_mode(*scene_from_json(room("hero", d65, 0.4)), 16, 1);
  const auto rgb = render_mode(*scene_from_json(room("rgb", d65, 0.4)), 16, 2);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const Estimate d = paired_difference(channel_values(*rgb.film, c), channel_values(*hero.film, c));
    // 1e-3 relative: D65's tabulated white and the sRGB matrix's (0.3127, 0.3290) differ in the 4th decimal, and the
    // emission conversion sums on a 1 nm grid while the film integrates the curves exactly.
    CHECK(std::fabs(d.mean) <= kSigmas * d.standard_error + 1e-3 * mean_of(channel_values(*hero.film, c)));
  }
}

TEST_CASE("rgb transport inputs: the perfect diffuser is exactly white, IOR does not disperse") {
  const Rgb white = reflectance_linear_srgb(ConstantSpectrum(1.0), library());
  CHECK(white.r == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(white.g == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(white.b == doctest::Approx(1.0).epsilon(1e-12));
  // A saturated red reflectance (ColorChecker "red") stays red: its red channel dominates green and blue.
  const SpectrumPtr red = std::make_shared<TabulatedSpectrum>(TabulatedSpectrum::from_csv(
      library().table("spectra/reflectances/colorchecker_classic_babelcolor_avg_10nm.csv"), "red", Extrapolation::clamp));
  const Rgb r = reflectance_linear_srgb(*red, library());
  CHECK(r.r > 5.0 * r.g);
  CHECK(r.r > 5.0 * r.b);
  const SpectrumPtr glass = rgb_transport_form(std::make_shared<ConstantSpectrum>(1.5), SpectrumRole::ior, library());
  const SampledSpectrum lanes = glass->sample(rgb_transport_lanes());
  CHECK(lanes[0] == lanes[1]);
  CHECK(lanes[1] == lanes[2]);
}

}  // namespace rimu::test

namespace rimu::test {
namespace {

// The grey room above with a sphere of homogeneous medium (index-matched boundary) in front of the camera.
nlohmann::json foggy_room(const std::string& mode, const nlohmann::json& medium) {
  const nlohmann::json d65 = {{"illuminant", "D65"}, {"scale", 0.2}};
  nlohmann::json s = room(mode, d65, 0.4);
  s["materials"]["fog boundary"] = {{"type", "dielectric"}, {"ior", 1.0}};
  nlohmann::json m = medium;
  m["boundary_material"] = "fog boundary";
  m["index_matched"] = true;
  s["media"] = {{"fog", m}};
  s["shapes"].push_back({{"type", "sphere"}, {"material", "fog boundary"}, {"center", {0.6, 0.45, 0.45}}, {"radius", 0.3}});
  return s;
}

Rgb rgb_lanes_of(const Spectrum& s) {
  const SampledSpectrum lanes = s.sample(rgb_transport_lanes());
  return {lanes[0], lanes[1], lanes[2]};
}

}  // namespace

TEST_CASE("rgb transport of media: constant coefficients stay constant, Chiang inputs per channel, RGB refused") {
  const Rgb c = coefficient_linear_srgb(ConstantSpectrum(37.5), library());
  CHECK(c.r == doctest::Approx(37.5).epsilon(1e-12));
  CHECK(c.g == doctest::Approx(37.5).epsilon(1e-12));
  CHECK(c.b == doctest::Approx(37.5).epsilon(1e-12));
  // Unlike a reflectance, a coefficient is not clipped at 1 (and a saturated one keeps its hue).
  CHECK(coefficient_linear_srgb(ConstantSpectrum(1e4), library()).g == doctest::Approx(1e4).epsilon(1e-12));

  const auto constant = scene_from_json(foggy_room("rgb", {{"type", "homogeneous"}, {"sigma_a", 0.5}, {"sigma_s", 3.0}}));
  REQUIRE(constant->media.size() == 1);
  const HomogeneousMedium& h = *constant->media[0].homogeneous();
  const Rgb sa = rgb_lanes_of(*h.sigma_a()), ss = rgb_lanes_of(*h.sigma_s());
  CHECK(sa.r == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(sa.b == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(ss.g == doctest::Approx(3.0).epsilon(1e-6));

  // Chiang 2016 with RGB inputs given in linear sRGB: per channel σ_t = 1/d, σ_s = α(A)σ_t (their Eq. 2).
  const auto artist = scene_from_json(foggy_room("rgb", {{"type", "homogeneous"},
                                                         {"albedo", {{"rgb", {0.85, 0.55, 0.45}}}},
                                                         {"mean_free_path", {{"rgb", {1.0, 0.35, 0.2}}}},
                                                         {"mean_free_path_scale_m", 0.008}}));
  const HomogeneousMedium& a = *artist->media[0].homogeneous();
  const Rgb s = rgb_lanes_of(*a.sigma_s()), t_minus_s = rgb_lanes_of(*a.sigma_a());
  const double albedo[3] = {0.85, 0.55, 0.45}, mfp[3] = {0.008, 0.0028, 0.0016};
  const double scattering[3] = {s.r, s.g, s.b}, absorption[3] = {t_minus_s.r, t_minus_s.g, t_minus_s.b};
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    const double alpha = 1.0 - std::exp(-11.43 * albedo[k] + 15.38 * albedo[k] * albedo[k] - 13.91 * std::pow(albedo[k], 3));
    CHECK(scattering[k] == doctest::Approx(alpha / mfp[k]).epsilon(1e-6));
    CHECK(absorption[k] == doctest::Approx((1.0 - alpha) / mfp[k]).epsilon(1e-5));
  }
  // Spectral mode keeps its 1 nm tables (no RGB lanes): the same scene's σ_s differs between red and blue.
  const auto spectral = scene_from_json(foggy_room("hero", {{"type", "homogeneous"},
                                                            {"albedo", {{"rgb", {0.85, 0.55, 0.45}}}},
                                                            {"mean_free_path", {{"rgb", {1.0, 0.35, 0.2}}}},
                                                            {"mean_free_path_scale_m", 0.008}}));
  CHECK(spectral->media[0].homogeneous()->sigma_s()->value(650.0) <
        spectral->media[0].homogeneous()->sigma_s()->value(450.0));

  nlohmann::json named = foggy_room("rgb", {{"type", "homogeneous"}, {"sigma_a", 0.5}, {"sigma_s", {{"spectrum", "fog"}}}});
  named["spectra"] = {{"fog", {{"rgb", {1.0, 2.0, 3.0}}}}};
  CHECK_THROWS_WITH_AS(scene_from_json(named), doctest::Contains("give coefficients as spectra"), InputError);
}

TEST_CASE("rgb transport equals spectral transport in a grey medium under D65") {
  // A wavelength-independent medium in the grey room: as for surfaces, rgb (with its spectral-tracking flights) and
  // hero (spectral MIS flights) estimate the same image.
  const nlohmann::json fog = {{"type", "homogeneous"}, {"sigma_a", 0.8}, {"sigma_s", 4.0}, {"g", 0.3}};
  const auto hero = render_mode(*scene_from_json(foggy_room("hero", fog)), 32, 1);
  const auto rgb = render_mode(*scene_from_json(foggy_room("rgb", fog)), 32, 2);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const Estimate d = paired_difference(channel_values(*rgb.film, c), channel_values(*hero.film, c));
    // The 1e-3 relative allowance of the surface-only test above (D65 white vs the sRGB white, 1 nm sums).
    CHECK(std::fabs(d.mean) <= kSigmas * d.standard_error + 1e-3 * mean_of(channel_values(*hero.film, c)));
  }
}

}  // namespace rimu::test

namespace rimu::test {

TEST_CASE("the lights wavelength density renders the visible density's image (F11 room, hero and independent)") {
  // Only the noise may differ: every lane stays an unbiased estimate under any positive density.
  const nlohmann::json red = {{"csv", "spectra/reflectances/colorchecker_classic_babelcolor_avg_10nm.csv"}, {"column", "red"}};
  const nlohmann::json f11 = {{"illuminant", "F11"}, {"scale", 0.2}};
  for (const char* mode : {"hero", "independent"}) {
    CAPTURE(mode);
    nlohmann::json lights_room = room(mode, f11, red);
    lights_room["integrator"]["wavelength_density"] = "lights";
    const auto lights_scene = scene_from_json(lights_room);
    REQUIRE(lights_scene->wavelength_density);
    const auto visible = render_mode(*scene_from_json(room(mode, f11, red)), 16, 1);
    const auto lights = render_mode(*lights_scene, 16, 2);
    for (int c = 0; c < 3; ++c) {
      CAPTURE(c);
      const Estimate d = paired_difference(channel_values(*lights.film, c), channel_values(*visible.film, c));
      CHECK(std::fabs(d.mean) <= kSigmas * d.standard_error);
    }
  }
  // Rgb mode has fixed lanes: no density is built.
  nlohmann::json rgb_room = room("rgb", f11, red);
  rgb_room["integrator"]["wavelength_density"] = "lights";
  CHECK_FALSE(scene_from_json(rgb_room)->wavelength_density);
}

}  // namespace rimu::test

namespace rimu::test {

TEST_CASE("rgb transport of an environment image: pixels used as given, same image as spectral when grey") {
  // A 16×8 grey environment (linear sRGB 0.3, with one brighter row to exercise importance sampling) around a grey
  // sphere. Grey pixels upsample to the sRGB white (D65-shaped) in spectral mode, and are (c, c, c) in rgb mode:
  // both carry the same film XYZ, and a grey sphere keeps it, so the two modes estimate the same image.
  std::vector<float> pixels(16 * 8 * 3, 0.3f);
  for (int x = 0; x < 16; ++x)
    for (int c = 0; c < 3; ++c) pixels[size_t((2 * 16 + x) * 3 + c)] = 1.2f;
  const std::filesystem::path image = write_pfm("rgb_mode_environment", 16, 8, pixels);
  auto scene = [&](const std::string& mode) {
    nlohmann::json s = nlohmann::json::parse(R"({
      "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "vertical_fov_deg": 40},
      "film": {"resolution": [16, 16], "filter": {"type": "box", "radius": 0.5}},
      "integrator": {"max_depth": 4},
      "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
      "shapes": [{"type": "sphere", "material": "grey", "center": [0, 0, 0], "radius": 0.8}]})");
    s["lights"] = {{{"type", "environment"}, {"image", image.string()}, {"scale", 2.0}}};
    s["integrator"]["wavelengths"] = mode;
    return scene_from_json(s);
  };
  const auto rgb_scene = scene("rgb");
  // The rgb form returns the pixel itself (× scale), not an upsampled spectrum point-sampled at 612/549/465 nm.
  const Light& light = *rgb_scene->lights[0];
  const SampledSpectrum seen = light.radiance_escaped({0, 0, 1}, rgb_transport_lanes());
  CHECK(seen[0] == doctest::Approx(0.6f).epsilon(1e-6));
  CHECK(seen[2] == doctest::Approx(0.6f).epsilon(1e-6));
  const auto hero = render_mode(*scene("hero"), 32, 1);
  const auto rgb = render_mode(*rgb_scene, 32, 2);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const Estimate d = paired_difference(channel_values(*rgb.film, c), channel_values(*hero.film, c));
    // The 1e-3 relative allowance of the grey-room test (D65 white vs the sRGB white, 1 nm sums).
    CHECK(std::fabs(d.mean) <= kSigmas * d.standard_error + 1e-3 * mean_of(channel_values(*hero.film, c)));
  }
}

}  // namespace rimu::test
