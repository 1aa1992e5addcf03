// The low-discrepancy sampler: padded, Owen-scrambled Sobol' pairs (Burley 2020), decorrelated per pixel.
#pragma once

#include <cstdint>
#include <memory>

#include "transport/sampling/owen_scrambling.h"
#include "transport/sampling/sampler.h"
#include "transport/sampling/sobol.h"

namespace rimu {

/// Every draw (one next_1d() or next_2d() call, i.e. one decision of the path) gets its own randomised copy of the
/// first Sobol' dimension (1D) or of the first two (2D), indexed by the pixel's sample index i:
///
///   i' = shuffle_index(i, K_shuffle(p, t))                   nested uniform shuffle (Burley 2020, §4)
///   u  = owen_scramble(sobol_dimension0(i'), K_u(p, t))
///   v  = owen_scramble(sobol_dimension1(i'), K_v(p, t))   (2D draws)
///
/// where p is the pixel, t the draw's number within the pixel sample (0, 1, 2, …) and the K three ScrambleKeys
/// (sobol_draw_keys). So the first 2ᵏ samples of a pixel stratify every 2D decision as a (0,k,2)-net and every 1D
/// decision into 2ᵏ equal intervals; different draws are paired at random (padding), and different pixels are
/// independent Owen scrambles of the same nets (no structured correlation between neighbours). A pure function of
/// (seed, pixel, sample index, draw number): thread- and order-independent.
///
/// Cost. Draws are computed eight at a time (draws t … t+7, both coordinates), lane by lane in loops the compiler
/// turns into SIMD: the per-draw work has no branches and only 32-bit integer operations (hashes, scrambles, bit
/// reversals, the table-free sobol_dimension1_reversed). A 1D draw wastes its batch lane's second coordinate;
/// that is cheaper than a separate 1D path. The nine scramble-key words of a draw depend on (pixel, draw) only,
/// not on the sample index, and the render loop takes a pass's samples of one pixel in a row (up to 16): so the
/// words of the first kCachedBatches batches are kept while the pixel stays the same, and each pixel sample after
/// the first pays only for its shuffle and scrambles. docs/sampling.md ("Cost") has the measurements.
class SobolSampler final : public Sampler {
 public:
  static constexpr int kBatch = 8;
  /// Batches whose key words are cached per pixel: 16 × 8 = 128 draws, more than a path of the default depth
  /// makes (3 camera draws + 5 per bounce); later draws recompute their words every time.
  static constexpr int kCachedBatches = 16;

  explicit SobolSampler(uint64_t seed) : seed_(seed) {}
  void start_pixel_sample(int x, int y, uint32_t sample_index) override;
  float next_1d() override {
    const uint32_t lane = lane_of_next_draw();
    ++draw_;
    dimension_ += 1;
    return u_[lane];
  }
  Vec2 next_2d() override {
    const uint32_t lane = lane_of_next_draw();
    ++draw_;
    dimension_ += 2;
    return {u_[lane], v_[lane]};
  }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<SobolSampler>(seed_); }

  /// The current dimension (the number of dimensions drawn since start_pixel_sample), for tests.
  uint32_t dimension() const { return dimension_; }

 private:
  // The batch lane that holds draw draw_, computing the next batch when draw_ lies outside the current one.
  uint32_t lane_of_next_draw() {
    const uint32_t lane = draw_ - batch_first_draw_;  // wraps to a huge value before the first batch
    if (lane < uint32_t(kBatch)) return lane;
    compute_batch(draw_);
    return 0;
  }
  void compute_batch(uint32_t first_draw);
  // The nine key words of each lane of the batch starting at draw `first_draw` (sobol_draw_keys, lane by lane).
  static void compute_key_words(const uint32_t pixel_key[2], uint32_t first_draw, uint32_t (&words)[9][kBatch]);

  uint64_t seed_;
  int pixel_x_ = 0, pixel_y_ = 0;
  bool has_pixel_ = false;        // pixel_x_, pixel_y_ and pixel_key_ describe the last started pixel
  uint32_t cached_batches_ = 0;   // key words of batches 0 … cached_batches_ − 1 of that pixel are in key_words_
  uint32_t pixel_key_[2] = {0, 0};
  uint32_t reversed_index_ = 0;
  uint32_t draw_ = 0, dimension_ = 0;
  uint32_t batch_first_draw_ = 0;
  alignas(16) float u_[kBatch] = {}, v_[kBatch] = {};
  alignas(32) uint32_t key_words_[kCachedBatches][9][kBatch] = {};
};

/// The three scramble keys of draw `draw` of a pixel sample whose pixel key is (key0, key1): nine 32-bit words,
/// each a hash of the draw's hash with its own salt. Public for the scramble-quality test.
DrawKeys sobol_draw_keys(uint32_t key0, uint32_t key1, uint32_t draw);

}  // namespace rimu
