#include "transport/sampling/sampler.h"

namespace rimu {

void IndependentSampler::start_pixel_sample(int x, int y, uint32_t sample_index) {
  // PCG32 (O'Neill 2014): the stream (increment) comes from the pixel, the state from the sample index, so
  // neighbouring pixels and successive samples get unrelated sequences.
  const uint64_t pixel = (uint64_t(uint32_t(x)) << 32) | uint32_t(y);
  random_.increment = (mix_bits(pixel ^ mix_bits(seed_)) << 1) | 1u;
  random_.state = 0;
  next_1d();
  random_.state += mix_bits(uint64_t(sample_index) ^ (seed_ * 0x9e3779b97f4a7c15ULL));
  next_1d();
}

float IndependentSampler::next_1d() { return random_.next_1d(); }

Vec2 IndependentSampler::next_2d() {
  const float a = next_1d();
  return {a, next_1d()};
}

}  // namespace rimu
