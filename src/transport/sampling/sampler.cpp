#include "transport/sampling/sampler.h"

namespace rimu {

void IndependentSampler::start_pixel_sample(int x, int y, uint32_t sample_index) {
  // PCG32 (O'Neill 2014): the stream (increment) comes from the pixel, the state from the sample index, so
  // neighbouring pixels and successive samples get unrelated sequences.
  const uint64_t pixel = (uint64_t(uint32_t(x)) << 32) | uint32_t(y);
  increment_ = (mix_bits(pixel ^ mix_bits(seed_)) << 1) | 1u;
  state_ = 0;
  next_1d();
  state_ += mix_bits(uint64_t(sample_index) ^ (seed_ * 0x9e3779b97f4a7c15ULL));
  next_1d();
}

float IndependentSampler::next_1d() {
  const uint64_t old = state_;
  state_ = old * 6364136223846793005ULL + increment_;
  const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
  const uint32_t rot = uint32_t(old >> 59u);
  const uint32_t bits = (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
  // 24 random bits → [0, 1) exactly representable in float, never 1.
  return float(bits >> 8) * 0x1p-24f;
}

Vec2 IndependentSampler::next_2d() {
  const float a = next_1d();
  return {a, next_1d()};
}

}  // namespace rimu
