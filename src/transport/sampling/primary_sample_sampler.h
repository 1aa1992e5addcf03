// The random numbers of a Markov chain in primary sample space (Kelemen et al. 2002, "A Simple and Robust Mutation
// Strategy for the Metropolis Light Transport Algorithm"): Metropolis light transport over any integrator that draws
// its decisions from a Sampler.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "transport/sampling/pcg32.h"
#include "transport/sampling/sampler.h"

namespace rimu {

/// A point u of the unit hypercube that an integrator reads dimension by dimension, and its mutations.
///
/// Each iteration proposes a new point: a large step draws every dimension anew (an independent sample, which lets
/// the chain leave any region), a small step moves each by a normal offset of standard deviation `sigma`, wrapped
/// into [0, 1) (a symmetric proposal: the acceptance probability is f(u')/f(u)). Dimensions are mutated lazily, when
/// the integrator first reads them in an iteration: one untouched for n small steps moves by √n·sigma, the sum of n
/// offsets, and one untouched since a large step was accepted is drawn anew. reject() restores the dimensions the
/// iteration touched.
///
/// A chain's numbers come from one PCG32 stream keyed by (seed, stream): the first iteration of stream i reads the
/// same point as a fresh sampler of stream i does (the bootstrap samples a chain starts from are replayed exactly).
class PrimarySampleSampler final : public Sampler {
 public:
  PrimarySampleSampler(uint64_t seed, uint64_t stream, float sigma, float large_step_probability);

  /// Begins the next proposal (the first call: the stream's first point, a large step) at dimension 0.
  void start_iteration();
  /// Keeps the proposal as the chain's state.
  void accept();
  /// Returns to the state before the proposal.
  void reject();
  bool large_step() const { return large_step_; }
  /// The value of `dimension` in the current point (tests; only dimensions read since the last large step accepted).
  float value(size_t dimension) const { return u_.at(dimension).value; }
  /// Draws the numbers from here on from stream `stream` of the same seed: a chain started from a bootstrap sample
  /// (replayed from that sample's stream) continues in a stream of its own, so two chains that start from the same
  /// sample part after it.
  void continue_in_stream(uint64_t stream);
  /// A uniform number from the chain's stream that is not part of u (the acceptance test).
  float next_free_1d() { return random_.next_1d(); }

  /// Restarts the current proposal's reading at dimension 0 (the point does not change).
  void start_pixel_sample(int, int, uint32_t) override { dimension_ = 0; }
  float next_1d() override;
  Vec2 next_2d() override {
    const float a = next_1d();
    return {a, next_1d()};
  }
  /// A sampler of the same stream and settings in its initial state (a chain is not copied mid-way).
  std::unique_ptr<Sampler> clone() const override;

 private:
  struct Dimension {
    float value = 0.0f;
    float backup = 0.0f;
    int64_t modified = -1;  ///< the iteration that last set the value
    int64_t modified_backup = -1;
  };
  float normal();

  uint64_t seed_, stream_;
  float sigma_, large_step_probability_;
  Pcg32 random_;
  std::vector<Dimension> u_;
  size_t dimension_ = 0;
  int64_t iteration_ = -1;
  int64_t last_large_step_ = -1;  ///< the iteration of the last accepted large step
  bool large_step_ = true;
};

}  // namespace rimu
