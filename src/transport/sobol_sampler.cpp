#include "transport/sobol_sampler.h"

#include "transport/owen_scrambling.h"
#include "transport/sobol.h"

namespace rimu {

void SobolSampler::start_pixel_sample(int x, int y, uint32_t sample_index) {
  // Per-pixel scrambling seeds (the pixel decorrelation): every pixel owns an independent Owen scramble and
  // shuffle of every draw; the seed enters hashed so that seeds 1, 2, 3 are as unrelated as any.
  const uint64_t pixel = (uint64_t(uint32_t(x)) << 32) | uint32_t(y);
  pixel_key_ = mix_bits(pixel ^ mix_bits(seed_ + 0x632be59bd9b4e019ULL));
  sample_index_ = sample_index;
  dimension_ = 0;
}

uint64_t SobolSampler::draw_key() const {
  // The golden-ratio step spreads consecutive dimensions over the whole 64-bit range before mixing.
  return mix_bits(pixel_key_ + (uint64_t(dimension_) + 1) * 0x9e3779b97f4a7c15ULL);
}

float SobolSampler::next_1d() {
  const uint64_t key = draw_key();
  const uint32_t index = shuffle_index(sample_index_, uint32_t(key));
  dimension_ += 1;
  return bits_to_unit_float(owen_scramble(sobol_dimension0(index), uint32_t(key >> 32)));
}

Vec2 SobolSampler::next_2d() {
  const uint64_t key = draw_key();
  const uint64_t key_v = mix_bits(key);  // a second, independent 32-bit seed for the second coordinate
  const uint32_t index = shuffle_index(sample_index_, uint32_t(key));
  dimension_ += 2;
  return {bits_to_unit_float(owen_scramble(sobol_dimension0(index), uint32_t(key >> 32))),
          bits_to_unit_float(owen_scramble(sobol_dimension1(index), uint32_t(key_v)))};
}

}  // namespace rimu
