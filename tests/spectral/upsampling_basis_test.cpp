// The fast upsampling path (upsampling_basis.h, RgbUpsampler::*_coefficients): round trips on random colours in
// every space, the hard cases of the exact path, and agreement with the exact path's spectra.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <string>

#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "test_support.h"
#include "upsampler_fixture.h"

using namespace rimu;

namespace {

using test::upsampler;

/// Deterministic uniform numbers in [0, 1) (a 32-bit LCG: reproducible failures).
struct Random {
  uint32_t state;
  double next() {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * (1.0 / 16777216.0);
  }
};

double delta_e(const RgbUpsampler& up, const Xyz& a, const Xyz& b) {
  const Xyz white = up.colorimetry().white_xyz();
  return delta_e_2000(lab_of(a, white), lab_of(b, white));
}

/// The knots of the reflectance the fast path gives: clamp(Φc, 0, 1), as evaluate_clamped interpolates them.
KnotValues fast_knots(const RgbUpsampler& up, const Rgb& rgb) { return up.fast_reflectance_spectrum(rgb).samples().knots(); }

}  // namespace

TEST_CASE("fast path: random colours of every space come back as the input colour unless reported moved") {
  // What the fast path adds to the exact path's float rounding: the 16-function basis rings by up to ~1e-2
  // around zero regions, and the clamped ringing is fitted back to the target colour (fit_clamped); a colour
  // whose fit leaves a relative XYZ residual above 1e-4 is reported as moved. So every colour not reported moved
  // is within ΔE00 ~0.01 of its input: asserted ≤ 0.02 (float knots and the residual's ΔE at dark colours),
  // mean ≤ 1e-3. The colours the fast path moves but the exact path does not are counted: near the brightness
  // limit (where the exact path maps too, from 2 % further) and saturated purples beyond the basis' reach.
  for (const std::string space : test::kUpsamplerSpaces) {
    CAPTURE(space);
    const RgbUpsampler& up = upsampler(space);
    Random random{42};
    std::vector<double> errors;
    int moved_only_by_fast = 0, exact_unmapped = 0;
    for (int i = 0; i < 4000; ++i) {
      // Mostly [0,1]³, some with a negative or an above-1 component.
      const Rgb rgb{1.2 * random.next() - 0.05, 1.2 * random.next() - 0.05, 1.2 * random.next() - 0.05};
      bool mapped = false;
      up.reflectance_coefficients(rgb, &mapped);
      const UpsampledReflectance exact = up.upsample_reflectance(rgb);
      exact_unmapped += !exact.gamut_mapped;
      if (mapped && !exact.gamut_mapped) ++moved_only_by_fast;
      const KnotValues knots = fast_knots(up, rgb);
      for (double v : knots) REQUIRE((v >= 0.0 && v <= 1.0));
      if (mapped) continue;
      errors.push_back(delta_e(up, up.space().to_xyz(rgb), up.colorimetry().xyz_of(knots)));
    }
    REQUIRE(errors.size() > 500);
    std::sort(errors.begin(), errors.end());
    double mean = 0;
    for (double e : errors) mean += e / double(errors.size());
    CAPTURE(mean);
    CAPTURE(moved_only_by_fast);
    CAPTURE(exact_unmapped);
    CHECK(mean <= 1e-3);
    CHECK(errors.back() <= 0.02);
    // Measured: ≤ 2.5 % of the colours the exact path reproduces (the wide spaces' purples); asserted ≤ 4 %.
    CHECK(moved_only_by_fast <= 0.04 * exact_unmapped);
  }
}

TEST_CASE("fast path: on the sRGB cube, every colour the exact path reproduces is reproduced") {
  // The target for sRGB reflectances, unmapped colours: mean ΔE00 ≤ 0.01, max ≤ 0.05 (measured on 33³:
  // 7.8e-6 and 1.6e-4). Here on 17³, including those the fast path reports moved, with the bounds.
  const RgbUpsampler& up = upsampler("srgb-linear");
  double sum = 0, largest = 0;
  int count = 0;
  for (int r = 0; r <= 16; ++r)
    for (int g = 0; g <= 16; ++g)
      for (int b = 0; b <= 16; ++b) {
        const Rgb rgb{r / 16.0, g / 16.0, b / 16.0};
        if (up.upsample_reflectance(rgb).gamut_mapped) continue;
        const double e = delta_e(up, up.space().to_xyz(rgb), up.colorimetry().xyz_of(fast_knots(up, rgb)));
        sum += e, largest = std::max(largest, e), ++count;
      }
  CAPTURE(count);
  CHECK(sum / count <= 0.01);
  CHECK(largest <= 0.05);
}

TEST_CASE("fast path: the clamped spectrum carries the target colour") {
  // smooth_coefficients re-imposes the colour with a 3×3 solve (aimed at t + δ, the clamping offset), fit_clamped
  // refines it on the clamped spectrum to a relative residual of 1e-6.
  const RgbUpsampler& up = upsampler("srgb-linear");
  Random random{7};
  for (int i = 0; i < 500; ++i) {
    const Rgb rgb{0.9 * random.next(), 0.9 * random.next(), 0.9 * random.next()};
    const Xyz want = up.space().to_xyz(rgb);
    bool mapped = false;
    KnotValues knots = up.basis().knots(up.emission_coefficients(rgb, &mapped));
    REQUIRE_FALSE(mapped);
    for (double& v : knots) v = std::max(v, 0.0);
    const Xyz got = up.colorimetry().xyz_of(knots);
    const double scale = want.x + want.y + want.z;
    CHECK(std::abs(got.x - want.x) <= 1e-5 * scale);
    CHECK(std::abs(got.y - want.y) <= 1e-5 * scale);
    CHECK(std::abs(got.z - want.z) <= 1e-5 * scale);
  }
}

TEST_CASE("fast path: white, grey, black, non-finite input") {
  for (const char* space : test::kUpsamplerSpaces) {
    CAPTURE(space);
    const RgbUpsampler& up = upsampler(space);
    // White and grey sit on the table's ρ = 0 row, the flat spectrum, which is the first basis function:
    // only float rounding of 16 coefficients separates them from flat.
    const KnotValues white = fast_knots(up, {1, 1, 1});
    const KnotValues grey = fast_knots(up, {0.18, 0.18, 0.18});
    for (int i = 0; i < kUpsampleKnotCount; ++i) {
      CHECK(white[i] == doctest::Approx(1.0).epsilon(1e-5));
      CHECK(grey[i] == doctest::Approx(0.18).epsilon(1e-5));
    }
    bool mapped = true;
    const BasisCoefficients black = up.reflectance_coefficients({0, 0, 0}, &mapped);
    CHECK_FALSE(mapped);
    for (float c : black.c) CHECK(c == 0.0f);
    CHECK(up.fast_emission_spectrum({0, 0, 0}).max_value() == 0.0);
  }
  const RgbUpsampler& up = upsampler("srgb-linear");
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(up.reflectance_coefficients({nan, 0.5, 0.5}), InputError);
  CHECK_THROWS_AS(up.emission_coefficients({0.5, inf, 0.5}), InputError);
}

TEST_CASE("fast path: primaries and out-of-locus colours: values in [0,1], near the exact path's mapped colour") {
  for (const std::string space : test::kUpsamplerSpaces) {
    CAPTURE(space);
    const RgbUpsampler& up = upsampler(space);
    for (const Rgb rgb : {Rgb{1, 0, 0}, Rgb{0, 1, 0}, Rgb{0, 0, 1}, Rgb{0.2, 0, 0}, Rgb{0, 0.2, 0}, Rgb{0, 0, 0.2},
                          Rgb{-0.5, 1, 0}, Rgb{0.3, -0.2, 0.1}}) {
      CAPTURE(rgb.r);
      CAPTURE(rgb.g);
      CAPTURE(rgb.b);
      bool mapped = false;
      up.reflectance_coefficients(rgb, &mapped);
      const UpsampledReflectance exact = up.upsample_reflectance(rgb);
      const KnotValues knots = fast_knots(up, rgb);
      for (double v : knots) REQUIRE((v >= 0.0 && v <= 1.0));
      // Where both paths map, they land on nearby colours: the same radial move and a brightness limit within
      // the ringing allowance (ΔE00 ≤ 1 at the 2 % step in Y) for sRGB. The primaries of the wider spaces sit on
      // or beyond the usable gamut's edge, whose narrow spectra the basis cannot hold, and so do colours beyond
      // the locus like (−0.5, 1, 0): measured up to ΔE00 13 from the exact path's mapped colour.
      const double bound = space == "srgb-linear" ? 1.0 : 15.0;
      if (exact.spectrum.samples().max_value() > 0.0f)
        CHECK(delta_e(up, up.colorimetry().xyz_of(knots), up.xyz_of(exact.spectrum.samples())) <= bound);
    }
  }
}

TEST_CASE("fast path: emission near the locus and from 1e-8 to 1e6 keeps its colour and luminance") {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const Observer& observer = test::library().observer(StandardObserver::cie1931_2deg);
  for (const double level : {1e-8, 1.0, 1e6}) {
    CAPTURE(level);
    const Rgb in{0.8 * level, 0.2 * level, 0.1 * level};
    bool mapped = true;
    up.emission_coefficients(in, &mapped);
    CHECK_FALSE(mapped);
    const EmissionSpectrum e = up.fast_emission_spectrum(in);
    // emission_xyz integrates on the CIE 1 nm grid under the illuminant's own table: Y matches the input up to
    // the illuminant-vs-rounded-white difference of KnotColorimetry (≤ 1e-4, upsampling_knots.h).
    CHECK(emission_xyz(e, observer).y == doctest::Approx(up.space().to_xyz(in).y).epsilon(1e-4));
    CHECK(e.shape().min_value() >= 0.0f);
  }
  // Chromaticities all round the white at relative radius ρ of the usable gamut. The basis cannot hold the
  // narrow or two-lobed spectra of the purple-red edge at zero (docs/upsampling.md: worst ΔE00 5 at ρ = 0.9, 74 at
  // ρ = 0.999); there the fast path must say so (mapped), and wherever it does not, the colour must be right.
  int reported = 0;
  for (const double rho : {0.5, 0.9, 0.97, 0.999}) {
    for (int a = 0; a < 72; ++a) {
      const double angle = a * 2 * 3.14159265358979 / 72 + 0.01;
      CAPTURE(rho);
      CAPTURE(angle);
      const Chromaticity xy = up.gamut().at(angle, up.table().usable_fraction * rho);
      const Xyz target = xyz_from_xyY(xy, 1.0);
      bool mapped = true;
      const BasisCoefficients c = up.emission_coefficients(up.space().from_xyz(target), &mapped);
      KnotValues knots = up.basis().knots(c);
      for (double& v : knots) v = std::max(v, 0.0);
      if (rho <= 0.5) CHECK_FALSE(mapped);
      if (mapped) {
        ++reported;
        continue;
      }
      CHECK(delta_e(up, target, up.colorimetry().xyz_of(knots)) <= 0.02);
    }
  }
  CHECK(reported <= 160);  // measured 145 of 288 (none at ρ = 0.5)
}

TEST_CASE("fast path: spectra stay within the stated distance of the exact path's") {
  // docs/upsampling.md "Fast path": RMS over the knots ≤ 4.1e-3 and largest knot difference ≤ 0.03 on the 33³
  // sRGB grid (unmapped). Asserted on a 9³ grid with a margin: RMS ≤ 5e-3, any knot ≤ 0.04.
  const RgbUpsampler& up = upsampler("srgb-linear");
  for (int r = 0; r <= 8; ++r)
    for (int g = 0; g <= 8; ++g)
      for (int b = 0; b <= 8; ++b) {
        const Rgb rgb{r / 8.0, g / 8.0, b / 8.0};
        const UpsampledReflectance exact = up.upsample_reflectance(rgb);
        bool mapped = false;
        up.reflectance_coefficients(rgb, &mapped);
        if (exact.gamut_mapped || mapped) continue;
        const KnotValues fast = fast_knots(up, rgb), want = exact.spectrum.samples().knots();
        double sum = 0, largest = 0;
        for (int i = 0; i < kUpsampleKnotCount; ++i) {
          sum += (fast[i] - want[i]) * (fast[i] - want[i]);
          largest = std::max(largest, std::abs(fast[i] - want[i]));
        }
        CAPTURE(r);
        CAPTURE(g);
        CAPTURE(b);
        CHECK(std::sqrt(sum / kUpsampleKnotCount) <= 5e-3);
        CHECK(largest <= 0.04);
      }
}

TEST_CASE("fast path: the 4-lane clamped evaluation is the knot spectrum of the clamped coefficients") {
  const RgbUpsampler& up = upsampler("acescg");
  Random random{3};
  for (int i = 0; i < 200; ++i) {
    const Rgb rgb{random.next(), random.next(), random.next()};
    const BasisCoefficients c = up.reflectance_coefficients(rgb);
    const ReflectanceSpectrum knots = up.fast_reflectance_spectrum(rgb);
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(float(random.next()));
    const Float4 got = up.basis().evaluate_clamped(c, lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
    const Float4 want = knots.evaluate(lambda);
    for (int lane = 0; lane < kLaneCount; ++lane) CHECK(got[lane] == doctest::Approx(want[lane]).epsilon(1e-5));
  }
}

TEST_CASE("fast path: the rendering evaluation is the knot-clamped one wherever no knot pair crosses a bound") {
  // evaluate() interpolates the basis first and clamps after; evaluate_clamped() clamps the two knots first.
  // Clamping is 1-Lipschitz, so on an interval whose knots a, b lie beyond a bound the two differ by at most
  // max(|a − clamp(a)|, |b − clamp(b)|), and where both knots are inside they agree up to float rounding.
  for (const std::string space : {"srgb-linear", "acescg"}) {
    CAPTURE(space);
    const RgbUpsampler& up = upsampler(space);
    Random random{11};
    int crossing_lanes = 0;
    for (int i = 0; i < 400; ++i) {
      const Rgb rgb{random.next(), random.next(), random.next()};
      const BasisCoefficients c = up.reflectance_coefficients(rgb);
      const KnotValues raw = up.basis().knots(c);
      const SampledWavelengths lambda = SampledWavelengths::sample_visible(float(random.next()));
      const Float4 got = up.basis().evaluate(c, lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
      const Float4 want = up.basis().evaluate_clamped(c, lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
      for (int lane = 0; lane < kLaneCount; ++lane) {
        const int knot = std::min(int((lambda.lambda_nm(lane) - kUpsampleFirstKnotNm) / kUpsampleKnotSpacingNm),
                                  kUpsampleKnotCount - 2);
        const double beyond = std::max(std::abs(raw[knot] - std::clamp(raw[knot], 0.0, 1.0)),
                                       std::abs(raw[knot + 1] - std::clamp(raw[knot + 1], 0.0, 1.0)));
        crossing_lanes += beyond > 0.0;
        CAPTURE(i);
        CAPTURE(lane);
        CHECK(std::abs(got[lane] - want[lane]) <= beyond + 2e-6);
      }
      // Unclamped, both are the same linear interpolation of Φc.
      const Float4 free_got = up.basis().evaluate(c, lambda.lambda_nm(), Float4(-INFINITY), Float4(INFINITY));
      const Float4 free_want = up.basis().evaluate_clamped(c, lambda.lambda_nm(), Float4(-INFINITY), Float4(INFINITY));
      for (int lane = 0; lane < kLaneCount; ++lane) CHECK(std::abs(free_got[lane] - free_want[lane]) <= 2e-6);
    }
    CHECK(crossing_lanes > 0);  // the random colours include ringing ones: the bound above was exercised
  }
}

TEST_CASE("fast path: the AVX2 and SSE evaluation kernels agree, and evaluate_blend is evaluate of the blend") {
  // evaluate() runs whichever kernel the CPU chose; both builds are compared here directly on the same cached
  // basis values (the AVX2 one only where the CPU has it), then the texture lookup's fused blend against
  // evaluate() of the blend formed in memory. A wrong lane order, a lost half of the 16 terms or a wrong weight
  // moves values by far more than the float rounding of a 16-term sum (|c_k φ_k| ≤ ~1, so 1e-5 absolute).
  const RgbUpsampler& up = upsampler("srgb-linear");
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  Random random{29};
  for (int i = 0; i < 200; ++i) {
    CAPTURE(i);
    BasisCoefficients corners[4];
    for (BasisCoefficients& c : corners) c = up.reflectance_coefficients({random.next(), random.next(), random.next()});
    const float w0 = float(random.next()), w1 = float(random.next());
    const float weight[4] = {(1 - w0) * (1 - w1), w0 * (1 - w1), (1 - w0) * w1, w0 * w1};
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(float(random.next()));
    const UpsamplingBasis::BasisAtWavelengths& phi = up.basis().at(lambda.lambda_nm());
    const Float4 sse(upsampling_kernels::dot_lanes_sse(phi.phi[0], corners[0].c.data()));
    for (int lane = 0; lane < kLaneCount; ++lane) {
      double want = 0;
      for (int k = 0; k < kUpsamplingBasisSize; ++k) want += double(phi.phi[lane][k]) * corners[0].c[k];
      CHECK(std::abs(sse[lane] - want) <= 1e-5);
    }
    if (avx2) {
      const Float4 fused(upsampling_kernels::dot_lanes_avx2(phi.phi[0], corners[0].c.data()));
      CHECK(max_lane(abs(fused - sse)) <= 1e-5f);
    }
    BasisCoefficients blend;
    for (int k = 0; k < kUpsamplingBasisSize; ++k)
      for (int j = 0; j < 4; ++j) blend.c[k] += weight[j] * corners[j].c[k];
    const BasisCoefficients* corner_pointers[4] = {&corners[0], &corners[1], &corners[2], &corners[3]};
    const Float4 free_lo(-INFINITY), free_hi(INFINITY);
    const Float4 want = up.basis().evaluate(blend, lambda.lambda_nm(), free_lo, free_hi);
    CHECK(max_lane(abs(up.basis().evaluate_blend(corner_pointers, weight, lambda.lambda_nm(), free_lo, free_hi) -
                       want)) <= 1e-5f);
    const Float4 sse_blend(upsampling_kernels::blend_dot_lanes_sse(phi.phi[0], corner_pointers, weight));
    CHECK(max_lane(abs(sse_blend - want)) <= 1e-5f);
  }
}

TEST_CASE("fast path: the per-thread basis cache never serves one basis's rows to another") {
  // sRGB (D65) and ACEScg (ACES white) have different tables, hence different bases; evaluated alternately at the
  // same wavelengths, each must give its own basis's values (the cache is keyed by the basis, not only by λ).
  const RgbUpsampler& a = upsampler("srgb-linear");
  const RgbUpsampler& b = upsampler("acescg");
  const BasisCoefficients ca = a.reflectance_coefficients({0.2, 0.5, 0.3});
  const BasisCoefficients cb = b.reflectance_coefficients({0.2, 0.5, 0.3});
  const Float4 lambda(412.0f, 505.5f, 611.0f, 700.25f);
  const Float4 free_lo(-INFINITY), free_hi(INFINITY);
  const Float4 want_a = a.basis().evaluate_clamped(ca, lambda, free_lo, free_hi);
  const Float4 want_b = b.basis().evaluate_clamped(cb, lambda, free_lo, free_hi);
  // The coefficients of one basis read with the other basis's rows give another spectrum: the check can fail.
  CHECK(max_lane(abs(b.basis().evaluate_clamped(ca, lambda, free_lo, free_hi) - want_a)) > 1e-3f);
  for (int round = 0; round < 3; ++round) {
    const Float4 got_a = a.basis().evaluate(ca, lambda, free_lo, free_hi);
    const Float4 got_b = b.basis().evaluate(cb, lambda, free_lo, free_hi);
    for (int lane = 0; lane < kLaneCount; ++lane) {
      CHECK(got_a[lane] == doctest::Approx(want_a[lane]).epsilon(1e-5));
      CHECK(got_b[lane] == doctest::Approx(want_b[lane]).epsilon(1e-5));
    }
  }
  // A basis built after another was destroyed gets a new identity even at a reused address.
  Float4 first;
  {
    const RgbUpsampler d65(test::library(), RgbColourSpace::named("srgb-linear"));
    first = d65.basis().evaluate(d65.reflectance_coefficients({0.2, 0.5, 0.3}), lambda, free_lo, free_hi);
  }
  const RgbUpsampler aces(test::library(), RgbColourSpace::named("acescg"));
  const BasisCoefficients c = aces.reflectance_coefficients({0.2, 0.5, 0.3});
  const Float4 got = aces.basis().evaluate(c, lambda, free_lo, free_hi);
  const Float4 want = aces.basis().evaluate_clamped(c, lambda, free_lo, free_hi);
  for (int lane = 0; lane < kLaneCount; ++lane) CHECK(got[lane] == doctest::Approx(want[lane]).epsilon(1e-5));
}

TEST_CASE("fast upsampling: the pseudo-angle cell location agrees with atan2 and the hull radius table") {
  // locate() replaces atan2 by a 2048-step table over the pseudo-angle p (upsampling_basis.h): its angle cell must
  // be θ·angle_count/2π within the lerp's bound h²/8·|θ''| ≤ 1e-6 rad (1e-5 allowed for float storage of the
  // cell coordinate), and its radius (from the tabulated 1/R) never above the hull's by more than the lerp's
  // chord error of the concave 1/R between vertices (~2e-6; 1e-5 allowed) and at most 2e-3 below it (at the
  // hull's vertices, where the lerp cuts across 1/R's kink), at random directions and on the axes and diagonals,
  // where p has its branch points.
  for (const char* space : {"srgb-linear", "acescg"}) {
    const UpsamplingBasis& basis = upsampler(space).basis();
    const int angle_count = upsampler(space).table().angle_count;
    Random random{99};
    double worst_below = 0;
    for (int i = 0; i < 20000; ++i) {
      double dx = random.next() - 0.5, dy = random.next() - 0.5;
      if (i < 8) dx = std::cos(i * std::numbers::pi / 4), dy = std::sin(i * std::numbers::pi / 4);
      if (i == 8) dx = -1, dy = -0.0;  // θ = π from below: the wrap of the angle cells
      double theta = std::atan2(dy, dx);
      if (theta < 0) theta += 2 * std::numbers::pi;
      const UpsamplingBasis::PolarCell cell = basis.locate(dx, dy);
      const double expected_cell = theta / (2 * std::numbers::pi) * angle_count;
      // Angles just below 2π may land on either side of the seam (cell coordinate ≈ 0 or ≈ angle_count).
      const double cell_error = std::min(std::abs(cell.angle_cell - expected_cell),
                                         std::abs(std::abs(cell.angle_cell - expected_cell) - angle_count));
      CHECK_MESSAGE(cell_error * (2 * std::numbers::pi / angle_count) <= 1e-5,
                    space << " (" << dx << ", " << dy << "): cell " << cell.angle_cell << " expected " << expected_cell);
      const double exact = upsampler(space).gamut().boundary_radius(std::atan2(dy, dx)) *
                           upsampler(space).table().usable_fraction;
      CHECK_MESSAGE(cell.usable_radius() <= exact * (1 + 1e-5),
                    space << " (" << dx << ", " << dy << "): radius " << cell.usable_radius() << " above the hull's " << exact);
      CHECK_MESSAGE(cell.usable_radius() >= exact * (1 - 2e-3),
                    space << " (" << dx << ", " << dy << "): radius " << cell.usable_radius() << " expected " << exact);
      worst_below = std::max(worst_below, 1 - cell.usable_radius() / exact);
    }
    MESSAGE(std::string(space) << ": locate()'s radius at most " << worst_below << " below the hull's (relative)");
  }
}

namespace {

/// A chromaticity inside `up`'s usable gamut (ρ ≤ 1) drawn from random RGB of its space, located as
/// RgbUpsampler locates it; false for colours outside (the caller draws again).
struct LocatedColour {
  Chromaticity xy;
  UpsamplingBasis::PolarCell cell;
  double rho = 0;
};
bool locate_random(const RgbUpsampler& up, Random& random, LocatedColour& out) {
  const Xyz xyz = up.space().to_xyz({random.next(), random.next(), random.next()});
  const double total = xyz.x + xyz.y + xyz.z;
  if (!(xyz.y > 1e-6 && total > 0)) return false;
  out.xy = {xyz.x / total, xyz.y / total};
  const Chromaticity w = up.gamut().white();
  const double dx = out.xy.x - w.x, dy = out.xy.y - w.y;
  out.cell = up.basis().locate(dx, dy);
  out.rho = std::hypot(dx, dy) / out.cell.usable_radius();
  return out.rho <= 1.0;
}

/// XYZ of clamp(Φc, 0, upper) at the knots, in double.
Xyz clamped_xyz(const RgbUpsampler& up, const BasisCoefficients& c, double upper) {
  KnotValues knots = up.basis().knots(c);
  for (double& v : knots) v = std::clamp(v, 0.0, upper);
  return up.colorimetry().xyz_of(knots);
}

/// How far a float evaluation of the colour of Φc may be from the double one, relative to |target|₁: each term
/// a_m,i·φ_k,i·c_k carries the float rounding of the stored basis value and of the float knot sums (≤ 2⁻²² of its
/// size, with the 16-term sum's growth well inside), and the terms cancel (coefficients of both signs), so the
/// bound is on the sum of their magnitudes, not on the colour.
double float_rounding_bound(const RgbUpsampler& up, const BasisCoefficients& c, const Xyz& target) {
  double magnitude = 0;
  for (int m = 0; m < 3; ++m)
    for (int k = 0; k < kUpsamplingBasisSize; ++k)
      for (int i = 0; i < kUpsampleKnotCount; ++i)
        magnitude += std::abs(up.colorimetry().row(m)[i] * up.basis().basis(k, i) * c.c[k]);
  return std::ldexp(magnitude, -22) / (std::abs(target.x) + std::abs(target.y) + std::abs(target.z));
}

double relative_miss(const Xyz& got, const Xyz& want) {
  return (std::abs(got.x - want.x) + std::abs(got.y - want.y) + std::abs(got.z - want.z)) /
         (std::abs(want.x) + std::abs(want.y) + std::abs(want.z));
}

}  // namespace

TEST_CASE("fast path: Φc is negative only in the low blocks, and the zero-only fit reaches the full fit's colour") {
  // fit_zero_clamped computes the clamped colour from the knots of bounds.low_blocks alone (the blocks where some
  // corner's spectrum is below a tenth of its peak): a negative knot anywhere else would be left unclamped and its
  // colour missed. The fit verifies its result and falls back to the full fit, so that is a cost, not an error;
  // the interpolated coefficients must have no negative knot outside the blocks (else the fallback would be the
  // rule), in every space. The fit itself, at Y = 1 and at the emission range's ends (1e-8, 1e6): its returned
  // residual is the clamped colour's (recomputed here in double from all 95 knots, within the float rounding of
  // the sum's terms), and where the full fit (every knot, its own Jacobian) holds the colour to 1e-4 so does the
  // zero-only fit.
  for (const std::string space : test::kUpsamplerSpaces) {
    CAPTURE(space);
    const RgbUpsampler& up = upsampler(space);
    const UpsamplingBasis& basis = up.basis();
    Random random{1234};
    int ringing = 0;
    for (int i = 0; i < 3000; ++i) {
      LocatedColour colour;
      if (!locate_random(up, random, colour)) continue;
      SmoothShapeBounds bounds;
      const BasisCoefficients c = basis.smooth_coefficients_in_cell(colour.xy, colour.cell.angle_cell, colour.rho, &bounds);
      CAPTURE(colour.xy.x);
      CAPTURE(colour.xy.y);
      REQUIRE((basis.negative_blocks(c) & ~bounds.low_blocks) == 0u);
      if (!bounds.rings) continue;
      ++ringing;
      for (const double scale : {1.0, 1e-8, 1e6}) {
        BasisCoefficients zero_only = c, full = c;
        zero_only *= float(scale);
        full *= float(scale);
        const Xyz target{scale * bounds.colour.x, scale * bounds.colour.y, scale * bounds.colour.z};
        const double left = basis.fit_zero_clamped(zero_only, bounds, float(scale), target, INFINITY);
        const double left_full = basis.fit_clamped(full, basis.correction_directions(bounds, float(scale)), target, INFINITY);
        CHECK(std::abs(relative_miss(clamped_xyz(up, zero_only, INFINITY), target) - left) <=
              float_rounding_bound(up, zero_only, target));
        if (left_full <= 1e-4) CHECK(left <= 1e-4);
      }
    }
    CAPTURE(ringing);
    CHECK(ringing > 100);  // the property is exercised where it matters
  }
}

TEST_CASE("fast path: the SSE4.1 setup kernels give the AVX2 kernels' coefficients") {
  // A basis built with Kernels::sse41 runs the baseline blend, clamped passes and zero-only passes; on a CPU
  // with AVX2 the upsampler's own basis runs the 8-lane fused builds. Both must give the same coefficients and
  // residuals up to float rounding of 16- and 96-term sums (1e-5 of the coefficients' size). On a CPU without
  // AVX2 both are the baseline and this compares it with itself.
  const RgbUpsampler& up = upsampler("srgb-linear");
  const UpsamplingBasis sse(up.table(), up.colorimetry(), UpsamplingBasis::Kernels::sse41);
  const UpsamplingBasis& best = up.basis();
  auto close = [](const BasisCoefficients& a, const BasisCoefficients& b) {
    float size = 0, difference = 0;
    for (int k = 0; k < kUpsamplingBasisSize; ++k)
      size = std::max(size, std::abs(a.c[k])), difference = std::max(difference, std::abs(a.c[k] - b.c[k]));
    return difference <= 1e-5f * size;
  };
  Random random{31};
  int fits = 0;
  for (int i = 0; i < 2000; ++i) {
    LocatedColour colour;
    if (!locate_random(up, random, colour)) continue;
    CAPTURE(i);
    SmoothShapeBounds bounds_sse, bounds_best;
    BasisCoefficients a = sse.smooth_coefficients_in_cell(colour.xy, colour.cell.angle_cell, colour.rho, &bounds_sse);
    BasisCoefficients b = best.smooth_coefficients_in_cell(colour.xy, colour.cell.angle_cell, colour.rho, &bounds_best);
    REQUIRE(close(a, b));
    CHECK(bounds_sse.low_blocks == bounds_best.low_blocks);
    const auto directions_sse = sse.correction_directions(bounds_sse, 1.0f);
    const auto directions_best = best.correction_directions(bounds_best, 1.0f);
    for (int m = 0; m < 3; ++m) CHECK(close(directions_sse[m], directions_best[m]));
    if (!bounds_best.rings) continue;
    ++fits;
    const Xyz target = bounds_best.colour;
    BasisCoefficients a_zero = a, b_zero = b;
    const double left_sse = sse.fit_zero_clamped(a_zero, bounds_sse, 1.0f, target, INFINITY);
    const double left_best = best.fit_zero_clamped(b_zero, bounds_best, 1.0f, target, INFINITY);
    CHECK(close(a_zero, b_zero));
    CHECK(std::abs(left_sse - left_best) <= 1e-6);
    // The full fit with clamping at 1 too: scaled so that its peak sits 1 % above 1.
    alignas(16) float knots[kUpsampleKnotCount + 1];
    const float scale = 1.01f / best.knots_float(b, knots);
    a *= scale, b *= scale;
    const Xyz scaled_target = clamped_xyz(up, b, 1.0);
    CHECK(std::abs(sse.fit_clamped(a, sse.correction_directions(bounds_sse, scale), scaled_target, 1.0f) -
                   best.fit_clamped(b, best.correction_directions(bounds_best, scale), scaled_target, 1.0f)) <= 1e-6);
    CHECK(close(a, b));
  }
  CHECK(fits > 50);
}

TEST_CASE("fast path: on the wide spaces' cubes, every colour the fast path does not flag is within ΔE00 0.05") {
  // What `mapped` promises callers: a colour not reported moved is the input colour (the max 0.05). The
  // wide spaces hold the hard cases: purples the basis cannot hold at zero (flagged), and greens whose fit raises
  // the peak above 1 (Rec.2020 (3, 16, 0)/32: the cheaper fit's verification must hand it to the full fit, else
  // clamping at 1 takes 2e-3 of its colour, ΔE00 0.054, unflagged). On the 33³ grids.
  for (const char* space : {"rec2020", "acescg"}) {
    CAPTURE(space);
    const RgbUpsampler& up = upsampler(space);
    int unflagged = 0;
    for (int r = 0; r <= 32; ++r)
      for (int g = 0; g <= 32; ++g)
        for (int b = 0; b <= 32; ++b) {
          const Rgb rgb{r / 32.0, g / 32.0, b / 32.0};
          bool mapped = true;
          up.reflectance_coefficients(rgb, &mapped);
          if (mapped) continue;
          ++unflagged;
          CAPTURE(r);
          CAPTURE(g);
          CAPTURE(b);
          CHECK(delta_e(up, up.space().to_xyz(rgb), up.colorimetry().xyz_of(fast_knots(up, rgb))) <= 0.05);
        }
    CHECK(unflagged > 15000);
  }
}
