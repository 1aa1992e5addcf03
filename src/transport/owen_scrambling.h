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
// the sample index. The round constants below are our own choice; the statistical quality of the flips (each
// digit's flip is a fair coin over seeds, independently for different prefixes) is checked in
// tests/transport/sobol_owen_test.cpp.
#pragma once

#include <cstdint>

namespace rimu {

/// Reverses the order of the 32 bits of `v` (bit 0 ↔ bit 31).
constexpr uint32_t reverse_bits(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
  return (v >> 16) | (v << 16);
}

/// Digit flips of bit-reversed digits (digit 1 in bit 0): bit j of the result is bit j of `reversed` XOR a
/// hash of (seed, bits 0..j−1). A bijection for every seed. Cost: a handful of integer multiplies.
uint32_t scramble_reversed_digits(uint32_t reversed, uint32_t seed);

/// Owen-scrambles a binary fraction x = bits / 2³² (digit 1 in bit 31). Nets stay nets; a fixed input becomes
/// uniform over seeds.
inline uint32_t owen_scramble(uint32_t bits, uint32_t seed) {
  return reverse_bits(scramble_reversed_digits(reverse_bits(bits), seed));
}

/// Shuffles sample indices (Burley 2020, §4, "nested uniform shuffle"): the same digit-wise flips applied to the
/// index, most significant bit first. Bit j of the result depends only on bits ≥ j of `index`, so every aligned
/// block {c·2ᵏ, …, c·2ᵏ + 2ᵏ − 1} maps onto an aligned block of the same size: the first 2ᵏ samples of the
/// shuffled sequence are still an aligned block of 2ᵏ points of the original sequence (a (0,k,2)-net for Sobol').
inline uint32_t shuffle_index(uint32_t index, uint32_t seed) { return owen_scramble(index, seed); }

/// A binary fraction's 24 leading digits as a float in [0, 1) (exact; never 1).
inline float bits_to_unit_float(uint32_t bits) { return float(bits >> 8) * 0x1p-24f; }

}  // namespace rimu
