// The sigmoid-polynomial upsampler (sigmoid_polynomial.h): round trips in CIELAB, bounds, exact greys, scaling.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "spectral/upsampling/sigmoid_polynomial.h"
#include "test_support.h"

using namespace rimu;

namespace {

const SigmoidFitter& fitter(const std::string& space) {
  static std::map<std::string, std::unique_ptr<SigmoidFitter>> cache;
  auto& slot = cache[space];
  if (!slot) slot = std::make_unique<SigmoidFitter>(test::library(), RgbColourSpace::named(space));
  return *slot;
}

// Linear sRGB colours from pale to saturated: the Cornell box's red and green walls (0.63, 0.065, 0.05),
// (0.14, 0.45, 0.091), a ColorChecker-like blue, near-greys, and the cube's corners (the sRGB cube lies inside
// the gamut of sigmoid spectra under D65, as Jakob & Hanika report).
const Rgb kSrgbColours[] = {{0.63, 0.065, 0.05}, {0.14, 0.45, 0.091}, {0.1, 0.2, 0.5},  {0.8, 0.7, 0.2},
                            {0.3, 0.31, 0.29},   {0.001, 0.002, 0.003}, {0.05, 0.05, 0.9}, {0.95, 0.05, 0.05},
                            {0.05, 0.9, 0.05},   {0.9, 0.9, 0.05},    {0.05, 0.9, 0.9},  {0.9, 0.05, 0.9},
                            {1, 0, 0},           {0, 1, 0},           {0, 0, 1},         {1, 1, 0},
                            {0, 1, 1},           {1, 0, 1}};
// Rec.2020's primaries lie on the spectral locus, so its saturated corners are beyond any reflectance: only
// moderate colours there.
const Rgb kRec2020Colours[] = {{0.63, 0.065, 0.05}, {0.14, 0.45, 0.091}, {0.1, 0.2, 0.5}, {0.8, 0.7, 0.2},
                               {0.3, 0.31, 0.29}};

}  // namespace

TEST_CASE("sigmoid polynomial: S maps the quadratic onto (0, 1), and constant(v) is v") {
  for (double v : {0.0, 1e-6, 0.18, 0.5, 0.9, 1.0}) {
    const SigmoidPolynomial p = SigmoidPolynomial::constant(v);
    for (double nm : {360.0, 555.0, 830.0}) CHECK(p.value(nm) == doctest::Approx(v).epsilon(1e-14));
  }
  // A steep quadratic stays within [0, 1] however large it grows.
  const SigmoidPolynomial steep{1e3, -1e6, 2.4e8};
  for (double nm = 360; nm <= 830; nm += 7) {
    const double s = steep.value(nm);
    CHECK(s >= 0.0);
    CHECK(s <= 1.0);
  }
}

TEST_CASE("sigmoid fit: in-gamut colours come back within ΔE*ab 0.1, and the albedo stays in [0, 1]") {
  const std::pair<std::string, std::vector<Rgb>> cases[] = {
      {"srgb-linear", {std::begin(kSrgbColours), std::end(kSrgbColours)}},
      {"rec2020", {std::begin(kRec2020Colours), std::end(kRec2020Colours)}}};
  for (const auto& [space, colours] : cases) {
    for (const Rgb& rgb : colours) {
      CAPTURE(space);
      CAPTURE(rgb.r);
      CAPTURE(rgb.g);
      CAPTURE(rgb.b);
      const SigmoidSpectrum s = fitter(space).fit_albedo(rgb);
      CHECK(s.delta_e_ab < 0.1);
      CHECK(fitter(space).delta_e_ab(rgb, s) == doctest::Approx(s.delta_e_ab));
      const Rgb back = fitter(space).rgb_of(s);
      // ΔE 0.1 bounds the RGB error to about 1e-3 of the white for these colours.
      CHECK(std::abs(back.r - rgb.r) < 2e-3);
      CHECK(std::abs(back.g - rgb.g) < 2e-3);
      CHECK(std::abs(back.b - rgb.b) < 2e-3);
      for (double nm = 360; nm <= 830; nm += 1) {
        const double v = s.value(nm);
        REQUIRE(v >= 0.0);
        REQUIRE(v <= 1.0);
      }
    }
  }
}

TEST_CASE("sigmoid fit: a colour beyond every reflectance comes back in [0, 1] with its ΔE*ab") {
  // Rec.2020's green primary is a spectral colour: no reflectance under D65 reaches it.
  const SigmoidSpectrum s = fitter("rec2020").fit_albedo({0.05, 0.9, 0.05});
  CHECK(s.delta_e_ab > 1.0);
  CHECK(fitter("rec2020").delta_e_ab({0.05, 0.9, 0.05}, s) == doctest::Approx(s.delta_e_ab));
  for (double nm = 360; nm <= 830; nm += 1) {
    REQUIRE(s.value(nm) >= 0.0);
    REQUIRE(s.value(nm) <= 1.0);
  }
}

TEST_CASE("sigmoid fit: black, white and greys are the exact constants") {
  for (double v : {0.0, 0.18, 0.5, 1.0}) {
    const SigmoidSpectrum s = fitter("srgb-linear").fit_albedo({v, v, v});
    CHECK(s.delta_e_ab == 0.0);
    for (double nm : {360.0, 500.0, 700.0, 830.0}) CHECK(s.value(nm) == doctest::Approx(v).epsilon(1e-14));
  }
  // The constant 1 is the space's white exactly (the illuminant's XYZ is mapped onto the space's white).
  const Rgb white = fitter("srgb-linear").rgb_of(fitter("srgb-linear").fit_albedo({1, 1, 1}));
  CHECK(white.r == doctest::Approx(1).epsilon(1e-12));
  CHECK(white.g == doctest::Approx(1).epsilon(1e-12));
  CHECK(white.b == doctest::Approx(1).epsilon(1e-12));
}

TEST_CASE("sigmoid fit: an unbounded RGB is 2·max times the albedo fit of rgb / (2·max)") {
  const SigmoidFitter& f = fitter("srgb-linear");
  const Rgb eta{0.2, 0.92, 1.1};
  const SigmoidSpectrum s = f.fit_unbounded(eta);
  CHECK(s.scale == doctest::Approx(2.2));
  const SigmoidSpectrum shape = f.fit_albedo({0.2 / 2.2, 0.92 / 2.2, 1.1 / 2.2});
  for (double nm = 360; nm <= 830; nm += 10) CHECK(s.value(nm) == doctest::Approx(2.2 * shape.value(nm)).epsilon(1e-12));
  const Rgb back = f.rgb_of(s);
  CHECK(std::abs(back.r - eta.r) < 5e-3);
  CHECK(std::abs(back.g - eta.g) < 5e-3);
  CHECK(std::abs(back.b - eta.b) < 5e-3);
  // A grey is the constant; black is 0.
  CHECK(f.fit_unbounded({3, 3, 3}).value(600) == doctest::Approx(3).epsilon(1e-14));
  CHECK(f.fit_unbounded({0, 0, 0}).value(600) == 0.0);
}

TEST_CASE("sigmoid fit: NaN, infinite, negative and (for an albedo) above-1 components are refused") {
  const SigmoidFitter& f = fitter("srgb-linear");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const SourceLocation where{"scene.pbrt", 12, ""};
  CHECK_THROWS_WITH_AS(f.fit_albedo({nan, 0.5, 0.5}, where), doctest::Contains("must be finite and >= 0"), InputError);
  CHECK_THROWS_WITH_AS(f.fit_albedo({0.5, -0.1, 0.5}, where), doctest::Contains("scene.pbrt:12"), InputError);
  CHECK_THROWS_WITH_AS(f.fit_albedo({0.5, 0.5, 1.2}, where), doctest::Contains("must be <= 1"), InputError);
  CHECK_THROWS_AS(f.fit_unbounded({inf, 1, 1}, where), InputError);
  CHECK_THROWS_AS(f.fit_unbounded({1, -1, 1}, where), InputError);
}
