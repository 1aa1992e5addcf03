#include "transport/sampling/primary_sample_sampler.h"

#include <cmath>

namespace rimu {

PrimarySampleSampler::PrimarySampleSampler(uint64_t seed, uint64_t stream, float sigma, float large_step_probability)
    : seed_(seed), stream_(stream), sigma_(sigma), large_step_probability_(large_step_probability) {
  continue_in_stream(stream);
}

void PrimarySampleSampler::continue_in_stream(uint64_t stream) {
  random_.increment = (mix_bits(stream ^ mix_bits(seed_)) << 1) | 1u;
  random_.state = mix_bits(seed_ * 0x9e3779b97f4a7c15ull + stream);
}

std::unique_ptr<Sampler> PrimarySampleSampler::clone() const {
  return std::make_unique<PrimarySampleSampler>(seed_, stream_, sigma_, large_step_probability_);
}

void PrimarySampleSampler::start_iteration() {
  ++iteration_;
  dimension_ = 0;
  // The first iteration is a large step that needs no number of its own, so that it reads the stream's first point.
  large_step_ = iteration_ == 0 || random_.next_1d() < large_step_probability_;
}

void PrimarySampleSampler::accept() {
  if (large_step_) last_large_step_ = iteration_;
}

void PrimarySampleSampler::reject() {
  for (Dimension& d : u_) {
    if (d.modified != iteration_) continue;
    d.value = d.backup;
    d.modified = d.modified_backup;
  }
  --iteration_;
}

float PrimarySampleSampler::normal() {
  // The sum of four uniform bytes of one 32-bit draw (Irwin–Hall), centred and scaled to unit variance: close to a
  // normal and, what the Metropolis–Hastings ratio needs, symmetric. A Box–Muller normal (a log and a cosine per
  // dimension per step) took 11 % of a door-ajar render (perf); this takes a few integer operations.
  const uint32_t bits = random_.next_bits();
  const int sum = int(bits & 0xffu) + int((bits >> 8) & 0xffu) + int((bits >> 16) & 0xffu) + int(bits >> 24);
  // Each byte has variance (256² − 1)/12, the sum four times that; its mean is 4 · 127.5 = 510.
  constexpr float kInverseDeviation = 0.0067658f;  // 1/√(4 · 65535/12) = 1/147.80
  return float(sum - 510) * kInverseDeviation;
}

float PrimarySampleSampler::next_1d() {
  if (dimension_ >= u_.size()) u_.resize(dimension_ + 1);
  Dimension& d = u_[dimension_++];
  if (d.modified == iteration_) return d.value;  // read twice in one iteration (not done by the integrators)
  // A dimension not read since before the last accepted large step: that step's value, drawn now.
  if (d.modified < last_large_step_) {
    d.value = random_.next_1d();
    d.modified = last_large_step_;
  }
  d.backup = d.value;
  d.modified_backup = d.modified;
  if (large_step_) {
    d.value = random_.next_1d();
  } else {
    // n small steps since the value was set: their offsets' sum, a normal of variance n·σ².
    const float spread = sigma_ * std::sqrt(float(iteration_ - d.modified));
    d.value += spread * normal();
    d.value -= std::floor(d.value);
    if (!(d.value < 1.0f)) d.value = 0.0f;  // -tiny wraps to 1.0f in float
  }
  d.modified = iteration_;
  return d.value;
}

}  // namespace rimu
