#include "render/image/mip_pyramid.h"

namespace rimu {
namespace {

constexpr int kEwaTableSize = 128;

// exp(−α r²) − exp(−α) at the centre of each of kEwaTableSize equal steps of r² ∈ [0, 1), α = 2 (Heckbert's
// Gaussian, shifted to reach zero at the ellipse's edge).
struct EwaTable {
  std::array<float, kEwaTableSize> weight{};
  EwaTable() {
    constexpr double kAlpha = 2.0;
    for (int i = 0; i < kEwaTableSize; ++i) {
      const double r2 = (i + 0.5) / kEwaTableSize;
      weight[size_t(i)] = float(std::exp(-kAlpha * r2) - std::exp(-kAlpha));
    }
  }
};

}  // namespace

float ewa_gaussian_weight(float r2) {
  static const EwaTable table;  // a pure function's cache, filled on first use
  const int i = std::clamp(int(r2 * float(kEwaTableSize)), 0, kEwaTableSize - 1);
  return table.weight[size_t(i)];
}

}  // namespace rimu
