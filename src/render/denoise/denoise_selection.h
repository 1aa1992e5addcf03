// How the denoiser (render/denoise/nfor_denoiser.h) picks, per pixel, one of its candidate filters: each
// candidate's error estimated from the two half buffers.
#pragma once

#include <array>
#include <vector>

#include "render/denoise/denoise_inputs.h"

namespace rimu {

/// filtered[c][t]: half t filtered by candidate c, with weights computed from the other half (3 channels).
using FilteredHalves = std::vector<std::array<std::vector<float>, 2>>;

/// Per candidate c and pixel p, the estimated relative error of c at p: the mean over halves t and channels of
/// (Â_t − B_{1−t})² / (m² + Var_half), Â_t half t filtered by c, B_{1−t} the other half's noisy value, m the first
/// candidate's estimate. Â_t and B_{1−t} are independent, so E[(Â_t − B_{1−t})²] = MSE(Â_t) + Var(B): Var(B) is the
/// same for every candidate, so the least estimate picks the least error. Relative, as the benchmarks' relMSE
/// measures: an absolute error would let the bright channels decide alone, and the filter that blurs a dim channel
/// (the red of a cyan patch, near 0) would win wherever it smooths the bright ones a little more. Var_half (a half's
/// variance, channels averaged) keeps a channel near 0 from being divided by ~0. Every output is finite and ≥ 0.
std::vector<std::vector<float>> candidate_errors(const PreparedDenoiseInput& d, const FilteredHalves& filtered);

}  // namespace rimu
