// Elementary-interval counting for base-2 nets in two dimensions, shared by the Sobol' tests.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rimu::test {

/// For 2ᵏ points given as 32-bit binary fractions, checks every elementary interval shape 2⁻ᵃ × 2⁻⁽ᵏ⁻ᵃ⁾
/// (a = 0..k): each of the 2ᵏ intervals of each shape must hold exactly one point (the (0,k,2)-net property).
/// Returns "" on success, else a description of the first failing shape.
inline std::string check_02_net(const std::vector<std::pair<uint32_t, uint32_t>>& points, int k) {
  if (points.size() != (size_t(1) << k)) return "expected 2^k points";
  for (int a = 0; a <= k; ++a) {
    std::vector<int> count(size_t(1) << k, 0);
    for (const auto& [u, v] : points) {
      // The leading a digits of u and k − a digits of v name the interval (64-bit shifts: a may be 0).
      const uint64_t cu = uint64_t(u) >> (32 - a), cv = uint64_t(v) >> (32 - (k - a));
      ++count[size_t((cu << (k - a)) | cv)];
    }
    for (size_t cell = 0; cell < count.size(); ++cell)
      if (count[cell] != 1)
        return "shape 2^-" + std::to_string(a) + " x 2^-" + std::to_string(k - a) + ": interval " +
               std::to_string(cell) + " holds " + std::to_string(count[cell]) + " points";
  }
  return "";
}

/// The float version: coordinates in [0,1) with at most 24 significant digits, as the samplers return them.
inline uint32_t unit_float_to_bits(float u) { return uint32_t(double(u) * 4294967296.0); }

}  // namespace rimu::test
