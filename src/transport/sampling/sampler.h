// Where a path's random numbers come from.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>

#include "transport/sampling/bit_mixing.h"  // mix_bits, used with samplers for seeding
#include "transport/sampling/pcg32.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// Hands out the uniform numbers of one pixel sample, dimension by dimension.
///
/// The integrator consumes dimensions in a fixed order (documented in path_integrator.h): every estimator draws
/// the same dimension for the same decision, so a low-discrepancy sampler stratifies each decision. Samplers are
/// deterministic functions of (seed, pixel, sample index, dimension): an image does not depend on the thread
/// count or tile order. One instance per thread (clone()); none is shared.
class Sampler {
 public:
  virtual ~Sampler() = default;
  /// Starts sample `sample_index` of pixel (x, y) at dimension 0.
  virtual void start_pixel_sample(int x, int y, uint32_t sample_index) = 0;
  /// The next dimension, uniform in [0, 1).
  virtual float next_1d() = 0;
  /// The next two dimensions, uniform in [0, 1)².
  virtual Vec2 next_2d() = 0;
  virtual std::unique_ptr<Sampler> clone() const = 0;
};

/// Independent uniform numbers (PCG32 seeded by a hash of seed, pixel and sample index): the baseline sampler.
class IndependentSampler final : public Sampler {
 public:
  explicit IndependentSampler(uint64_t seed) : seed_(seed) {}
  void start_pixel_sample(int x, int y, uint32_t sample_index) override;
  float next_1d() override;
  Vec2 next_2d() override;
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<IndependentSampler>(seed_); }

 private:
  uint64_t seed_;
  Pcg32 random_;
};

/// Which sampler a render uses (docs/sampling.md compares them).
enum class SamplerKind {
  independent,  ///< IndependentSampler: the baseline
  sobol,        ///< SobolSampler (transport/sampling/sobol_sampler.h): padded Owen-scrambled Sobol' pairs, the default
};

/// A sampler of the given kind and seed (the prototype the render loop clones per thread).
std::unique_ptr<Sampler> make_sampler(SamplerKind kind, uint64_t seed);
/// "independent" or "sobol".
const char* sampler_kind_name(SamplerKind kind);
/// The kind named "independent" or "sobol"; nullopt for anything else.
std::optional<SamplerKind> parse_sampler_kind(std::string_view name);

}  // namespace rimu
