#include "transport/owen_scrambling.h"

#include "transport/sampler.h"  // mix_bits

namespace rimu {

uint32_t scramble_reversed_digits(uint32_t x, uint32_t seed) {
  // Every step changes bit j by a function of bits below j only (see the header), so the whole is a nested
  // uniform scramble. The seed enters additively (each digit gets a fair coin) and through odd multipliers,
  // whose partial products x_i·m_{j−i} make the flip of digit j a seed-dependent function of the whole prefix:
  // two prefixes then receive (nearly) independent flips, which is what distinguishes Owen's scramble from a
  // random digital shift. The fixed even multipliers carry low bits upwards once more between the seeded steps.
  // The three seeded values must be independent: two additions of related values would cancel (a first version
  // added seed and seed ^ const, and digit 1 lost its coin). Constants: arbitrary; the quality test checks the
  // result, not the constants.
  const uint64_t h = mix_bits(seed);
  const uint32_t multiplier = uint32_t(h) | 1u, offset = uint32_t(h >> 32);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x *= multiplier;
  x ^= x * 0xb82f1e52u;
  x += offset;
  x *= offset | 1u;
  x ^= x * 0xc7afe638u;
  return x;
}

}  // namespace rimu
