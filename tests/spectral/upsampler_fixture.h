// The upsampling tests' shared set-up (upsampler_test.cpp, upsampling_basis_test.cpp): one RgbUpsampler per colour
// space, built on first use and kept for the test binary's life, so the tables are read and the fast path's bases
// built once for both files, and the spaces every "in every space" test walks.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "spectral/upsampling/rgb_upsampler.h"
#include "test_support.h"

namespace rimu::test {

inline const RgbUpsampler& upsampler(const std::string& space) {
  static std::map<std::string, std::unique_ptr<RgbUpsampler>> cache;
  auto& slot = cache[space];
  if (!slot) slot = std::make_unique<RgbUpsampler>(library(), RgbColourSpace::named(space));
  return *slot;
}

inline constexpr const char* kUpsamplerSpaces[] = {"srgb-linear", "rec2020", "display-p3",
                                                   "acescg",      "aces2065-1", "cie-rgb"};

}  // namespace rimu::test
