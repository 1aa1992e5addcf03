// CIE94 and CMC(l:c) against the values colour-science (colour/difference/tests/test_delta_e.py, v0.4) publishes for
// its reference pairs, to the 8 decimals it prints; and their asymmetry.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/colorimetry/delta_e_94_cmc.h"

using namespace rimu;

namespace {
const Lab kReference{100.0, 21.57210357, 272.22819350};
const Lab kSamples[3] = {{100.0, 426.67945353, 72.39590835}, {100.0, 74.05216981, 276.45318193},
                         {100.0, 8.32281957, -73.58297716}};
}  // namespace

TEST_CASE("CIE94 matches colour-science's graphic-arts and textiles values") {
  const double graphic_arts[3] = {83.7792255009, 10.0539319546, 57.5354537067};
  const double textiles[3] = {88.33555305, 10.61265789, 60.3686872611};
  for (int i = 0; i < 3; ++i) {
    CAPTURE(i);
    CHECK(std::abs(delta_e_1994(kReference, kSamples[i]) - graphic_arts[i]) <= 5e-9);
    // 88.33555305 is printed truncated (colour-science's doctest shows 88.3355530...): one unit of its last digit.
    CHECK(std::abs(delta_e_1994(kReference, kSamples[i], Cie94Factors::textiles()) - textiles[i]) <= 1e-8);
  }
  // The reference's chroma sets the weights: swapping the colours changes the result.
  CHECK(std::abs(delta_e_1994(kSamples[0], kReference) - delta_e_1994(kReference, kSamples[0])) > 1.0);
}

TEST_CASE("CMC(l:c) matches colour-science's values, including a pair where l matters") {
  const double cmc_2_1[3] = {172.70477129, 20.59732717, 121.71841479};
  for (int i = 0; i < 3; ++i) {
    CAPTURE(i);
    CHECK(std::abs(delta_e_cmc(kReference, kSamples[i]) - cmc_2_1[i]) <= 5e-9);
    CHECK(std::abs(delta_e_cmc(kReference, kSamples[i], 1.0, 1.0) - cmc_2_1[i]) <= 5e-9);  // ΔL = 0 here
  }
  const Lab reference{48.99183622, -0.10561667, 400.65619925}, sample{50.65907324, -0.11671910, 402.82235718};
  CHECK(std::abs(delta_e_cmc(reference, sample, 2.0, 1.0) - 0.899699975683419) <= 5e-9);
  CHECK(delta_e_cmc(reference, sample, 1.0, 1.0) > 1.5 * delta_e_cmc(reference, sample, 2.0, 1.0));
}

TEST_CASE("both are 0 for identical colours, and S_L is 0.511 below L* = 16 for CMC") {
  CHECK(delta_e_1994(kReference, kReference) == 0.0);
  CHECK(delta_e_cmc(kReference, kReference) == 0.0);
  // A pure lightness step below L* = 16: ΔE = ΔL / (l · 0.511).
  CHECK(delta_e_cmc({10.0, 0.0, 0.0}, {11.0, 0.0, 0.0}, 1.0, 1.0) == doctest::Approx(1.0 / 0.511).epsilon(1e-14));
}
