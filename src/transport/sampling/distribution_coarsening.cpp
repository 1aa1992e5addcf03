#include "transport/sampling/distribution_coarsening.h"

#include <cassert>

namespace rimu {

namespace {
/// Per-block Σf and Σf² of a blocking of the weights into (w/f) × (h/f) blocks of f × f cells.
struct BlockMoments {
  std::vector<double> sums, squares;
  int width = 0, height = 0, factor = 1;
  double total = 0.0;  // Σf over every cell
};

BlockMoments moments(std::span<const float> weights, int width, int height, int factor) {
  assert(factor >= 1 && width % factor == 0 && height % factor == 0 && weights.size() == size_t(width) * height);
  BlockMoments m;
  m.width = width / factor;
  m.height = height / factor;
  m.factor = factor;
  m.sums.assign(size_t(m.width) * m.height, 0.0);
  m.squares.assign(m.sums.size(), 0.0);
  for (int y = 0; y < height; ++y) {
    const size_t block_row = size_t(y / factor) * m.width;
    const float* in = weights.data() + size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      const double f = in[x];
      m.sums[block_row + x / factor] += f;
      m.squares[block_row + x / factor] += f * f;
      m.total += f;
    }
  }
  return m;
}

/// The moments of blocks twice as large: sums and squares add.
BlockMoments merge_pairs(const BlockMoments& fine) {
  BlockMoments coarse;
  coarse.width = fine.width / 2;
  coarse.height = fine.height / 2;
  coarse.factor = fine.factor * 2;
  coarse.total = fine.total;
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

/// R_f − 1 of the header: (1/F) Σₖ nₖ (Σ_{i∈k} fᵢ²)/Bₖ − 1; 0 if every weight is 0.
double added_variance(const BlockMoments& m) {
  if (!(m.total > 0.0)) return 0.0;
  const double cells_per_block = double(m.factor) * m.factor;
  double r = 0.0;
  for (size_t k = 0; k < m.sums.size(); ++k)
    if (m.sums[k] > 0.0) r += cells_per_block * m.squares[k] / m.sums[k];
  return r / m.total - 1.0;
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
  return added_variance(moments(weights, width, height, factor));
}

SamplingBlock choose_sampling_block(std::span<const float> weights, int width, int height,
                                    double max_added_variance, int max_factor) {
  SamplingBlock chosen;
  if (max_factor < 2 || width % 2 != 0 || height % 2 != 0) return chosen;
  // The 2 × 2 moments from the weights (one pass), then each coarser level from the one before: about 1.3 passes
  // over the table's size in all, instead of one per factor.
  for (BlockMoments m = moments(weights, width, height, 2);; m = merge_pairs(m)) {
    const double v = added_variance(m);
    if (!(v <= max_added_variance)) break;
    chosen = {m.factor, v};
    if (m.factor * 2 > max_factor || m.width % 2 != 0 || m.height % 2 != 0) break;
  }
  return chosen;
}

}  // namespace rimu
