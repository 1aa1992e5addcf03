// Goniometric (IES-style) point lights: the candela table's bilinear interpolation, its exact integral over the
// sphere, sampling proportional to the table (chi-square against the sampler's own pdf) and the light's frame.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "light_test_support.h"
#include "spectral/spectra/spectrum.h"
#include "transport/lights/candela_distribution.h"
#include "transport/lights/goniometric_light.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;
double rad(double deg) { return deg * kPi / 180.0; }

// A table with uneven γ and C steps, a dark cap and a C-dependence: values[c][γ].
CandelaDistribution uneven_table() {
  const std::vector<double> gamma{0, 10, 25, 45, 90, 120, 180};
  const std::vector<double> c{0, 30, 90, 200, 360};
  std::vector<double> v;
  for (size_t i = 0; i < c.size(); ++i)
    for (size_t j = 0; j < gamma.size(); ++j)
      v.push_back(gamma[j] >= 120 ? 0.0 : 100.0 + 50.0 * std::cos(rad(c[i])) * double(j) + 10.0 * double(i));
  return CandelaDistribution(gamma, c, v);
}

}  // namespace

TEST_CASE("candela table: exact at grid points, bilinear between, zero outside the tabulated angles") {
  // values[c][γ] on γ = 0, 30, 60 and C = 0, 90, 360.
  const CandelaDistribution t({0, 30, 60}, {0, 90, 360}, {1000, 800, 200, 1000, 400, 100, 1000, 800, 200});
  CHECK(t.intensity_deg(30, 0) == doctest::Approx(800).epsilon(1e-14));
  CHECK(t.intensity_deg(60, 90) == doctest::Approx(100).epsilon(1e-14));
  // Bilinear: at (45°, 45°) the mean of the four corners 800, 200, 400, 100.
  CHECK(t.intensity_deg(45, 45) == doctest::Approx(375).epsilon(1e-14));
  // Linear along γ at C = 90: a quarter of the way from 30° to 60°.
  CHECK(t.intensity_deg(37.5, 90) == doctest::Approx(400 + 0.25 * (100 - 400)).epsilon(1e-14));
  CHECK(t.intensity_deg(61, 0) == 0.0);  // beyond the last vertical angle: dark
  CHECK(t.intensity_deg(30, 360 + 90) == doctest::Approx(400).epsilon(1e-14));
  // The same through a direction: γ = 30°, C = 90° is (0, sin 30°, cos 30°).
  CHECK(t.intensity(Vec3{0.0f, 0.5f, float(std::cos(rad(30)))}) == doctest::Approx(400).epsilon(1e-5));
  CHECK(t.peak() == 1000);
}

TEST_CASE("candela table: its sphere integral is exact for a profile linear in gamma") {
  // I = 1000 cd to 30°, falling linearly to 0 at 60°, dark beyond. ∫I dω = 2π·1000·[(1 − cos 30°) + ∫₃₀⁶⁰ (60°−γ)/30°
  // sin γ dγ], and ∫_{γ0}^{γ1} (γ1 − γ)/Δγ sin γ dγ = cos γ0 − (sin γ1 − sin γ0)/Δγ (integration by parts).
  // Exact arithmetic: the tolerance is rounding.
  const CandelaDistribution t({0, 30, 60, 90}, {0, 360}, {1000, 1000, 0, 0, 1000, 1000, 0, 0});
  const double expected =
      2 * kPi * 1000 * ((1 - std::cos(rad(30))) + std::cos(rad(30)) - (std::sin(rad(60)) - std::sin(rad(30))) / rad(30));
  CHECK(t.integral_sr() == doctest::Approx(expected).epsilon(1e-12));
  // An isotropic 1 cd table gives 4π lm.
  CHECK(CandelaDistribution({0, 180}, {0, 360}, {1, 1, 1, 1}).integral_sr() == doctest::Approx(4 * kPi).epsilon(1e-12));
}

TEST_CASE("candela table sampling: chi-square against its pdf, and cell probabilities follow the table") {
  const CandelaDistribution t = uneven_table();
  const auto& g = t.gamma_deg();
  const auto& c = t.c_deg();
  // Bins: each table cell split in two in C and in two in cos γ; the pdf is constant on a cell, so a bin's expected
  // count is N · pdf · Ω_bin exactly. Splitting the cells checks the placement inside a cell as well.
  const int n = 200000;
  const size_t nc = c.size() - 1, ng = g.size() - 1;
  std::vector<double> observed(nc * ng * 4, 0.0), expected(nc * ng * 4, 0.0);
  auto bin_of = [&](double gamma_deg, double c_deg) {
    size_t j = 0, i = 0;
    while (j + 1 < ng && gamma_deg >= g[j + 1]) ++j;
    while (i + 1 < nc && c_deg >= c[i + 1]) ++i;
    const double mid_cos = 0.5 * (std::cos(rad(g[j])) + std::cos(rad(g[j + 1])));
    const size_t sub_g = std::cos(rad(gamma_deg)) < mid_cos ? 1 : 0;
    const size_t sub_c = c_deg >= 0.5 * (c[i] + c[i + 1]) ? 1 : 0;
    return ((j * nc + i) * 2 + sub_g) * 2 + sub_c;
  };
  std::mt19937 rng(5);
  for (int k = 0; k < n; ++k) {
    const auto s = t.sample({test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(s);
    const double gamma = std::acos(std::clamp(double(s->w.z), -1.0, 1.0)) * 180 / kPi;
    double phi = std::atan2(double(s->w.y), double(s->w.x)) * 180 / kPi;
    if (phi < 0) phi += 360;
    if (k % 64 == 0) CHECK(s->pdf == doctest::Approx(t.pdf(s->w)).epsilon(1e-4));  // sample() agrees with pdf()
    observed[bin_of(gamma, phi)] += 1;
  }
  double total_probability = 0;
  for (size_t j = 0; j < ng; ++j) {
    for (size_t i = 0; i < nc; ++i) {
      const double dc = rad(c[i + 1] - c[i]) / 2, dcos = (std::cos(rad(g[j])) - std::cos(rad(g[j + 1]))) / 2;
      const double cg = std::acos(std::cos(rad(g[j])) - dcos) * 180 / kPi;  // γ at the cell's cos-centre
      const float p = t.pdf(Vec3{float(std::sin(rad(cg)) * std::cos(rad(0.5 * (c[i] + c[i + 1])))),
                                 float(std::sin(rad(cg)) * std::sin(rad(0.5 * (c[i] + c[i + 1])))), float(std::cos(rad(cg)))});
      for (size_t b = 0; b < 4; ++b) expected[(j * nc + i) * 4 + b] = n * double(p) * dc * dcos;
      total_probability += double(p) * 4 * dc * dcos;
    }
  }
  CHECK(total_probability == doctest::Approx(1.0).epsilon(1e-5));
  const test::ChiSquareResult r = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
  CAPTURE(r.statistic);
  CHECK(r.p_value > test::kChiSquareAlpha);

  // The cell probabilities are the table's: P(cell) ∝ (mean of its corners) · Ω_cell. Cells (C 30-90°, γ 10-25°)
  // and (C 200-360°, γ 45-90°), computed from the construction of uneven_table().
  auto corner = [&](size_t i, size_t j) { return g[j] >= 120 ? 0.0 : 100.0 + 50.0 * std::cos(rad(c[i])) * double(j) + 10.0 * double(i); };
  auto weight = [&](size_t i, size_t j) {
    return 0.25 * (corner(i, j) + corner(i + 1, j) + corner(i, j + 1) + corner(i + 1, j + 1)) * rad(c[i + 1] - c[i]) *
           (std::cos(rad(g[j])) - std::cos(rad(g[j + 1])));
  };
  auto cell_probability = [&](size_t i, size_t j) {
    const double cg = std::acos(0.5 * (std::cos(rad(g[j])) + std::cos(rad(g[j + 1]))));
    const double cc = rad(0.5 * (c[i] + c[i + 1]));
    const Vec3 w{float(std::sin(cg) * std::cos(cc)), float(std::sin(cg) * std::sin(cc)), float(std::cos(cg))};
    return double(t.pdf(w)) * rad(c[i + 1] - c[i]) * (std::cos(rad(g[j])) - std::cos(rad(g[j + 1])));
  };
  CHECK(cell_probability(1, 1) / cell_probability(3, 3) == doctest::Approx(weight(1, 1) / weight(3, 3)).epsilon(1e-5));
  // The dark cap (γ ≥ 120°) is never sampled.
  CHECK(t.pdf(Vec3{0, 0, -1}) == 0.0f);
}

TEST_CASE("goniometric light: the table is read in the light's frame, power is spectrum times table integral") {
  // Axis straight down, C = 0° along +x: C = 90° is then −z (counter-clockwise seen from above, LM-63 type C).
  auto table = std::make_shared<const CandelaDistribution>(std::vector<double>{0, 90, 180},
                                                           std::vector<double>{0, 90, 180, 270, 360},
                                                           std::vector<double>{100, 10, 0, 100, 40, 0, 100, 70, 0,
                                                                               100, 20, 0, 100, 10, 0});
  const LightSpectrum spectrum(std::make_shared<ConstantSpectrum>(2.0), 1.0);
  const GoniometricLight light({0, 2, 0}, {0, -1, 0}, {1, 0, 0}, spectrum, table);
  const SampledWavelengths lambda = SampledWavelengths::sample_visible(0.3f);
  // Horizontal directions (γ = 90°) at C = 0, 90, 180, 270: +x, −z, −x, +z; a receiver 3 m away in each.
  const std::pair<Vec3, double> cases[] = {{{3, 2, 0}, 10}, {{0, 2, -3}, 40}, {{-3, 2, 0}, 70}, {{0, 2, 3}, 20}};
  for (const auto& [p, cd] : cases) {
    CAPTURE(cd);
    const auto s = light.sample_li({p, {0, 0, 0}}, lambda, {0.5f, 0.5f});
    REQUIRE(s);
    CHECK(float(s->radiance[0]) == doctest::Approx(2.0 * cd / 9.0).epsilon(1e-5));
  }
  // Straight below: 100 cd. Φ = ∫S dλ · ∫I dω (S = 2 over 360-830 nm).
  CHECK(float(light.sample_li({{0, 0, 0}, {0, 1, 0}}, lambda, {0, 0})->radiance[0]) == doctest::Approx(50.0).epsilon(1e-5));
  CHECK(light.total_power_w(1.0) == doctest::Approx(2.0 * 470.0 * table->integral_sr()).epsilon(1e-9));
  // Emission samples are world directions where the table is lit, with the table's density there.
  std::mt19937 rng(3);
  for (int k = 0; k < 100; ++k) {
    const auto e = light.sample_emission_direction({test::uniform01(rng), test::uniform01(rng)});
    REQUIRE(e);
    CHECK(light.table_value(e->w) > 0.0);
  }
}
