// How coarse a piecewise-constant sampling table may be: summing the weights of f × f blocks of cells gives a
// table with f² times fewer cells, whose density is constant over each block instead of following every cell.
//
// Why. An environment map of 2048² pixels makes sampling tables of 16 MiB each, and every light sample reads a
// random row of one: cache misses that were a sixth of a dense cloud's render time under such a sky. Many maps
// carry less detail than their pixel count (pbrt's `imgtool makeequiarea` resamples a 255 KB latitude-longitude
// sky to 2048²), and a table 4× coarser in each direction then samples them as well, in 1 MiB.
//
// The measure (importance-sampling theory). Sampling the cells' own sum ∫f by the density p gives an estimator
// with relative second moment R = (1/F²) Σᵢ fᵢ²/pᵢ, F = Σᵢ fᵢ: 1 for the exact table (p ∝ f), larger for a
// coarser one. For a block k of nₖ cells with sum Bₖ the coarse density gives each of its cells pᵢ = Bₖ/(nₖ F), so
//   R_f = (1/F) Σₖ nₖ (Σ_{i∈k} fᵢ²) / Bₖ.
// R_f − 1 is the relative variance the coarsening adds to a light sample whose other factors (BSDF, cosine,
// visibility) vary independently of the map within a block: a light sample's relative second moment (1 + v) becomes
// about R_f (1 + v). choose_sampling_block takes the largest power-of-two factor dividing both sides with
// R_f − 1 ≤ the allowed increase, going up from f = 2 and stopping at the first factor above it. R_f ≥ R_1 = 1
// always, but it need not grow with f (4 × 4 cells: one 2 × 2 block holding a single cell of 1, three holding 0.5
// in every cell: R_2 = 10/7, R_4 = 64/49), so a larger factor past a rejected one is not tried: on real maps the
// cost of blocks grows with their size, and stopping early only keeps a table finer than it could be.
#pragma once

#include <span>
#include <vector>

namespace rimu {

struct SamplingBlock {
  int factor = 1;               ///< cells per block side (1: keep every cell)
  double added_variance = 0.0;  ///< R_f − 1 of that factor
};

/// The block sums of `weights` (width × height cells, row by row, finite and ≥ 0) for factor f, which must
/// divide both sides: (width/f) × (height/f) cells.
std::vector<float> block_sums(std::span<const float> weights, int width, int height, int factor);

/// R_f − 1 (above) of sampling `weights` by their f × f block sums; 0 if every weight is 0.
double coarsening_added_variance(std::span<const float> weights, int width, int height, int factor);

/// The coarsest power-of-two blocking (up to `max_factor`) whose added variance is ≤ `max_added_variance`.
SamplingBlock choose_sampling_block(std::span<const float> weights, int width, int height,
                                    double max_added_variance, int max_factor = 16);

}  // namespace rimu
