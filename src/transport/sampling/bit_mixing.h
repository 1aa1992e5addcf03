// Integer hashes for seeds, pixel keys and decorrelation.
#pragma once

#include <cstdint>

namespace rimu {

/// A 64-bit mix (Stafford's "Mix13" variant of the MurmurHash3 finaliser), for seeding and decorrelation.
/// Inline: the Sobol' sampler calls it several times per draw, in the render loop's hot path.
inline uint64_t mix_bits(uint64_t v) {
  v ^= v >> 31;
  v *= 0x7fb5d329728ea185ULL;
  v ^= v >> 27;
  v *= 0x81dadef4bc2dd44dULL;
  v ^= v >> 33;
  return v;
}

/// A 32-bit integer hash: Wellons' "lowbias32" (two multiply-xorshift rounds; constants from his hash-prospector
/// search, github.com/skeeto/hash-prospector). Only 32-bit operations, so loops over it vectorise (SSE4.1 pmulld):
/// the Sobol' sampler hashes four draws at once with it.
constexpr uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

}  // namespace rimu
