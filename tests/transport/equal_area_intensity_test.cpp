// pbrt-v4's goniometric light as an intensity image in the equal-area octahedral mapping: nearest-pixel values,
// the exact sphere integral (every pixel subtends 4π/N²), sampling proportional to the pixels (chi-square), and the
// light's explicit (possibly mirrored) frame.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "light_test_support.h"
#include "square_chi_square.h"
#include "spectral/spectra/spectrum.h"
#include "transport/lights/equal_area_intensity.h"
#include "transport/sampling/equal_area_square.h"
#include "transport/lights/goniometric_light.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;

// 6 × 6 pixels of uneven values with two black pixels.
EqualAreaIntensity uneven_image() {
  std::vector<double> v;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) v.push_back((x == 2 && y < 2) ? 0.0 : 1.0 + x + 3.0 * y + 0.5 * ((x * y) % 4));
  return EqualAreaIntensity(6, v);
}

}  // namespace

TEST_CASE("equal-area intensity: the value of the pixel a direction falls in, and the exact integral") {
  const EqualAreaIntensity t = uneven_image();
  double sum = 0.0;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      sum += t.pixel(x, y);
      // A point a quarter of the way into the pixel (not only its centre) maps back into that pixel.
      const Vec3 w = equal_area_square_to_sphere({(x + 0.25f) / 6.0f, (y + 0.7f) / 6.0f});
      CHECK(t.intensity(w) == t.pixel(x, y));
    }
  CHECK(t.integral_sr() == doctest::Approx(4.0 * kPi * sum / 36.0).epsilon(1e-12));
  CHECK(t.peak() == doctest::Approx(1.0 + 5 + 15 + 0.5 * ((5 * 5) % 4)));
  // The centre of the square is local +z, the middle of the right edge +x, of the bottom edge (last row) +y.
  CHECK(t.intensity({0, 0, 1}) == t.pixel(3, 3));
  CHECK(t.intensity({1, 0, 0}) == t.pixel(5, 3));
  CHECK(t.intensity({0, 1, 0}) == t.pixel(3, 5));
}

TEST_CASE("equal-area intensity sampling: chi-square by pixel against I/∫I, and pdf() agrees with sample()") {
  const EqualAreaIntensity t = uneven_image();
  const int n = 200000;
  std::vector<double> observed(36, 0.0), expected(36, 0.0);
  double sum = 0.0;
  for (int i = 0; i < 36; ++i) sum += t.pixel(i % 6, i / 6);
  for (int i = 0; i < 36; ++i) expected[size_t(i)] = n * t.pixel(i % 6, i / 6) / sum;
  std::mt19937 rng(11);
  for (int k = 0; k < n; ++k) {
    const auto s = t.sample({test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(s);
    const Vec2 uv = equal_area_sphere_to_square(s->w);
    observed[test::square_cell(uv, 6)] += 1;
    if (k % 64 == 0) {
      // p(ω) = I(ω)/∫I exactly.
      CHECK(s->pdf == doctest::Approx(t.pdf(s->w)).epsilon(1e-4));
      CHECK(double(s->pdf) == doctest::Approx(t.intensity(s->w) / t.integral_sr()).epsilon(1e-4));
    }
  }
  const test::ChiSquareResult r = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(r.statistic);
  CHECK(r.p_value > test::kChiSquareAlpha);
  CHECK(observed[2] == 0.0);  // the black pixels are never drawn
  CHECK(t.pdf(equal_area_square_to_sphere({2.5f / 6, 0.5f / 6})) == 0.0f);
}

TEST_CASE("goniometric light with an explicit frame: the image is read in that frame, even a left-handed one") {
  // pbrt's goniometric frame with an identity light transform: local x, y, z = world x, z, y (left-handed).
  const Frame frame{{1, 0, 0}, {0, 0, 1}, {0, 1, 0}};
  auto table = std::make_shared<const EqualAreaIntensity>(uneven_image());
  const GoniometricLight light({0, 0, 0}, frame, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), 1.0), table);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      const Vec3 local = equal_area_square_to_sphere({(x + 0.5f) / 6.0f, (y + 0.5f) / 6.0f});
      const Vec3 world{local.x, local.z, local.y};
      CHECK(light.table_value(world) == table->pixel(x, y));
    }
  const auto s = light.sample_emission_direction({0.3f, 0.8f});
  REQUIRE(s);
  CHECK(double(s->pdf) == doctest::Approx(light.table_value(s->w) / table->integral_sr()).epsilon(1e-4));
}
