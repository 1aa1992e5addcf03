// The physical camera: exposure pinned to the reflected-light meter equation (ISO 2720, K = 12.5), sunny-16 and a
// metered room rendered to similar mid-greys, and white balance in the film's own space.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "render/reports/light_meter.h"
#include "render/camera/physical_camera.h"
#include "render/film/pixel_filter.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/photometry/light_units.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

using rimu::test::kPi;

// An 18 % grey Lambertian plane lit by a sun of `lux` at normal incidence, seen at a slant.
std::unique_ptr<Scene> grey_card_scene(double lux) {
  const json document{
      {"camera", {{"from", {0.0, 1.0, 3.0}}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 20}}},
      {"integrator", {{"max_depth", 2}}},
      {"materials", {{"grey", {{"type", "diffuse"}, {"reflectance", 0.18}}}}},
      {"lights", json::array({{{"type", "distant"}, {"direction", {0, 0, 1}}, {"spectrum", {{"daylight", 5500}}},
                               {"illuminance_lx", lux}}})},
      {"shapes", json::array({{{"type", "quad"}, {"vertices", {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}}},
                               {"material", "grey"}}})}};
  return load_scene(document, "grey card", std::filesystem::current_path(), test::library());
}

// The exposed film value (Y × film_exposure_scale) of the grey card, averaged over a 12x12 render.
MeterReading exposed_grey(double lux, const PhysicalCameraSettings& camera) {
  const auto scene = grey_card_scene(lux);
  Film film(FilmOptions{12, 12, std::nullopt, 0}, SpectralResponse::cie_xyz(test::library()));
  RenderOptions options;
  options.samples_per_pixel = 8;
  options.threads = 1;
  render(scene->transport_view(), scene->settings.integrator, Camera(scene->camera, 12, 12), PixelFilter::box(), film,
         options);
  MeterReading r = measure_luminance_nt(film, film.pixel_bounds());
  const double per_nit = film_exposure_scale(camera, film.response()) / film.response().luminance_nits_per_unit_y();
  r.value *= per_nit;
  r.standard_error *= per_nit;
  return r;
}

}  // namespace

TEST_CASE("the meter equation: a surface at the metered luminance lands on mid-grey") {
  // ISO 2720: N²/t = L S / K, K = 12.5. Sunny 16 (f/16, 1/100 s, ISO 100): L_m = 12.5·256/(0.01·100) = 3200 nt,
  // EV = log2(25600) = 14.64. Exact arithmetic: tolerances are rounding.
  const PhysicalCameraSettings sunny16{100.0, 0.01, 16.0, 0.0};
  CHECK(metered_luminance_nt(sunny16) == doctest::Approx(3200.0).epsilon(1e-15));
  CHECK(exposure_value(sunny16) == doctest::Approx(std::log2(25600.0)).epsilon(1e-15));
  CHECK(imaging_ratio_per_nit(sunny16) * 3200.0 == doctest::Approx(kMeterMidGrey).epsilon(1e-15));
  // +1 EV of compensation doubles the film value; one stop more ISO does too.
  CHECK(imaging_ratio_per_nit({100.0, 0.01, 16.0, 1.0}) == doctest::Approx(2.0 * imaging_ratio_per_nit(sunny16)));
  CHECK(imaging_ratio_per_nit({200.0, 0.01, 16.0, 0.0}) == doctest::Approx(2.0 * imaging_ratio_per_nit(sunny16)));
  // The same luminance as EV at ISO 100 (light_units.h): EV100 14.64 ↔ 0.125·2^14.64 = 3200 nt.
  CHECK(luminance_nt_from_ev100(exposure_value(sunny16)) == doctest::Approx(3200.0).epsilon(1e-12));
  CHECK_THROWS_AS(metered_luminance_nt({0.0, 0.01, 16.0, 0.0}), InputError);
}

TEST_CASE("a 100000 lx sun at sunny 16 and a 100 lx room at metered settings land at similar mid-greys") {
  // Grey card ρ = 0.18: L = ρE/π. Film value v = 0.18 · L / L_m. Sun, sunny 16: L = 5729.6 nt, L_m = 3200 nt,
  // v = 0.3223. Room, 100 lx, f/2 at 1/10 s, ISO 100 (what an incident meter with C = 250 gives: N²/t = E S / C =
  // 40): L = 5.730 nt, L_m = 12.5·4/(0.1·100) = 5 nt, v = 0.2063. Render tolerances: 5 standard errors.
  const PhysicalCameraSettings sunny16{100.0, 0.01, 16.0, 0.0};
  const PhysicalCameraSettings room{100.0, 0.1, 2.0, 0.0};
  const MeterReading sun = exposed_grey(100000.0, sunny16);
  const MeterReading indoor = exposed_grey(100.0, room);
  const double sun_expected = 0.18 * (0.18 * 100000.0 / kPi) / 3200.0;
  const double room_expected = 0.18 * (0.18 * 100.0 / kPi) / 5.0;
  CAPTURE(sun.value);
  CAPTURE(indoor.value);
  CHECK(sun.standard_error < 0.01 * sun_expected);
  CHECK(std::abs(sun.value - sun_expected) <= 5.0 * sun.standard_error);
  CHECK(std::abs(indoor.value - room_expected) <= 5.0 * indoor.standard_error);
  // Both within one stop of 0.18, and within one stop of each other: the light differs by 1000× (10 stops).
  CHECK(std::abs(std::log2(sun.value / 0.18)) < 1.0);
  CHECK(std::abs(std::log2(indoor.value / 0.18)) < 1.0);
  CHECK(std::abs(std::log2(sun.value / indoor.value)) < 1.0);
}

TEST_CASE("white balance maps the chosen illuminant's white to D65 (XYZ) or to R = G = B (camera)") {
  // The CAT maps source white onto destination white exactly (chromatic_adaptation.h), so a white surface under a
  // 2700 K blackbody, white-balanced to 2700 K, has D65's chromaticity (CIE 15:2004 Table T.3: x 0.31272, y 0.32903
  // at 5 nm; the 1 nm sums here agree to ±2e-5).
  const BlackbodySpectrum tungsten(2700.0, BlackbodySpectrum::Scale::peak_one);
  const SpectralResponse xyz = SpectralResponse::cie_xyz(test::library());
  const Matrix3 wb = white_balance_matrix(tungsten, xyz, test::library());
  const auto white = film_channels(tungsten, xyz);
  const auto balanced = wb.apply(white);
  const double sum = balanced[0] + balanced[1] + balanced[2];
  CHECK(balanced[0] / sum == doctest::Approx(0.31272).epsilon(2e-5 / 0.31272));
  CHECK(balanced[1] / sum == doctest::Approx(0.32903).epsilon(2e-5 / 0.32903));

  const SpectralResponse camera = SpectralResponse::camera_rgb(test::library(), "nikon_d850");
  const auto raw = white_balance_matrix(tungsten, camera, test::library()).apply(film_channels(tungsten, camera));
  CHECK(raw[0] == doctest::Approx(raw[1]).epsilon(1e-12));
  CHECK(raw[2] == doctest::Approx(raw[1]).epsilon(1e-12));
}
