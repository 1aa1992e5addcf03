#include "spectral/upsampling/dense_linear_solve.h"

#include <cmath>
#include <utility>

namespace rimu {

bool solve_dense(std::vector<double>& m, std::vector<double>& b, int size) {
  for (int col = 0; col < size; ++col) {
    int pivot = col;
    for (int r = col + 1; r < size; ++r)
      if (std::abs(m[r * size + col]) > std::abs(m[pivot * size + col])) pivot = r;
    if (std::abs(m[pivot * size + col]) < 1e-300) return false;
    if (pivot != col) {
      for (int c = 0; c < size; ++c) std::swap(m[col * size + c], m[pivot * size + c]);
      std::swap(b[col], b[pivot]);
    }
    for (int r = col + 1; r < size; ++r) {
      const double f = m[r * size + col] / m[col * size + col];
      if (f == 0.0) continue;
      for (int c = col; c < size; ++c) m[r * size + c] -= f * m[col * size + c];
      b[r] -= f * b[col];
    }
  }
  for (int r = size - 1; r >= 0; --r) {
    double s = b[r];
    for (int c = r + 1; c < size; ++c) s -= m[r * size + c] * b[c];
    b[r] = s / m[r * size + r];
  }
  return true;
}

}  // namespace rimu
