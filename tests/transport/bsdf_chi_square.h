// A chi-square goodness-of-fit test of a BSDF's sample() against its pdf() (the hero lane), for tests.
#pragma once

#include <cstdint>
#include <string>

#include "transport/bsdfs/bsdf.h"

namespace rimu::test {

/// The outcome of one goodness-of-fit test.
struct ChiSquareOutcome {
  double chi_square = 0;
  int degrees_of_freedom = 0;
  double p_value = 1;
  std::string failure;  ///< non-empty when the test could not even be run (NaN sample, sample in a 0-density cell)
};

/// Draws `sample_count` samples of bsdf.sample(wo, ·) and bins wi over (cos θ ∈ [−1, 1]: 20 bins) × (φ: 20 bins),
/// plus one cell per side for delta samples. Expected counts: the integral of pdf()[0] over each cell (nested
/// adaptive Simpson quadrature in θ and φ, so that narrow lobes near the pole or the horizon are resolved), and
/// for delta samples the discrete probability they report (which must be the same for every delta sample on
/// that side). Cells with an expected count below 5 are pooled, smallest first (the usual validity condition of
/// Pearson's test). The p-value is test::chi_square_p_value() (tests/statistics.h).
ChiSquareOutcome bsdf_chi_square(const Bsdf& bsdf, Vec3 wo, int sample_count, uint64_t seed);

}  // namespace rimu::test
