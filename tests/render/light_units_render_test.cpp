// Photometric lights measured in renders: what the scene asks for (lm, cd, lx, nt, EV) is what the meter and the
// camera read. Every tolerance is five standard errors of the Monte Carlo estimate (a false alarm below 1e-6 under
// the normal approximation), and each test also checks that the standard error is small enough to mean something.
// The conversions use CIE 15's 1 nm rectangle sum of S·V while the renderer's estimators converge to the exact
// integral of the piecewise-linear tables; for these smooth spectra the two differ by < 1e-5, far below the noise.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <memory>
#include <numbers>

#include "meter_reading_check.h"
#include "input_error_check.h"
#include "test_image_files.h"
#include "render/film/film.h"
#include "render/reports/light_meter.h"
#include "render/film/pixel_filter.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/photometry/emitter_photometry.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace light_units_render_test {

using rimu::test::kPi;
double cos_deg(double d) { return std::cos(d * kPi / 180.0); }

// A scene with the given lights and shapes, a camera at `from` looking at the origin, and a grey and a black material.
json scene_with(json lights, json shapes = json::array(), std::vector<float> from = {0.0f, 0.5f, 3.0f}) {
  return json{{"camera", {{"from", from}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 20}}},
              {"integrator", {{"max_depth", 2}}},
              {"materials",
               {{"half", {{"type", "diffuse"}, {"reflectance", 0.5}}}, {"black", {{"type", "diffuse"}, {"reflectance", 0.0}}}}},
              {"lights", std::move(lights)},
              {"shapes", std::move(shapes)}};
}

std::unique_ptr<Scene> load(const json& document) {
  return load_scene(document, "test scene", std::filesystem::current_path(), test::library());
}

MeterReading meter(const Scene& scene, Vec3 position, Vec3 normal, int samples = 4000) {
  return measure_illuminance_lx(scene.transport_view(), position, normal, test::library().photopic_v(), samples, 7);
}

// The scene's camera image, 12 x 12 pixels at `spp`, box filter, one thread.
std::unique_ptr<Film> render_12x12(const Scene& scene, int spp) {
  auto film = std::make_unique<Film>(FilmOptions{12, 12, std::nullopt, 0}, SpectralResponse::cie_xyz(test::library()));
  RenderOptions options;
  options.samples_per_pixel = spp;
  options.threads = 1;
  render(scene.transport_view(), scene.settings.integrator, Camera(scene.camera, 12, 12), PixelFilter::box(), *film,
         options);
  return film;
}

// Renders a 12x12 image at `spp` and reads the luminance over all of it.
MeterReading camera_luminance(const Scene& scene, int spp = 8) {
  const auto film = render_12x12(scene, spp);
  return measure_luminance_nt(*film, film->pixel_bounds());
}

using test::check_reading;

json light_quad(json emission, float half_size, bool two_sided = false) {
  // A square in the plane z = 0, facing +z, of side 2·half_size (before a transform that doubles it).
  return json{{"type", "quad"},
              {"vertices", {{-half_size, -half_size, 0}, {half_size, -half_size, 0}, {half_size, half_size, 0}, {-half_size, half_size, 0}}},
              {"material", "black"},
              {"emission", std::move(emission)},
              {"two_sided", two_sided},
              {"transform", {{{"scale", 2.0}}}}};
}

TEST_CASE("a 1000 lm point light at 2 m gives 1000/(16π) lx on a facing sensor") {
  const auto scene = load(scene_with(json::array(
      {{{"type", "point"}, {"position", {0, 0, 2}}, {"spectrum", {{"blackbody", 2856}}}, {"luminous_power_lm", 1000}}})));
  check_reading(meter(*scene, {0, 0, 0}, {0, 0, 1}), 1000.0 / (16.0 * kPi));
  SUBCASE("the same lamp given in candela") {
    const auto cd = load(scene_with(json::array({{{"type", "point"}, {"position", {0, 0, 2}},
                                                  {"spectrum", {{"blackbody", 2856}}},
                                                  {"luminous_intensity_cd", 1000.0 / (4.0 * kPi)}}})));
    check_reading(meter(*cd, {0, 0, 0}, {0, 0, 1}), 1000.0 / (16.0 * kPi));
  }
}

TEST_CASE("a 10000 lx sun on a Lambertian plane of albedo 0.5 has luminance 5000/π nt in the camera") {
  // L = ρ E / π for a Lambertian reflector under irradiance E at normal incidence.
  const auto scene = load(scene_with(
      json::array({{{"type", "distant"}, {"direction", {0, 0, 1}}, {"spectrum", {{"daylight", 5500}}}, {"illuminance_lx", 10000}}}),
      json::array({{{"type", "quad"}, {"vertices", {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}}}, {"material", "half"}}})));
  check_reading(meter(*scene, {0, 0, 0.001f}, {0, 0, 1}), 10000.0);
  check_reading(camera_luminance(*scene), 5000.0 / kPi);
}

TEST_CASE("a spot light's lux on and off its axis follow the chosen power convention") {
  // 800 lm, cone 40°, full intensity to 30° (half-angles 20° and 15°), 3 m above the sensor.
  const double cone_sr = 2.0 * kPi * (1.0 - 0.5 * (cos_deg(15.0) + cos_deg(20.0)));
  for (const char* convention : {"cone", "point"}) {
    CAPTURE(convention);
    const auto scene = load(scene_with(json::array(
        {{{"type", "spot"}, {"position", {0, 0, 3}}, {"direction", {0, 0, -1}}, {"cone_angle_deg", 40},
          {"falloff_start_deg", 30}, {"spectrum", {{"blackbody", 3000}}}, {"luminous_power_lm", 800},
          {"power_convention", convention}}})));
    const double intensity_cd = 800.0 / (std::string(convention) == "cone" ? cone_sr : 4.0 * kPi);
    check_reading(meter(*scene, {0, 0, 0}, {0, 0, 1}), intensity_cd / 9.0);
    // 17.5° off the axis, 3 m away, facing the lamp: E = I s(θ)/d².
    const double t = (cos_deg(17.5) - cos_deg(20.0)) / (cos_deg(15.0) - cos_deg(20.0));
    const Vec3 p{0.0f, float(3.0 * std::sin(17.5 * kPi / 180.0)), float(3.0 - 3.0 * cos_deg(17.5))};
    const Vec3 to_light = normalize(Vec3{0, 0, 3} - p);
    check_reading(meter(*scene, p, to_light), intensity_cd * t * t * (3.0 - 2.0 * t) / 9.0);
  }
}

TEST_CASE("recolouring an 800 lm light from 2700 K to 6500 K keeps its lux and changes its watts") {
  auto lamp = [](double cct_k) {
    return load(scene_with(json::array(
        {{{"type", "point"}, {"position", {0, 0, 2}}, {"spectrum", {{"blackbody", cct_k}}}, {"luminous_power_lm", 800}}})));
  };
  const auto warm = lamp(2700), cool = lamp(6500);
  const MeterReading a = meter(*warm, {0, 0, 0}, {0, 0, 1}), b = meter(*cool, {0, 0, 0}, {0, 0, 1});
  check_reading(a, 800.0 / (16.0 * kPi));
  check_reading(b, 800.0 / (16.0 * kPi));
  // The radiant power is 800/K(T) W: the efficacies of the two shapes (computed independently here).
  const auto efficacy = [](double t) {
    return shape_integrals(BlackbodySpectrum(t, BlackbodySpectrum::Scale::peak_one), test::library().photopic_v())
        .efficacy_lm_W();
  };
  CHECK(warm->lights[0]->total_power_w(1.0) == doctest::Approx(800.0 / efficacy(2700)).epsilon(1e-6));
  CHECK(cool->lights[0]->total_power_w(1.0) == doctest::Approx(800.0 / efficacy(6500)).epsilon(1e-6));
  CHECK(std::abs(warm->lights[0]->total_power_w(1.0) / cool->lights[0]->total_power_w(1.0) - 1.0) > 0.2);

  SUBCASE("keep radiometric keeps the watts of the reference colour instead") {
    const auto kept = load(scene_with(json::array(
        {{{"type", "point"}, {"position", {0, 0, 2}}, {"spectrum", {{"blackbody", 6500}}}, {"luminous_power_lm", 800},
          {"keep", "radiometric"}, {"reference_spectrum", {{"blackbody", 2700}}}}})));
    CHECK(kept->lights[0]->total_power_w(1.0) == doctest::Approx(800.0 / efficacy(2700)).epsilon(1e-6));
    check_reading(meter(*kept, {0, 0, 0}, {0, 0, 1}), 800.0 / (16.0 * kPi) * efficacy(6500) / efficacy(2700));
  }
}

TEST_CASE("area lights: lumens over the area after the transform, one- and two-sided, seen by the camera") {
  // A 0.5 m square scaled by 2: 1 m². One-sided: L = Φ/(πA) = 1000/π nt; two-sided: half that. The camera at z = 3
  // looks at its front and sees only the emitter (fov 20° covers 1.06 m at 3 m: the 1 m square fills the middle).
  for (bool two_sided : {false, true}) {
    CAPTURE(two_sided);
    const auto scene = load(scene_with(
        json::array(),
        json::array({light_quad({{"spectrum", {{"illuminant", "D65"}}}, {"luminous_power_lm", 1000}}, 0.25f, two_sided)}),
        {0, 0, 3}));
    const auto film = render_12x12(*scene, 4);
    check_reading(measure_luminance_nt(*film, PixelBounds{3, 3, 9, 9}), 1000.0 / kPi / (two_sided ? 2.0 : 1.0));
    CHECK(scene->lights[0]->total_power_w(1.0) ==
          doctest::Approx(1000.0 / shape_integrals(*test::library().illuminant("D65"), test::library().photopic_v())
                                       .efficacy_lm_W()).epsilon(1e-6));
  }
}

TEST_CASE("an emission image's white_luminance_nt: a white pixel seen by the camera has that luminance") {
  // A 2 × 1 image, white | 50 % grey (linear), on the same 1 m² square: the camera reads 300 nt over the white half
  // and 150 nt over the grey one (the columns away from the bilinear blend between the pixel centres), and the same
  // with "scale" 300 / 72 983 film units. Both keys at once: an error at "scale".
  const std::filesystem::path image = test::write_pfm("white_luminance", 2, 1, {1, 1, 1, 0.5f, 0.5f, 0.5f});
  for (const json& emission : {json{{"image", image.string()}, {"white_luminance_nt", 300}},
                              json{{"image", image.string()}, {"scale", 300.0 / 72983.0}}}) {
    CAPTURE(emission.dump());
    json quad = light_quad(emission, 0.25f);
    quad["uvs"] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // without, each triangle's uvs are its barycentrics
    const auto scene = load(scene_with(json::array(), json::array({quad}), {0, 0, 3}));
    const auto film = render_12x12(*scene, 8);
    // u grows along +x, which the camera at +z looking at −z has on its right: the white pixel (u < ¼ unblended,
    // x < −0.25 m) fills image columns 1-2, the grey (u > ¾) columns 9-10 (0.088 m per column at 3 m).
    const MeterReading white = measure_luminance_nt(*film, PixelBounds{1, 3, 3, 9});
    const MeterReading grey = measure_luminance_nt(*film, PixelBounds{9, 3, 11, 9});
    // Wavelength sampling is the only noise; 1e-5 covers 72 983's rounding (K_m ∫ȳ dλ = 72 983.3).
    CHECK(white.value == doctest::Approx(300.0).epsilon(4.5 * white.standard_error / 300.0 + 1e-5));
    CHECK(grey.value == doctest::Approx(150.0).epsilon(4.5 * grey.standard_error / 150.0 + 1e-5));
  }
  const json both = {{"image", image.string()}, {"white_luminance_nt", 300}, {"scale", 1}};
  test::input_error([&] { load(scene_with(json::array(), json::array({light_quad(both, 0.25f)}))); },
                    {"/shapes/0/emission/scale", "white_luminance_nt"});
  std::filesystem::remove(image);
}

TEST_CASE("a projector in candela and in lumens: the lux under each pixel, the right way round") {
  // A 2 × 2 image (linear greys: top row 1, 0.25; bottom row 0.5, 0) projected straight down from 2 m with a 60° field
  // and up = +z, so image right is world −x (axis × up): the top-left pixel lands at x > 0, z > 0. Under each pixel's
  // centre, at screen (±½, ±½)·tan 30° · 2 m, a meter facing up reads g · I_white · cos θ / d². With lumens, I_white
  // is Φ / Σ g·Ω over the pixels, Ω the solid angle of each quarter of the picture: by symmetry ¼ of the whole
  // picture's 4·atan(tan²30°/√(1 + 2 tan²30°)).
  const std::filesystem::path image = test::write_pfm("projector", 2, 2, {1, 1, 1, 0.25f, 0.25f, 0.25f, 0.5f, 0.5f, 0.5f, 0, 0, 0});
  const double t = std::tan(kPi / 6.0), quarter_sr = std::atan(t * t / std::sqrt(1.0 + 2.0 * t * t));
  const double greys[2][2] = {{1.0, 0.25}, {0.5, 0.0}};  // [row][column]
  for (const bool lumens : {false, true}) {
    CAPTURE(lumens);
    json projector = {{"type", "projection"}, {"position", {0, 2, 0}}, {"direction", {0, -1, 0}}, {"up", {0, 0, 1}},
                      {"fov_deg", 60}, {"image", image.string()}};
    if (lumens) projector["luminous_power_lm"] = 500;
    else projector["white_intensity_cd"] = 800;
    const double white_cd = lumens ? 500.0 / ((1.0 + 0.25 + 0.5) * quarter_sr) : 800.0;
    const auto scene = load(scene_with(json::array({projector})));
    for (int row = 0; row < 2; ++row)
      for (int column = 0; column < 2; ++column) {
        CAPTURE(row);
        CAPTURE(column);
        // Screen (x, y) = (column − ½, ½ − row); world x = −x·tan·2, z = y·tan·2.
        const double x = -(column - 0.5) * t * 2.0, z = (0.5 - row) * t * 2.0, d2 = x * x + z * z + 4.0;
        const double expected = greys[row][column] * white_cd * (2.0 / std::sqrt(d2)) / d2;
        const MeterReading reading = meter(*scene, {float(x), 0, float(z)}, {0, 1, 0});
        if (expected == 0.0) CHECK(reading.value == 0.0);
        else check_reading(reading, expected);
      }
  }
  std::filesystem::remove(image);
}

TEST_CASE("environment light in nits and in EV at ISO 100") {
  // Seen directly, a constant environment's luminance is the authored one; EV 10 is 0.125·2^10 = 128 nt (K = 12.5).
  const auto nits = load(scene_with(json::array({{{"type", "environment"}, {"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", 1000}}})));
  check_reading(camera_luminance(*nits, 2), 1000.0);
  const auto ev = load(scene_with(json::array({{{"type", "environment"}, {"spectrum", {{"illuminant", "D65"}}}, {"ev100", 10}}})));
  check_reading(camera_luminance(*ev, 2), 128.0);
}

TEST_CASE("photometric light keys: errors name the key and the units that apply") {
  auto fails_with = [](json light, const std::string& message) {
    CAPTURE(message);
    CHECK_THROWS_WITH_AS(load(scene_with(json::array({std::move(light)}))), doctest::Contains(message.c_str()), InputError);
  };
  fails_with({{"type", "point"}, {"position", {0, 0, 1}}, {"spectrum", 1.0}, {"illuminance_lx", 100}},
             "/lights/0/illuminance_lx: a point light cannot be given in lx; use lm or W");
  fails_with({{"type", "point"}, {"position", {0, 0, 1}}, {"spectrum", 1.0}, {"luminous_power_lm", 100}, {"luminous_intensity_cd", 5}},
             "takes one amount");
  fails_with({{"type", "point"}, {"position", {0, 0, 1}}, {"luminous_power_lm", 100}}, "needs 'spectrum'");
  fails_with({{"type", "point"}, {"position", {0, 0, 1}}, {"spectrum", 1.0}, {"luminous_power_lm", -5}}, "/lights/0/luminous_power_lm");
  fails_with({{"type", "point"}, {"position", {0, 0, 1}}, {"spectrum", 1.0}, {"intensity", 1.0}, {"luminous_power_lm", 5}},
             "give either 'intensity'");
  fails_with({{"type", "point"}, {"position", {0, 0, 1}}, {"spectrum", 0.0}, {"luminous_power_lm", 5}}, "/lights/0/spectrum");
  fails_with({{"type", "distant"}, {"direction", {0, 0, 1}}, {"spectrum", 1.0}, {"illuminance_lx", 5}, {"keep", "radiometric"}},
             "needs 'reference_spectrum'");
}

TEST_CASE("the light meter's standard error is honest: over 100 seeds its errors over it spread like t(15)") {
  // A 1000 lm, 2856 K point light 2 m above the meter: the only randomness is the hero wavelengths, stratified within
  // each of the reading's 16 independent batches (replicates_for(256)), so (reading − exact)/SE has a t distribution
  // of 15 degrees of freedom: E[z²] = 15/13 = 1.154, Var[z²] = 3.39, so the mean of 100 z² has standard deviation
  // 0.18; the bounds are ±4 of it. The textbook s/√n over the 256 stratified samples, used before, overstated this
  // error 34-fold (mean z² 0.00086 here).
  const auto scene = load(scene_with(json::array(
      {{{"type", "point"}, {"position", {0, 0, 2}}, {"spectrum", {{"blackbody", 2856}}}, {"luminous_power_lm", 1000}}})));
  const double exact = 1000.0 / (16.0 * kPi);
  double sum_z2 = 0.0;
  constexpr int kSeeds = 100;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const MeterReading r =
        measure_illuminance_lx(scene->transport_view(), {0, 0, 0}, {0, 0, 1}, test::library().photopic_v(), 256, uint64_t(seed));
    REQUIRE(r.standard_error > 0.0);
    sum_z2 += (r.value - exact) * (r.value - exact) / (r.standard_error * r.standard_error);
  }
  const double mean_z2 = sum_z2 / kSeeds;
  MESSAGE("light meter: mean z² over " << kSeeds << " seeds " << mean_z2 << " (t(15): 1.154)");
  CHECK(mean_z2 > 1.154 - 4 * 0.18);
  CHECK(mean_z2 < 1.154 + 4 * 0.18);
}

}  // namespace light_units_render_test
