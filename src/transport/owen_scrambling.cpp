#include "transport/owen_scrambling.h"

namespace rimu {

uint32_t scramble_reversed_digits(uint32_t x, uint32_t seed) {
  // Every step changes bit j by a function of bits below j only (see the header), so the whole is a nested
  // uniform scramble. The seed enters additively (each digit gets a fair coin) and through odd multipliers,
  // whose partial products x_i·m_{j−i} make the flip of digit j a seed-dependent function of the whole prefix:
  // two prefixes then receive (nearly) independent flips, which is what distinguishes Owen's scramble from a
  // random digital shift. The fixed even multipliers carry low bits upwards once more between the seeded steps.
  // (Constants: arbitrary odd/even 32-bit values; the quality test checks the result, not the constants.)
  const uint32_t multiplier_a = (seed * 0x2c1b3c6du) | 1u;
  const uint32_t multiplier_b = ((seed >> 16 | seed << 16) * 0x297a2d39u) | 1u;
  x += seed;
  x ^= x * 0x6c50b47cu;
  x *= multiplier_a;
  x ^= x * 0xb82f1e52u;
  x += seed ^ 0x5bd1e995u;
  x *= multiplier_b;
  x ^= x * 0xc7afe638u;
  return x;
}

}  // namespace rimu
