// Hash-based nested uniform (Owen) scrambling of 32-bit binary fractions and of sample indices.
//
// Owen (1995) scrambling randomises a base-2 point coordinate x = 0.b₁b₂b₃… digit by digit: digit bₖ is flipped
// by a random bit that depends only on the digits above it (b₁…bₖ₋₁) and on the seed. Points sharing their first
// k−1 digits stay together (so every elementary interval of a (t,m,s)-net maps onto an elementary interval of the
// same shape: nets stay nets), and each coordinate becomes uniform on [0,1).
//
// A full random tree of flips costs one hash per digit. Laine & Karras ("Stratified sampling for stochastic
// transparency", EGSR 2011, §3) observed that with the digits bit-reversed (b₁ in the integer's bit 0) the
// operations  x += c,  x ^= c,  x *= odd c,  x ^= x·(even c)  each change integer bit j only by a function of
// bits below j, i.e. each is such a digit-wise flip; any composition of them is an Owen scramble. Burley
// ("Practical Hash-based Owen Scrambling", JCGT 9(4), 2020, §3-4) uses this for Sobol' points and for shuffling
// the sample index. The three even multipliers are those of Burley's listing; the seeded odd multiplier and
// offset are ours (see scramble_reversed_digits). The statistical quality of the flips (each digit's flip is a
// fair coin over seeds, independently for different prefixes) is checked in tests/transport/sobol_owen_test.cpp.
#pragma once

#include <cstdint>

#include "transport/sampling/bit_mixing.h"

namespace rimu {

/// Reverses the order of the 32 bits of `v` (bit 0 ↔ bit 31): a byte swap (one instruction) and three swaps of
/// bit groups within the bytes.
constexpr uint32_t reverse_bits(uint32_t v) {
  v = __builtin_bswap32(v);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  return ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
}

/// The random words that select one nested uniform scramble: a seeded addition, a seeded odd multiplier and a
/// seeded offset (scramble_reversed_digits says why all three). Independent random words give independent
/// scrambles; the sampler draws them from its per-draw hashes, tests from a 32-bit seed (scramble_key).
struct ScrambleKey {
  uint32_t add = 0, multiplier = 1, offset = 0;
};

/// The key of a 32-bit seed: the seed itself plus the two halves of its 64-bit hash.
inline ScrambleKey scramble_key(uint32_t seed) {
  const uint64_t h = mix_bits(seed);
  return {seed, uint32_t(h) | 1u, uint32_t(h >> 32)};
}

/// Digit flips of bit-reversed digits (digit 1 in bit 0): bit j of the result is bit j of `reversed` XOR a
/// random function of (key, bits 0..j−1). A bijection for every key. Cost: six integer multiplies.
inline uint32_t scramble_reversed_digits(uint32_t x, ScrambleKey key) {
  // Every step changes bit j by a function of bits below j only (see the file comment), so the whole is a nested
  // uniform scramble. The key enters additively (each digit gets a fair coin) and through odd multipliers, whose
  // partial products x_i·m_{j−i} make the flip of digit j a key-dependent function of the whole prefix: two
  // prefixes then receive (nearly) independent flips, which is what distinguishes Owen's scramble from a random
  // digital shift. The fixed even multipliers carry low bits upwards once more between the seeded steps. The
  // three key words must be independent: two additions of related values would cancel (a first version added
  // seed and seed ^ const, and digit 1 lost its coin).
  x += key.add;
  x ^= x * 0x6c50b47cu;
  x *= key.multiplier | 1u;
  x ^= x * 0xb82f1e52u;
  x += key.offset;
  x *= key.offset | 1u;
  x ^= x * 0xc7afe638u;
  return x;
}

/// The three scramble keys of one sampler draw: the index shuffle and the two coordinates.
struct DrawKeys {
  ScrambleKey shuffle, u, v;
};

/// The same with the key of a 32-bit seed.
inline uint32_t scramble_reversed_digits(uint32_t reversed, uint32_t seed) {
  return scramble_reversed_digits(reversed, scramble_key(seed));
}

/// Owen-scrambles a binary fraction x = bits / 2³² (digit 1 in bit 31). Nets stay nets; a fixed input becomes
/// uniform over seeds.
inline uint32_t owen_scramble(uint32_t bits, ScrambleKey key) {
  return reverse_bits(scramble_reversed_digits(reverse_bits(bits), key));
}
inline uint32_t owen_scramble(uint32_t bits, uint32_t seed) { return owen_scramble(bits, scramble_key(seed)); }

/// Shuffles sample indices (Burley 2020, §4, "nested uniform shuffle"): the same digit-wise flips applied to the
/// index, most significant bit first. Bit j of the result depends only on bits ≥ j of `index`, so every aligned
/// block {c·2ᵏ, …, c·2ᵏ + 2ᵏ − 1} maps onto an aligned block of the same size: the first 2ᵏ samples of the
/// shuffled sequence are still an aligned block of 2ᵏ points of the original sequence (a (0,k,2)-net for Sobol').
inline uint32_t shuffle_index(uint32_t index, ScrambleKey key) { return owen_scramble(index, key); }
inline uint32_t shuffle_index(uint32_t index, uint32_t seed) { return owen_scramble(index, seed); }

/// A binary fraction's 24 leading digits as a float in [0, 1) (exact; never 1).
inline float bits_to_unit_float(uint32_t bits) { return float(bits >> 8) * 0x1p-24f; }

}  // namespace rimu
