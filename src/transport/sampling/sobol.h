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
// These two need no table from the published file (the recurrence above is all of it), and no table at run time
// either (see sobol_dimension1_reversed); the sampler pads higher dimensions with independently scrambled and
// shuffled copies of this pair (docs/sampling.md explains why).
#pragma once

#include <array>
#include <cstdint>

#include "transport/sampling/owen_scrambling.h"

namespace rimu {

/// Sobol' dimension 0 (van der Corput): the index's bits mirrored behind the binary point.
constexpr uint32_t sobol_dimension0(uint32_t index) { return reverse_bits(index); }

/// reverse_bits(sobol_dimension1(index)), without a table. With the fraction's digits bit-reversed, bit m of
/// x₁(i) is ⊕ of the index bits k whose position is a superset of m's (k & m = m): v_{1,k} has digit m + 1 set
/// iff C(k, m) is odd, which by Lucas' theorem means m ⊆ k. That superset-XOR over the five bits of a position is
/// five butterfly steps (a GF(2) zeta transform), 15 integer operations that vectorise.
constexpr uint32_t sobol_dimension1_reversed(uint32_t index) {
  uint32_t y = index;
  y ^= (y >> 1) & 0x55555555u;   // positions with bit 0 clear take their bit-0 superset
  y ^= (y >> 2) & 0x33333333u;   // … bit 1
  y ^= (y >> 4) & 0x0f0f0f0fu;   // … bit 2
  y ^= (y >> 8) & 0x00ff00ffu;   // … bit 3
  y ^= (y >> 16) & 0x0000ffffu;  // … bit 4
  return y;
}

/// Sobol' dimension 1 (polynomial x + 1, m₁ = 1) of point `index`, natural order.
constexpr uint32_t sobol_dimension1(uint32_t index) { return reverse_bits(sobol_dimension1_reversed(index)); }

namespace sobol_detail {

/// v_{1,k} for k = 1..32 as 32-bit fractions (element k−1), from the recurrence in the file comment; tests check
/// sobol_dimension1 against the XOR of these.
constexpr std::array<uint32_t, 32> dimension1_directions() {
  std::array<uint32_t, 32> v{};
  v[0] = 1u << 31;  // m₁ = 1: v₁ = 1/2
  for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
  return v;
}

}  // namespace sobol_detail

}  // namespace rimu
