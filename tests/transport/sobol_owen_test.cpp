// The statistical quality of the hash-based Owen scramble: each digit's flip must behave like the fair,
// independent coin of Owen's (1995) random tree, which is what makes scrambled-net estimators unbiased with
// variance o(1/N). A weak hash shows up here as flips that are biased or shared between sibling prefixes (the
// extreme case, a random digital shift x ^ seed, gives every prefix the same flip).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "transport/sampling/owen_scrambling.h"
#include "transport/sampling/sampler.h"
#include "transport/sampling/sobol_sampler.h"

using namespace rimu;

namespace {

constexpr int kSeeds = 4096;

// The flip that `scramble` applies to digit j (0 = most significant) of inputs whose first j digits are `prefix`
// (and whose later digits are zero), for seed s.
template <class Scramble>
int flip(const Scramble& scramble, int j, uint32_t prefix, uint32_t seed) {
  const uint32_t x = j == 0 ? 0u : prefix << (32 - j);
  return int(scramble(x, seed) >> (31 - j) & 1u);
}

// Over kSeeds seeds: the largest |P(flip) − ½| of single prefixes and |P(flip(p) = flip(p')) − ½| of prefix
// pairs differing in one digit, for digits 0..8 (all prefixes) and digits 16 and 23 (64 random prefixes each).
template <class Scramble>
double worst_deviation(const Scramble& scramble) {
  std::vector<uint32_t> seeds(kSeeds);
  for (int s = 0; s < kSeeds; ++s) seeds[size_t(s)] = uint32_t(mix_bits(uint64_t(s) + 0xabcdefULL));
  double worst = 0;
  auto test_prefix = [&](int j, uint32_t prefix) {
    std::vector<int> base(kSeeds);
    int ones = 0;
    for (int s = 0; s < kSeeds; ++s) ones += base[size_t(s)] = flip(scramble, j, prefix, seeds[size_t(s)]);
    worst = std::fmax(worst, std::fabs(double(ones) / kSeeds - 0.5));
    for (int i = 0; i < j; ++i) {
      int agree = 0;
      for (int s = 0; s < kSeeds; ++s) agree += base[size_t(s)] == flip(scramble, j, prefix ^ (1u << i), seeds[size_t(s)]);
      worst = std::fmax(worst, std::fabs(double(agree) / kSeeds - 0.5));
    }
  };
  for (int j = 0; j <= 8; ++j)
    for (uint32_t p = 0; p < (1u << j); ++p) test_prefix(j, p);
  for (int j : {16, 23})
    for (uint64_t t = 0; t < 64; ++t) test_prefix(j, uint32_t(mix_bits(t + 99)) & ((1u << j) - 1));
  return worst;
}

}  // namespace

TEST_CASE("Owen scramble flips are fair and independent between sibling prefixes") {
  // Each statistic is a proportion over 4096 seeds: σ = 0.5/√4096 = 0.0078 if the flips are fair independent
  // coins. About 6,700 statistics are taken; a 5σ bound (0.039) is exceeded by chance with probability ~4e-3.
  const double bound = 5.0 * 0.5 / std::sqrt(double(kSeeds));
  const double owen = worst_deviation([](uint32_t x, uint32_t seed) { return owen_scramble(x, seed); });
  MESSAGE("worst deviation from 1/2: ", owen, " (bound ", bound, ")");
  CHECK(owen < bound);
  // The sampler's keys come from sobol_draw_keys (32-bit hashes of pixel key and draw), not from scramble_key:
  // each of its three keys must pass on its own. The seed plays the pixel key; draws 0 and 7 are both checked.
  const auto keys = [](uint32_t seed) { return sobol_draw_keys(seed, seed ^ 0x5bd1e995u, seed & 1u ? 0u : 7u); };
  const double shuffle = worst_deviation([&](uint32_t x, uint32_t seed) { return owen_scramble(x, keys(seed).shuffle); });
  const double u = worst_deviation([&](uint32_t x, uint32_t seed) { return owen_scramble(x, keys(seed).u); });
  const double v = worst_deviation([&](uint32_t x, uint32_t seed) { return owen_scramble(x, keys(seed).v); });
  MESSAGE("sampler keys: worst deviation shuffle ", shuffle, ", u ", u, ", v ", v);
  CHECK(shuffle < bound);
  CHECK(u < bound);
  CHECK(v < bound);
  // The check can fail: a random digital shift flips every prefix alike (agreement 1, deviation 0.5).
  const double shift = worst_deviation([](uint32_t x, uint32_t seed) { return x ^ seed; });
  CHECK(shift > bound);
}
