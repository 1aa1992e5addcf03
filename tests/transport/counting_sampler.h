// A sampler that counts the dimensions drawn from it (an independent sampler underneath): for tests of how many
// random numbers an estimator takes.
#pragma once

#include <cstdint>
#include <memory>

#include "transport/sampling/sampler.h"

namespace rimu::test {

class CountingSampler final : public Sampler {
 public:
  explicit CountingSampler(uint64_t seed) : inner_(seed) {}
  /// Restarts the count too.
  void start_pixel_sample(int x, int y, uint32_t i) override {
    inner_.start_pixel_sample(x, y, i);
    count = 0;
  }
  float next_1d() override {
    ++count;
    return inner_.next_1d();
  }
  Vec2 next_2d() override {
    count += 2;
    return inner_.next_2d();
  }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<CountingSampler>(1); }
  long count = 0;

 private:
  IndependentSampler inner_;
};

}  // namespace rimu::test
