#include "transport/sampling/distribution_coarsening.h"

#include <cassert>

namespace rimu {

namespace {
/// The largest power of two ≤ max_factor dividing both sides.
int largest_power_of_two_dividing(int width, int height, int max_factor) {
  int f = 1;
  while (f * 2 <= max_factor && width % (f * 2) == 0 && height % (f * 2) == 0) f *= 2;
  return f;
}
}  // namespace

std::vector<float> block_sums(std::span<const float> weights, int width, int height, int factor) {
  assert(factor >= 1 && width % factor == 0 && height % factor == 0 && weights.size() == size_t(width) * height);
  const int cw = width / factor, ch = height / factor;
  std::vector<double> sums(size_t(cw) * ch, 0.0);
  for (int y = 0; y < height; ++y) {
    double* row = sums.data() + size_t(y / factor) * cw;
    const float* in = weights.data() + size_t(y) * width;
    for (int x = 0; x < width; ++x) row[x / factor] += in[x];
  }
  return {sums.begin(), sums.end()};
}

double coarsening_added_variance(std::span<const float> weights, int width, int height, int factor) {
  assert(factor >= 1 && width % factor == 0 && height % factor == 0 && weights.size() == size_t(width) * height);
  const int cw = width / factor, ch = height / factor;
  std::vector<double> sums(size_t(cw) * ch, 0.0), squares(size_t(cw) * ch, 0.0);
  double total = 0.0;
  for (int y = 0; y < height; ++y) {
    const size_t block_row = size_t(y / factor) * cw;
    const float* in = weights.data() + size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      const double f = in[x];
      sums[block_row + x / factor] += f;
      squares[block_row + x / factor] += f * f;
      total += f;
    }
  }
  if (!(total > 0.0)) return 0.0;
  const double cells_per_block = double(factor) * factor;
  double r = 0.0;
  for (size_t k = 0; k < sums.size(); ++k)
    if (sums[k] > 0.0) r += cells_per_block * squares[k] / sums[k];
  return r / total - 1.0;
}

namespace {
/// Per-block Σf and Σf² of a (w/f) × (h/f) blocking, built from the next finer blocking's (sums and squares add).
struct BlockMoments {
  std::vector<double> sums, squares;
  int width = 0, height = 0;
};

BlockMoments merge_pairs(const BlockMoments& fine) {
  BlockMoments coarse;
  coarse.width = fine.width / 2;
  coarse.height = fine.height / 2;
  coarse.sums.assign(size_t(coarse.width) * coarse.height, 0.0);
  coarse.squares.assign(coarse.sums.size(), 0.0);
  for (int y = 0; y < fine.height; ++y)
    for (int x = 0; x < fine.width; ++x) {
      const size_t from = size_t(y) * fine.width + x, to = size_t(y / 2) * coarse.width + x / 2;
      coarse.sums[to] += fine.sums[from];
      coarse.squares[to] += fine.squares[from];
    }
  return coarse;
}

double added_variance(const BlockMoments& blocks, int cells_per_block, double total) {
  double r = 0.0;
  for (size_t k = 0; k < blocks.sums.size(); ++k)
    if (blocks.sums[k] > 0.0) r += cells_per_block * blocks.squares[k] / blocks.sums[k];
  return r / total - 1.0;
}
}  // namespace

SamplingBlock choose_sampling_block(std::span<const float> weights, int width, int height,
                                    double max_added_variance, int max_factor) {
  assert(weights.size() == size_t(width) * height);
  SamplingBlock chosen;
  if (max_factor < 2 || width % 2 != 0 || height % 2 != 0) return chosen;
  // The 2 × 2 moments from the weights (one pass), then each coarser level from the one before: about 1.3 passes
  // over the table's size in all, instead of one per factor.
  BlockMoments blocks;
  blocks.width = width / 2;
  blocks.height = height / 2;
  blocks.sums.assign(size_t(blocks.width) * blocks.height, 0.0);
  blocks.squares.assign(blocks.sums.size(), 0.0);
  double total = 0.0;
  for (int y = 0; y < height; ++y) {
    const float* in = weights.data() + size_t(y) * width;
    const size_t block_row = size_t(y / 2) * blocks.width;
    for (int x = 0; x < width; ++x) {
      const double f = in[x];
      blocks.sums[block_row + x / 2] += f;
      blocks.squares[block_row + x / 2] += f * f;
      total += f;
    }
  }
  if (!(total > 0.0)) return {std::min(max_factor, largest_power_of_two_dividing(width, height, max_factor)), 0.0};
  for (int factor = 2;; factor *= 2) {
    const double v = added_variance(blocks, factor * factor, total);
    if (!(v <= max_added_variance)) break;
    chosen = {factor, v};
    if (factor * 2 > max_factor || blocks.width % 2 != 0 || blocks.height % 2 != 0) break;
    blocks = merge_pairs(blocks);
  }
  return chosen;
}

}  // namespace rimu
