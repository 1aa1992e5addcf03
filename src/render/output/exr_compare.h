// Comparing two EXR images value by value in units in the last place (ULPs) of float32: how tests and the farm
// scripts check that a merged or resumed image equals a single process's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace rimu {

struct ExrDifference {
  uint64_t values = 0;           ///< values compared (image channels as float32; UINT channels bit for bit)
  uint64_t different = 0;        ///< values that are not bit-identical
  uint64_t max_ulps = 0;         ///< the largest float32 ULP distance of an image value (UINT: any difference = 1)
  std::string worst;             ///< where max_ulps occurs: "channel Y at (x, y): a vs b"
};

/// Compares every channel of `a` with the same channel of `b` (half and float channels read as float32; UINT
/// channels, e.g. a partial's sums, compared exactly unless `image_only`, which skips them). InputError naming the
/// file if either cannot be read or their data windows or channel lists differ.
ExrDifference compare_exr(const std::filesystem::path& a, const std::filesystem::path& b, bool image_only);

}  // namespace rimu
