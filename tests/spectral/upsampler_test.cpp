// The RGB → spectrum upsampler (rgb_upsampler.h): exact white and greys, the hard cases of issue 3, round trips.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "spectral/upsampling/smoothest_spectrum.h"
#include "test_support.h"
#include "upsampler_fixture.h"

using namespace rimu;

namespace {

using test::upsampler;

/// One unit in the last place of a float near `x`: the resolution the knots are stored with.
float ulp(float x) { return std::nextafter(x, 2 * x + 1) - x; }

}  // namespace

TEST_CASE("RGB (1,1,1) upsamples to exactly 1.0 at every wavelength, in every space") {
  // By construction (KnotColorimetry rescales X and Z so the flat spectrum is the space's white), the white's
  // smoothest spectrum is flat; the run time reaches it to ~1e-15 in double, which rounds to exactly 1.0f.
  for (const char* space : test::kUpsamplerSpaces) {
    CAPTURE(space);
    const auto u = upsampler(space).upsample_reflectance({1, 1, 1});
    CHECK_FALSE(u.gamut_mapped);
    for (int i = 0; i < kUpsampleKnotCount; ++i) CHECK(u.spectrum.samples().knot(i) == 1.0f);
    const SampledWavelengths lambda(Float4(360.0f, 455.5f, 612.25f, 830.0f), Float4(1.0f));
    for (int lane = 0; lane < 4; ++lane) CHECK(u.spectrum.evaluate(lambda)[lane] == 1.0f);
    CHECK(u.delta_e2000 < 1e-6);
  }
}

TEST_CASE("RGB (0.18,0.18,0.18) upsamples to a flat 0.18 within one float ulp") {
  // The double result is 0.18·(1 ± 1e-15); rounding to float may land one ulp (1.5e-8) either side of 0.18f.
  for (const char* space : test::kUpsamplerSpaces) {
    CAPTURE(space);
    const auto u = upsampler(space).upsample_reflectance({0.18, 0.18, 0.18});
    CHECK_FALSE(u.gamut_mapped);
    for (int i = 0; i < kUpsampleKnotCount; ++i) CHECK(std::abs(u.spectrum.samples().knot(i) - 0.18f) <= ulp(0.18f));
  }
}

TEST_CASE("black upsamples to exactly zero, as reflectance and as emission") {
  const auto& up = upsampler("srgb-linear");
  const auto r = up.upsample_reflectance({0, 0, 0});
  const auto e = up.upsample_emission({0, 0, 0});
  CHECK_FALSE(r.gamut_mapped);
  CHECK_FALSE(e.gamut_mapped);
  CHECK(r.delta_e2000 == 0.0);
  const SampledWavelengths lambda(Float4(400.0f, 500.0f, 600.0f, 700.0f), Float4(1.0f));
  for (int lane = 0; lane < 4; ++lane) {
    CHECK(r.spectrum.evaluate(lambda)[lane] == 0.0f);
    CHECK(e.spectrum.evaluate(lambda)[lane] == 0.0f);
  }
}

TEST_CASE("NaN and infinite components are an InputError that names the value and where it came from") {
  const auto& up = upsampler("srgb-linear");
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  for (double b : bad) {
    CHECK_THROWS_AS(up.upsample_reflectance({0.5, b, 0.1}), InputError);
    CHECK_THROWS_AS(up.upsample_emission({b, 0.5, 0.1}), InputError);
  }
  try {
    up.upsample_reflectance({0.5, std::nan(""), 0.1}, {"scene.json", 12, "/materials/0/albedo"});
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("not finite") != std::string::npos);
    CHECK(e.where().key == "/materials/0/albedo");
  }
}

TEST_CASE("negative components: inside the locus reproduced exactly, otherwise mapped, never a negative value") {
  const auto& up = upsampler("srgb-linear");
  SUBCASE("a cyan beyond sRGB but inside the spectral locus keeps its negative red through the round trip") {
    // sRGB (−0.05, 0.5, 0.5): xy = (0.200, 0.320), well inside the locus. Round-trip error comes only from the
    // float knots (relative 6e-8), so RGB returns to 1e-6.
    const auto u = up.upsample_reflectance({-0.05, 0.5, 0.5});
    CHECK_FALSE(u.gamut_mapped);
    CHECK(u.spectrum.samples().min_value() >= 0.0f);
    const Rgb back = up.rgb_of(u.spectrum);
    CHECK(back.r == doctest::Approx(-0.05).epsilon(1e-5));
    CHECK(back.g == doctest::Approx(0.5).epsilon(1e-6));
  }
  SUBCASE("negative luminance gives black, flagged as mapped") {
    // (1, −0.5, −0.5): Y = 0.2126 − 0.5·(0.7152 + 0.0722) < 0 (ITU-R BT.709 luminance weights).
    const auto u = up.upsample_reflectance({1, -0.5, -0.5});
    CHECK(u.gamut_mapped);
    CHECK(u.spectrum.max_value() == 0.0);
    CHECK(u.delta_e2000 > 0.0);
  }
  SUBCASE("a chromaticity beyond the locus moves towards the white, stays non-negative, and is reported") {
    const auto u = up.upsample_reflectance({-0.3, 1.0, -0.2});
    CHECK(u.gamut_mapped);
    CHECK(u.spectrum.samples().min_value() >= 0.0f);
    CHECK(u.spectrum.samples().max_value() <= 1.0f);
    CHECK(u.delta_e2000 > 1.0);
  }
}

TEST_CASE("every space's primaries give spectra in [0,1], mapped where a smooth reflectance cannot reach them") {
  // No primary of these spaces at full intensity is a smooth reflectance: the brightness limit at sRGB red's
  // chromaticity is below its Y = 0.2126, and AP0/AP1 primaries lie outside the spectral locus.
  for (const char* space : test::kUpsamplerSpaces) {
    CAPTURE(space);
    for (const Rgb p : {Rgb{1, 0, 0}, Rgb{0, 1, 0}, Rgb{0, 0, 1}}) {
      INFO("primary (", p.r, ", ", p.g, ", ", p.b, ")");
      const auto u = upsampler(space).upsample_reflectance(p);
      CHECK(u.spectrum.samples().min_value() >= 0.0f);
      CHECK(u.spectrum.samples().max_value() <= 1.0f);
      CHECK(u.gamut_mapped);
      // Half intensity of a primary's chromaticity, when that chromaticity is inside the gamut, needs at most a
      // brightness clip: the chromaticity of the result must be the input's.
      const auto half = upsampler(space).upsample_reflectance({p.r * 0.05, p.g * 0.05, p.b * 0.05});
      const Xyz in = upsampler(space).space().to_xyz({p.r * 0.05, p.g * 0.05, p.b * 0.05});
      const double rho = upsampler(space).gamut().relative_radius(chromaticity_of(in));
      if (rho < upsampler(space).table().usable_fraction) {
        CHECK_FALSE(half.gamut_mapped);
        CHECK(half.delta_e2000 < 1e-4);
      }
    }
  }
}

TEST_CASE("round trip of every 17³ grid colour of sRGB, ACEScg and Rec.2020: exact unless mapped, always in [0,1]") {
  // Colours that need no mapping are reproduced to float precision: the run time re-imposes the exact XYZ in
  // double, then stores knots as floats (relative error ≤ 6e-8, i.e. ΔE00 ~ 1e-5 at most near black, where
  // CIELAB's slope is largest). Measured max over the 33³ grid: 2.3e-6 (docs/upsampling.md); asserted ≤ 1e-4.
  for (const char* space : {"srgb-linear", "acescg", "rec2020"}) {
    CAPTURE(space);
    const auto& up = upsampler(space);
    double worst = 0;
    for (int r = 0; r <= 16; ++r)
      for (int g = 0; g <= 16; ++g)
        for (int b = 0; b <= 16; ++b) {
          const auto u = up.upsample_reflectance({r / 16.0, g / 16.0, b / 16.0});
          REQUIRE(u.spectrum.samples().min_value() >= 0.0f);
          REQUIRE(u.spectrum.samples().max_value() <= 1.0f);
          if (!u.gamut_mapped) {
            worst = std::max(worst, u.delta_e2000);
          } else if (std::string(space) == "srgb-linear" && r + g + b > 0) {
            // sRGB lies inside the knot gamut, so its mapping only clips brightness: chromaticity is kept to the
            // float precision of the knots (relative 6e-8 on X, Y, Z; 1e-6 in xy leaves margin for dark colours).
            const Chromaticity want = chromaticity_of(up.space().to_xyz({r / 16.0, g / 16.0, b / 16.0}));
            const Chromaticity got = chromaticity_of(up.xyz_of(u.spectrum.samples()));
            CHECK(std::abs(got.x - want.x) <= 1e-6);
            CHECK(std::abs(got.y - want.y) <= 1e-6);
          }
        }
    CHECK(worst <= 1e-4);
  }
}

TEST_CASE("the round trip also holds through colorimetry.h with the illuminant's own table") {
  // An independent path: reflectance_xyz (CIE 15 1 nm sum) of the upsampled spectrum under CIE D65, then the
  // sRGB matrix. It differs from the internal one only by the D65 table's white (0.31272, 0.32903) versus the
  // rounded (0.3127, 0.3290): 1 + O(2e-4) on X and Z (KnotColorimetry), so RGB agrees to 5e-4.
  const auto& up = upsampler("srgb-linear");
  const Rgb in{0.7, 0.4, 0.2};
  const auto u = up.upsample_reflectance(in);
  REQUIRE_FALSE(u.gamut_mapped);
  const Xyz xyz = reflectance_xyz(u.spectrum, *up.illuminant(), test::library().observer(StandardObserver::cie1931_2deg));
  const Rgb back = up.space().from_xyz({xyz.x / 100, xyz.y / 100, xyz.z / 100});
  CHECK(back.r == doctest::Approx(in.r).epsilon(5e-4));
  CHECK(back.g == doctest::Approx(in.g).epsilon(5e-4));
  CHECK(back.b == doctest::Approx(in.b).epsilon(5e-4));
}

TEST_CASE("chromaticities on and just inside the gamut edge: non-negative, continuous like the exact optimum") {
  // Near the edge the smoothest spectrum itself is very sensitive: its peak grows like 1/(1 − ρ), and the exact
  // QP solution moves by up to 3.8 % of its peak when ρ moves by 1e-4 at ρ = 1 (measured over 360 angles,
  // docs/upsampling.md; the table's spectra move by up to 1.6 %). Continuity is asserted at that scale: ≤ 5 % of
  // the peak per 1e-4 in ρ. A jump between table cells, or a discontinuous gamut clip, would be of the order
  // of the peak itself.
  const auto& up = upsampler("srgb-linear");
  const double edge = up.table().usable_fraction;
  for (int a = 0; a < 72; ++a) {
    const double angle = a * 2 * 3.14159265358979 / 72 + 0.01;
    CAPTURE(angle);
    const Chromaticity xy_on = up.gamut().at(angle, edge), xy_inside = up.gamut().at(angle, edge * (1 - 1e-4));
    const KnotValues on = up.smooth_shape(xy_on), inside = up.smooth_shape(xy_inside);
    const auto exact_on = smoothest_knot_spectrum(up.colorimetry(), xyz_from_xyY(xy_on, 1.0));
    const auto exact_inside = smoothest_knot_spectrum(up.colorimetry(), xyz_from_xyY(xy_inside, 1.0));
    REQUIRE(exact_on);
    REQUIRE(exact_inside);
    double peak = 0, jump = 0, exact_jump = 0;
    for (int i = 0; i < kUpsampleKnotCount; ++i) {
      REQUIRE(on[i] >= 0.0);
      REQUIRE(inside[i] >= 0.0);
      peak = std::max(peak, on[i]);
      jump = std::max(jump, std::abs(on[i] - inside[i]));
      exact_jump = std::max(exact_jump, std::abs(exact_on->knots[i] - exact_inside->knots[i]));
    }
    CHECK(jump <= 0.05 * peak);
    CHECK(exact_jump <= 0.05 * peak);
  }
}

TEST_CASE("away from the edge the table's spectra are nearly as smooth as the exact optimum") {
  // Bilinear interpolation of the table plus the colour correction cannot be smoother than the optimum, and is
  // rougher where spectra change fast between nodes. Measured worst over 360 angles (docs/upsampling.md):
  // 1.2 % at ρ = 0.5, 7.8 % at ρ = 0.9 (of the usable gamut); asserted 2 % and 10 %.
  const auto& up = upsampler("srgb-linear");
  for (const auto& [rho, bound] : {std::pair{0.5, 1.02}, std::pair{0.9, 1.10}}) {
    for (int a = 0; a < 72; ++a) {
      const double angle = a * 2 * 3.14159265358979 / 72 + 0.01;
      CAPTURE(angle);
      CAPTURE(rho);
      const Chromaticity xy = up.gamut().at(angle, rho * up.table().usable_fraction);
      const auto exact = smoothest_knot_spectrum(up.colorimetry(), xyz_from_xyY(xy, 1.0));
      REQUIRE(exact);
      const double ratio = roughness(up.smooth_shape(xy)) / roughness(exact->knots);
      CHECK(ratio >= 1.0 - 1e-9);
      CHECK(ratio <= bound);
    }
  }
}

TEST_CASE("small input changes give small spectrum changes (continuity, including across the brightness clip)") {
  const auto& up = upsampler("srgb-linear");
  // 0.9 red is beyond the brightness limit at that chromaticity: the clip must be continuous too.
  for (const Rgb base : {Rgb{0.5, 0.3, 0.2}, Rgb{0.9, 0.1, 0.05}, Rgb{0.02, 0.6, 0.9}}) {
    const auto a = up.upsample_reflectance(base);
    const auto b = up.upsample_reflectance({base.r + 1e-5, base.g, base.b - 1e-5});
    float jump = 0;
    for (int i = 0; i < kUpsampleKnotCount; ++i)
      jump = std::max(jump, std::abs(a.spectrum.samples().knot(i) - b.spectrum.samples().knot(i)));
    // The map from RGB to knots has a slope of O(1-10) away from the locus; 1e-3 would catch a cell jump.
    CHECK(jump <= 1e-3f);
  }
}

TEST_CASE("emission keeps its luminance from 1e-8 to 1e6 and is illuminant-shaped for white") {
  const auto& up = upsampler("srgb-linear");
  const Observer& observer = test::library().observer(StandardObserver::cie1931_2deg);
  for (const double level : {1e-8, 1.0, 1e6}) {
    CAPTURE(level);
    const Rgb in{0.8 * level, 0.2 * level, 0.1 * level};
    const auto e = up.upsample_emission(in);
    CHECK_FALSE(e.gamut_mapped);
    // emission_xyz: K_m Σ S ȳ Δλ in cd/m²; Y is exact up to float knots and a float scale (relative 1e-6).
    const Xyz xyz = emission_xyz(e.spectrum, observer);
    CHECK(xyz.y == doctest::Approx(up.space().to_xyz(in).y).epsilon(1e-6));
    CHECK(e.spectrum.shape().min_value() >= 0.0f);
    CHECK(std::isfinite(e.spectrum.max_value()));
  }
  // White: the spectrum is the space's illuminant (CIE D65) times a constant.
  const auto white = up.upsample_emission({2, 2, 2});
  const double ratio_560 = white.spectrum.value(560) / up.illuminant()->value(560);
  for (const double l : {400.0, 455.0, 532.0, 700.0})
    CHECK(white.spectrum.value(l) / up.illuminant()->value(l) == doctest::Approx(ratio_560).epsilon(1e-6));
}

TEST_CASE("the four-lane evaluation equals the scalar one") {
  const auto u = upsampler("acescg").upsample_reflectance({0.3, 0.6, 0.1});
  const SampledWavelengths lambda(Float4(361.3f, 498.7f, 650.0f, 829.9f), Float4(1.0f));
  const Float4 lanes = u.spectrum.evaluate(lambda);
  for (int lane = 0; lane < 4; ++lane)
    CHECK(lanes[lane] == doctest::Approx(u.spectrum.value(lambda.lambda_nm(lane))).epsilon(1e-6));
}

TEST_CASE("the smoothest spectrum of the white is flat, and the table agrees with the optimiser at its nodes") {
  const auto& up = upsampler("rec2020");
  const auto flat = smoothest_knot_spectrum(up.colorimetry(), up.colorimetry().white_xyz());
  REQUIRE(flat);
  for (double v : flat->knots) CHECK(v == doctest::Approx(1.0).epsilon(1e-12));
  // A grid node: the stored 16-bit shape (resolution 1/65535 of the peak) against a fresh solve.
  const UpsamplingTable& t = up.table();
  const int a = 17, r = 9;
  const Chromaticity xy = up.gamut().at(2 * 3.14159265358979323846 * a / t.angle_count, t.radius_of_row(r) * t.usable_fraction);
  const auto exact = smoothest_knot_spectrum(up.colorimetry(), xyz_from_xyY(xy, 1.0));
  REQUIRE(exact);
  const double peak = *std::max_element(exact->knots.begin(), exact->knots.end());
  for (int i = 0; i < kUpsampleKnotCount; ++i)
    CHECK(std::abs(t.shapes[t.entry(a, r) * kUpsampleKnotCount + i] / 65535.0 - exact->knots[i] / peak) <= 1.0 / 65535);
}

TEST_CASE("a colour space whose white has no table is an InputError") {
  const RgbColourSpace odd("odd", {0.64, 0.33}, {0.3, 0.6}, {0.15, 0.06}, {0.35, 0.35});
  CHECK_THROWS_AS(RgbUpsampler(test::library(), odd), InputError);
}

TEST_CASE("reflectance_spectrum (textures' per-lookup path) is upsample_reflectance's spectrum, bit for bit") {
  // The same knots through the same code, minus the diagnostics: compared with ==, including black, negative
  // components (inside and outside the locus), colours above the brightness limit and out-of-gamut primaries.
  std::vector<Rgb> inputs = {{0, 0, 0}, {1, 1, 1}, {0.18, 0.18, 0.18}, {-0.1, 0.5, 0.2}, {-1, -1, 0.1},
                             {5, 0.1, 0.1}, {0, 0, -1}, {1e-9, 2e-9, 0}};
  for (int r = 0; r <= 8; ++r)
    for (int g = 0; g <= 8; ++g)
      for (int b = 0; b <= 8; ++b) inputs.push_back({r / 8.0, g / 8.0, b / 8.0});
  for (const char* space : test::kUpsamplerSpaces)
    for (const Rgb& rgb : inputs) {
      CAPTURE(space);
      CAPTURE(rgb.r);
      CAPTURE(rgb.g);
      CAPTURE(rgb.b);
      const KnotSamples full = upsampler(space).upsample_reflectance(rgb).spectrum.samples();
      const KnotSamples lean = upsampler(space).reflectance_spectrum(rgb).samples();
      bool identical = true;
      for (int i = 0; i < kUpsampleKnotCount; ++i) identical = identical && full.knot(i) == lean.knot(i);
      CHECK(identical);
    }
}
