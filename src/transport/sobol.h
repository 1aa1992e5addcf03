// The first two dimensions of Sobol's sequence in base 2, as 32-bit binary fractions (bits / 2³²).
//
// Sobol' (1967) points are digital: x_d(i) = ⊕ₖ iₖ·v_{d,k}, the XOR of the direction numbers v_{d,k} selected by
// the bits iₖ of the index (natural order, not Gray-code order). Their first two dimensions form a (0,2)-sequence:
// every aligned block of 2ᵐ consecutive points puts exactly one point in each elementary interval of area 2⁻ᵐ.
//
//  - dimension 0: v_{0,k} = 2⁻ᵏ, i.e. the van der Corput radical inverse in base 2;
//  - dimension 1: primitive polynomial x + 1 (degree s = 1, a = 0) with m₁ = 1, the first row of Joe & Kuo's
//    direction-number file new-joe-kuo-6.21201 ("2 1 0 1": d = 2, s = 1, a = 0, m₁ = 1; S. Joe and F. Y. Kuo,
//    "Constructing Sobol sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30, 2008).
//    Sobol's recurrence for degree 1 is m_k = 2·m_{k−1} ⊕ m_{k−1}, giving m = 1, 3, 5, 15, 17, 51, …; as fractions
//    v_{1,k} = m_k / 2ᵏ, i.e. v_{1,k} = v_{1,k−1} ⊕ (v_{1,k−1} / 2): the columns of Pascal's triangle mod 2.
//
// These two need no table from the published file (the recurrence above is all of it); the sampler pads higher
// dimensions with independently scrambled and shuffled copies of this pair (docs/sampling.md explains why).
#pragma once

#include <array>
#include <cstdint>

#include "transport/owen_scrambling.h"

namespace rimu {

/// Sobol' dimension 0 (van der Corput): the index's bits mirrored behind the binary point.
constexpr uint32_t sobol_dimension0(uint32_t index) { return reverse_bits(index); }

namespace sobol_detail {

/// v_{1,k} for k = 1..32 as 32-bit fractions (element k−1), from the recurrence in the file comment.
constexpr std::array<uint32_t, 32> dimension1_directions() {
  std::array<uint32_t, 32> v{};
  v[0] = 1u << 31;  // m₁ = 1: v₁ = 1/2
  for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  return v;
}

/// XOR-linearity lets the 32-bit product be split by bytes: table[b][byte] = ⊕ of the directions selected by
/// the byte's bits at index positions 8b..8b+7 (4 KiB, computed at compile time).
constexpr std::array<std::array<uint32_t, 256>, 4> dimension1_byte_tables() {
  const std::array<uint32_t, 32> v = dimension1_directions();
  std::array<std::array<uint32_t, 256>, 4> table{};
  for (int b = 0; b < 4; ++b)
    for (int byte = 0; byte < 256; ++byte) {
      uint32_t x = 0;
      for (int bit = 0; bit < 8; ++bit)
        if (byte >> bit & 1) x ^= v[size_t(8 * b + bit)];
      table[size_t(b)][size_t(byte)] = x;
    }
  return table;
}

inline constexpr std::array<std::array<uint32_t, 256>, 4> kDimension1Tables = dimension1_byte_tables();

}  // namespace sobol_detail

/// Sobol' dimension 1 (polynomial x + 1, m₁ = 1) of point `index`, natural order. Four table look-ups.
constexpr uint32_t sobol_dimension1(uint32_t index) {
  const auto& t = sobol_detail::kDimension1Tables;
  return t[0][index & 0xffu] ^ t[1][index >> 8 & 0xffu] ^ t[2][index >> 16 & 0xffu] ^ t[3][index >> 24];
}

}  // namespace rimu
