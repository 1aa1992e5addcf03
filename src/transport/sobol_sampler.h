// The low-discrepancy sampler: padded, Owen-scrambled Sobol' pairs (Burley 2020), decorrelated per pixel.
#pragma once

#include <cstdint>
#include <memory>

#include "transport/sampler.h"

namespace rimu {

/// Every draw (one next_1d() or next_2d() call, i.e. one decision of the path) gets its own randomised copy of the
/// first Sobol' dimension (1D) or of the first two (2D), indexed by the pixel's sample index:
///
///   index' = shuffle_index(i, seed_shuffle(p, d))            nested uniform shuffle (Burley 2020, §4)
///   u      = owen_scramble(sobol_dimension0(index'), seed_0(p, d))
///   v      = owen_scramble(sobol_dimension1(index'), seed_1(p, d))   (2D draws)
///
/// where p is the pixel and d the draw's first dimension. So the first 2ᵏ samples of a pixel stratify every 2D
/// decision as a (0,k,2)-net and every 1D decision into 2ᵏ equal intervals; different draws are paired at random
/// (padding), and different pixels are independent Owen scrambles of the same nets (no structured correlation
/// between neighbours). A pure function of (seed, pixel, sample index, dimension): thread- and order-independent.
/// Cost per draw: two 64-bit hashes, one shuffle, one or two scrambles; no tables beyond 4 KiB (sobol.h).
class SobolSampler final : public Sampler {
 public:
  explicit SobolSampler(uint64_t seed) : seed_(seed) {}
  void start_pixel_sample(int x, int y, uint32_t sample_index) override;
  float next_1d() override;
  Vec2 next_2d() override;
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<SobolSampler>(seed_); }

  /// The current dimension (the number of dimensions drawn since start_pixel_sample), for tests.
  uint32_t dimension() const { return dimension_; }

 private:
  // The 64-bit key of the current draw: a hash of (seed, pixel, dimension).
  uint64_t draw_key() const;

  uint64_t seed_;
  uint64_t pixel_key_ = 0;
  uint32_t sample_index_ = 0;
  uint32_t dimension_ = 0;
};

}  // namespace rimu
