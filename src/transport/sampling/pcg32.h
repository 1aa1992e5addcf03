// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms for Random Number
// Generation", the XSH-RR output on a 64-bit LCG): the independent sampler's and the medium walks' generator.
#pragma once

#include <cstdint>

namespace rimu {

struct Pcg32 {
  uint64_t state = 0;
  uint64_t increment = 1;  ///< odd: selects one of 2⁶³ streams

  uint32_t next_bits() {
    const uint64_t old = state;
    state = old * 6364136223846793005ULL + increment;
    const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    const uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  }
  /// Uniform in [0, 1): 24 random bits, exactly representable in float, never 1.
  float next_1d() { return float(next_bits() >> 8) * 0x1p-24f; }
};

}  // namespace rimu
