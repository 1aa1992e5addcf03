// Sobol' dimensions 0 and 1 against values derived from their definition, the (0,2)-sequence property with and
// without Owen scrambling, and the nested structure of the hash-based scramble and index shuffle.
#include <doctest/doctest.h>

#include <cstdint>
#include <set>
#include <vector>

#include "sobol_net_check.h"
#include "transport/sampling/owen_scrambling.h"
#include "transport/sampling/sampler.h"
#include "transport/sampling/sobol.h"

using namespace rimu;

namespace {
constexpr double kTwoTo32 = 4294967296.0;
double fraction(uint32_t bits) { return double(bits) / kTwoTo32; }
}  // namespace

TEST_CASE("Sobol dimension 0 is the base-2 van der Corput radical inverse") {
  // φ₂(i): the binary digits of i mirrored behind the point (van der Corput 1935). Exact dyadic values.
  const double expected[16] = {0,      1 / 2.,  1 / 4.,  3 / 4.,  1 / 8.,  5 / 8.,  3 / 8.,  7 / 8.,
                               1 / 16., 9 / 16., 5 / 16., 13 / 16., 3 / 16., 11 / 16., 7 / 16., 15 / 16.};
  for (uint32_t i = 0; i < 16; ++i) CHECK(fraction(sobol_dimension0(i)) == expected[i]);
  CHECK(sobol_dimension0(1u << 31) == 1u);  // the last digit
}

TEST_CASE("Sobol dimension 1 matches the points derived from polynomial x+1, m1 = 1 (Joe-Kuo row d=2)") {
  // Joe & Kuo (2008), new-joe-kuo-6.21201, first row "2 1 0 1". Sobol's recurrence for s = 1: m_k = 2m_{k-1} ^
  // m_{k-1}: m = 1, 3, 5, 15, 17, so v = 1/2, 3/4, 5/8, 15/16, 17/32. Points in natural (not Gray-code) order,
  // x(i) = XOR of v_k over the set bits of i, worked by hand: e.g. x(7) = 1/2 ^ 3/4 ^ 5/8 = .100^.110^.101 = .111.
  // Exact dyadic values: compared with ==.
  const double expected[17] = {0,       1 / 2.,  3 / 4.,  1 / 4.,  5 / 8.,  1 / 8.,  3 / 8.,  7 / 8.,  15 / 16.,
                               7 / 16., 3 / 16., 11 / 16., 5 / 16., 13 / 16., 9 / 16., 1 / 16., 17 / 32.};
  for (uint32_t i = 0; i < 17; ++i) CHECK(fraction(sobol_dimension1(i)) == expected[i]);
  // m_6 = 2·17 ^ 17 = 51: v_6 = 51/64, the point at index 32.
  CHECK(fraction(sobol_dimension1(32)) == 51 / 64.);
  // The table-free butterfly (sobol_dimension1_reversed) agrees with the bit-by-bit XOR of the directions, for
  // the first 4096 indices and for indices that use all 32 bits.
  constexpr auto v = sobol_detail::dimension1_directions();
  auto by_directions = [&](uint32_t i) {
    uint32_t x = 0;
    for (int k = 0; k < 32; ++k)
      if (i >> k & 1) x ^= v[size_t(k)];
    return x;
  };
  for (uint32_t i = 0; i < 4096; ++i) CHECK(sobol_dimension1(i) == by_directions(i));
  for (uint32_t i : {0x12345678u, 0xffffffffu, 0x80000001u, 0x00ff00ffu, 0xdeadbeefu}) {
    CHECK(sobol_dimension1(i) == by_directions(i));
    CHECK(sobol_dimension1_reversed(i) == reverse_bits(by_directions(i)));
  }
}

TEST_CASE("reverse_bits mirrors every bit") {
  for (int k = 0; k < 32; ++k) CHECK(reverse_bits(1u << k) == 1u << (31 - k));
  CHECK(reverse_bits(0x12345678u) == 0x1e6a2c48u);
  CHECK(reverse_bits(reverse_bits(0xdeadbeefu)) == 0xdeadbeefu);
}

TEST_CASE("The first two Sobol dimensions form a (0,2)-sequence, unscrambled and Owen-scrambled") {
  // Every aligned block of 2^k points is a (0,k,2)-net (Sobol' 1967; the pair has t = 0, Niederreiter 1992
  // Ch. 4): exactly one point in each elementary interval of every shape. Owen scrambling maps elementary
  // intervals onto elementary intervals of the same shape, so it must keep the property exactly.
  for (int k = 1; k <= 12; ++k) {
    for (uint32_t block : {0u, 1u, 37u}) {
      const uint32_t first = block << k;
      std::vector<std::pair<uint32_t, uint32_t>> plain, scrambled;
      const uint32_t seed_u = uint32_t(mix_bits(uint64_t(k) * 131 + block)), seed_v = uint32_t(mix_bits(seed_u));
      for (uint32_t i = first; i < first + (1u << k); ++i) {
        plain.emplace_back(sobol_dimension0(i), sobol_dimension1(i));
        scrambled.emplace_back(owen_scramble(sobol_dimension0(i), seed_u), owen_scramble(sobol_dimension1(i), seed_v));
      }
      INFO("k = ", k, ", block ", block);
      CHECK(test::check_02_net(plain, k) == "");
      CHECK(test::check_02_net(scrambled, k) == "");
    }
  }
}

TEST_CASE("The net check detects points that are not a net") {
  // Guard against a vacuous checker: independent-looking points (a hash) are no (0,4,2)-net, and a net with one
  // point moved to another interval fails.
  std::vector<std::pair<uint32_t, uint32_t>> random_points, moved;
  for (uint32_t i = 0; i < 16; ++i) {
    random_points.emplace_back(uint32_t(mix_bits(i)), uint32_t(mix_bits(i + 1000)));
    moved.emplace_back(sobol_dimension0(i), sobol_dimension1(i));
  }
  moved[3].first ^= 1u << 31;
  CHECK(test::check_02_net(random_points, 4) != "");
  CHECK(test::check_02_net(moved, 4) != "");
}

TEST_CASE("Owen scrambling is nested: shared leading digits stay shared, the first differing digit stays different") {
  // The defining property of a nested uniform scramble (Owen 1995): digit j's flip depends only on digits < j.
  // So two inputs agreeing on exactly j leading digits give outputs agreeing on exactly j leading digits.
  for (uint64_t t = 0; t < 2000; ++t) {
    const uint32_t seed = uint32_t(mix_bits(t));
    const uint32_t x = uint32_t(mix_bits(t + 77777));
    const int j = int(t % 32);
    const uint32_t y = x ^ (0x80000000u >> j) ^ (uint32_t(mix_bits(t + 5)) & (0x7fffffffu >> j));
    const uint32_t sx = owen_scramble(x, seed), sy = owen_scramble(y, seed);
    REQUIRE(__builtin_clz(x ^ y) == j);
    CHECK(__builtin_clz(sx ^ sy) == j);
  }
}

TEST_CASE("The index shuffle maps aligned blocks of 2^k indices onto aligned blocks") {
  // Burley (2020) §4: the first 2^k shuffled indices are a permutation of one aligned block, so the shuffled
  // Sobol' points still form a (0,k,2)-net; blocks differ between seeds.
  std::set<uint32_t> block_starts;
  for (uint32_t s = 0; s < 16; ++s) {
    const uint32_t seed = uint32_t(mix_bits(s + 12345));
    for (int k : {0, 3, 8}) {
      std::set<uint32_t> seen;
      const uint32_t block = shuffle_index(0, seed) >> k;
      for (uint32_t i = 0; i < (1u << k); ++i) {
        const uint32_t shuffled = shuffle_index(i, seed);
        CHECK((shuffled >> k) == block);
        seen.insert(shuffled);
      }
      CHECK(seen.size() == (size_t(1) << k));
      if (k == 8) block_starts.insert(block);
    }
  }
  CHECK(block_starts.size() == 16);
}
