// Chromatic adaptation transforms against published matrices and their defining property.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/colour_spaces/chromatic_adaptation.h"

using namespace rimu;

namespace {

// ASTM E308-01 white points (1931 2°, Y = 1), the whites Lindbloom used for his published CAT matrices.
constexpr Xyz kD65Astm{0.95047, 1.0, 1.08883};
constexpr Xyz kD50Astm{0.96422, 1.0, 0.82521};
constexpr Xyz kAAstm{1.09850, 1.0, 0.35585};

constexpr CatMethod kAllMethods[] = {CatMethod::bradford, CatMethod::cat02, CatMethod::cat16, CatMethod::von_kries,
                                     CatMethod::xyz_scaling};

}  // namespace

TEST_CASE("Bradford D65->D50 matches Lindbloom's published matrix to its 7 decimals") {
  // B. Lindbloom, "Chromatic Adaptation" (brucelindbloom.com, Eqn_ChromAdapt.html), Bradford D65 -> D50,
  // computed from the Bradford cone matrix and the ASTM E308 whites above and printed to 7 decimals:
  // tolerance is half a unit of the 7th decimal.
  const double published[3][3] = {
      {1.0478112, 0.0228866, -0.0501270}, {0.0295424, 0.9904844, -0.0170491}, {-0.0092345, 0.0150436, 0.7521316}};
  const Matrix3 m = chromatic_adaptation_matrix(kD65Astm, kD50Astm, CatMethod::bradford);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      CAPTURE(i);
      CAPTURE(j);
      CAPTURE(m(i, j));
      CHECK(std::abs(m(i, j) - published[i][j]) <= 5e-8 + 1e-13);
    }
}

TEST_CASE("every CAT maps the source white exactly onto the destination white, and inverts") {
  // M_A⁻¹·diag(d/s)·M_A applied to the source white gives M_A⁻¹·(cone of d) = d by construction; only double
  // rounding remains.
  const Xyz whites[] = {kD65Astm, kD50Astm, kAAstm, white_point_xyz(RgbColourSpace::named("acescg"))};
  for (CatMethod method : kAllMethods)
    for (const Xyz& source : whites)
      for (const Xyz& destination : whites) {
        CAPTURE(int(method));
        const Xyz mapped = chromatic_adaptation_matrix(source, destination, method).apply(source);
        CHECK(std::abs(mapped.x - destination.x) <= 1e-13);
        CHECK(std::abs(mapped.y - destination.y) <= 1e-13);
        CHECK(std::abs(mapped.z - destination.z) <= 1e-13);
        // Adapting there and back is the identity.
        const Matrix3 round_trip = chromatic_adaptation_matrix(destination, source, method) *
                                   chromatic_adaptation_matrix(source, destination, method);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) CHECK(std::abs(round_trip(i, j) - (i == j ? 1.0 : 0.0)) <= 1e-13);
      }
}

TEST_CASE("XYZ scaling is the diagonal of the white ratios, the methods differ off the white") {
  const Matrix3 scaling = chromatic_adaptation_matrix(kD65Astm, kD50Astm, CatMethod::xyz_scaling);
  CHECK(scaling(0, 0) == doctest::Approx(0.96422 / 0.95047).epsilon(1e-15));
  CHECK(scaling(2, 2) == doctest::Approx(0.82521 / 1.08883).epsilon(1e-15));
  CHECK(scaling(0, 1) == 0.0);
  // A saturated colour lands in different places under different cone spaces (the reason the choice matters).
  const Xyz red{0.4124, 0.2126, 0.0193};
  const Xyz by_bradford = chromatic_adaptation_matrix(kD65Astm, kD50Astm, CatMethod::bradford).apply(red);
  const Xyz by_scaling = scaling.apply(red);
  CHECK(std::abs(by_bradford.x - by_scaling.x) > 1e-3);
}

TEST_CASE("Rec.709 -> Rec.2020 RGB conversion matches ITU-R BT.2087") {
  // ITU-R BT.2087-0 (2015) section 2 prints the linear-light 709 -> 2020 matrix to 4 decimals. Both spaces
  // have white D65, so the CAT is the identity and the matrix is NPM_2020⁻¹ · NPM_709. Tolerance: half a unit
  // of the 4th decimal.
  const double published[3][3] = {{0.6274, 0.3293, 0.0433}, {0.0691, 0.9195, 0.0114}, {0.0164, 0.0880, 0.8956}};
  const Matrix3 m = rgb_conversion_matrix(RgbColourSpace::named("rec709"), RgbColourSpace::named("rec2020"));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      CAPTURE(i);
      CAPTURE(j);
      CAPTURE(m(i, j));
      CHECK(std::abs(m(i, j) - published[i][j]) <= 5e-5 + 1e-12);
    }
}

TEST_CASE("converting between spaces with different whites keeps RGB white at (1,1,1)") {
  // A von Kries CAT maps white to white, so (1,1,1) in ACEScg (ACES white) must become (1,1,1) in sRGB (D65).
  for (CatMethod method : kAllMethods) {
    CAPTURE(int(method));
    const Matrix3 m =
        rgb_conversion_matrix(RgbColourSpace::named("acescg"), RgbColourSpace::named("srgb-linear"), method);
    const auto white = m.apply(std::array<double, 3>{1.0, 1.0, 1.0});
    for (double channel : white) CHECK(std::abs(channel - 1.0) <= 1e-13);
  }
}
