// CIELAB and CIELUV: the CIE 15:2004 definitions, their inverses, and behaviour at black and at the seam.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/colorimetry/cielab.h"

using namespace rimu;

namespace {

constexpr Xyz kD65{0.95047, 1.0, 1.08883};  // ASTM E308-01, 1931 2°, Y = 1

bool all_finite(const Lab& lab) { return std::isfinite(lab.l) && std::isfinite(lab.a) && std::isfinite(lab.b); }
bool all_finite(const Luv& luv) { return std::isfinite(luv.l) && std::isfinite(luv.u) && std::isfinite(luv.v); }

}  // namespace

TEST_CASE("the reference white is L* = 100 with zero a*, b*, u*, v*") {
  // By definition (CIE 15:2004 section 8.2): f(1) = 1, so L* = 116 - 16 and the opponent terms cancel.
  const Xyz whites[] = {kD65, Xyz{96.422, 100.0, 82.521}, Xyz{1.0, 1.0, 1.0}};
  for (const Xyz& white : whites) {
    const Lab lab = lab_of(white, white);
    CHECK(lab.l == doctest::Approx(100.0).epsilon(1e-15));
    CHECK(std::abs(lab.a) <= 1e-13);
    CHECK(std::abs(lab.b) <= 1e-13);
    const Luv luv = luv_of(white, white);
    CHECK(luv.l == doctest::Approx(100.0).epsilon(1e-15));
    CHECK(std::abs(luv.u) <= 1e-12);
    CHECK(std::abs(luv.v) <= 1e-12);
  }
}

TEST_CASE("CIELAB coefficients on exact cubes") {
  // With X/Xn = 0.216, Y/Yn = 0.125, Z/Zn = 0.064 the cube roots are 0.6, 0.5, 0.4, so CIE 15:2004's
  // L* = 116·0.5 − 16 = 42, a* = 500·(0.6 − 0.5) = 50, b* = 200·(0.5 − 0.4) = 20 exactly: this pins the
  // 116/16/500/200 coefficients and the sign conventions (a* red-positive, b* yellow-positive).
  const Lab lab = lab_of({0.216 * kD65.x, 0.125 * kD65.y, 0.064 * kD65.z}, kD65);
  CHECK(lab.l == doctest::Approx(42.0).epsilon(1e-14));
  CHECK(lab.a == doctest::Approx(50.0).epsilon(1e-13));
  CHECK(lab.b == doctest::Approx(20.0).epsilon(1e-13));
}

TEST_CASE("Lab and Luv round trips through XYZ, bright and dark") {
  // Includes components below ε = 216/24389 (the linear segment) and mixed cases (Y above, Z below).
  const double fractions[] = {0.0, 1e-6, 0.004, 0.0088, 0.0089, 0.05, 0.18, 0.5, 1.0, 1.3};
  for (double fx : fractions)
    for (double fy : fractions)
      for (double fz : fractions) {
        const Xyz xyz{fx * kD65.x, fy * kD65.y, fz * kD65.z};
        CAPTURE(fx);
        CAPTURE(fy);
        CAPTURE(fz);
        const Xyz from_lab = xyz_from_lab(lab_of(xyz, kD65), kD65);
        CHECK(std::abs(from_lab.x - xyz.x) <= 1e-13);
        CHECK(std::abs(from_lab.y - xyz.y) <= 1e-13);
        CHECK(std::abs(from_lab.z - xyz.z) <= 1e-13);
        if (fy == 0.0) continue;  // CIELUV of Y = 0 is L* = 0, which loses the chromaticity by definition
        // CIELUV is ill-conditioned when Y is small next to X and Z. u' and v' come back with an absolute error
        // δ of a few ulp of the white's u'n, v'n (≈ 0.2-0.5; we take δ = 1e-15, ~9 ulp). Then
        // X = 9Y·u'/(4v') and Z = Y·(12 − 3u' − 20v')/(4v') err by about |X or Z|·δ/v' (through 1/v') plus
        // δ·Y/v' = δ·(X + 15Y + 3Z)/9 (through the numerators), with v' = 9Y/(X + 15Y + 3Z).
        const double delta = 1e-15;
        const double v_prime = uv1976_of(xyz).v;
        const double numerator_error = delta * (xyz.x + 15.0 * xyz.y + 3.0 * xyz.z);
        const Xyz from_luv = xyz_from_luv(luv_of(xyz, kD65), kD65);
        CHECK(std::abs(from_luv.x - xyz.x) <= xyz.x * delta / v_prime + numerator_error);
        CHECK(std::abs(from_luv.y - xyz.y) <= 1e-14 * xyz.y);
        CHECK(std::abs(from_luv.z - xyz.z) <= xyz.z * delta / v_prime + numerator_error);
      }
}

TEST_CASE("black is L* = 0 without NaN, and comes back as black") {
  const Lab lab = lab_of({0, 0, 0}, kD65);
  CHECK(all_finite(lab));
  CHECK(lab.l == 0.0);
  CHECK(std::abs(lab.a) <= 1e-14);
  CHECK(std::abs(lab.b) <= 1e-14);
  const Luv luv = luv_of({0, 0, 0}, kD65);
  CHECK(all_finite(luv));
  CHECK(luv.l == 0.0);
  CHECK(luv.u == 0.0);
  CHECK(luv.v == 0.0);
  const Xyz from_luv = xyz_from_luv(luv, kD65);
  CHECK(from_luv.x == 0.0);
  CHECK(from_luv.y == 0.0);
  CHECK(from_luv.z == 0.0);
  const Lch lch = lch_of(lab);
  CHECK(lch.c <= 1e-14);
  CHECK(std::isfinite(lch.h_deg));
}

TEST_CASE("L* is continuous with a continuous slope at Y/Yn = 216/24389") {
  // The exact CIE 15:2004 constants make both branches give L* = 8 at ε, with slope κ = 24389/27 on both
  // sides. Probing at ε(1 ± 1e-9): the cube-root branch's curvature changes the slope by ~1e-9 relative, so
  // the secant slopes agree with κ to 1e-6 relative (rounding in the 1e-11 steps dominates).
  const double eps = kCielabEpsilon;
  const double step = eps * 1e-9;
  const auto lightness = [](double relative_y) { return lab_of({0.0, relative_y, 0.0}, {1.0, 1.0, 1.0}).l; };
  CHECK(lightness(eps) == doctest::Approx(8.0).epsilon(1e-14));
  CHECK(std::abs(lightness(eps + step) - lightness(eps - step)) <= 2.0 * step * kCielabKappa * (1.0 + 1e-6));
  const double slope_below = (lightness(eps) - lightness(eps - step)) / step;
  const double slope_above = (lightness(eps + step) - lightness(eps)) / step;
  CHECK(slope_below == doctest::Approx(kCielabKappa).epsilon(1e-6));
  CHECK(slope_above == doctest::Approx(kCielabKappa).epsilon(1e-6));
  CHECK(kCielabKappa * kCielabEpsilon == doctest::Approx(8.0).epsilon(1e-15));
}

TEST_CASE("LCh: chroma, hue within 0-360 degrees, and the neutral hue") {
  const Lch lch = lch_of(Lab{50.0, 3.0, -4.0});
  CHECK(lch.c == doctest::Approx(5.0).epsilon(1e-15));
  CHECK(lch.h_deg == doctest::Approx(360.0 - 53.13010235415598).epsilon(1e-14));
  CHECK(lch_of(Lab{50.0, 0.0, 0.0}).h_deg == 0.0);
  CHECK(lch_of(Lab{50.0, -1.0, 0.0}).h_deg == doctest::Approx(180.0).epsilon(1e-15));
  // A hue just below 0 must wrap into [0, 360), never be reported as 360.
  const double tiny_negative = lch_of(Lab{50.0, 1.0, -1e-300}).h_deg;
  CHECK(tiny_negative >= 0.0);
  CHECK(tiny_negative < 360.0);
  const Lab back = lab_from_lch(lch);
  CHECK(back.a == doctest::Approx(3.0).epsilon(1e-14));
  CHECK(back.b == doctest::Approx(-4.0).epsilon(1e-14));
  const Luv luv_back = luv_from_lch(lch_of(Luv{60.0, -12.0, 5.0}));
  CHECK(luv_back.u == doctest::Approx(-12.0).epsilon(1e-14));
  CHECK(luv_back.v == doctest::Approx(5.0).epsilon(1e-14));
}
