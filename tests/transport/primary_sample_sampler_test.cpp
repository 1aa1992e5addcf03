// The Markov chain's random numbers for Metropolis light transport (transport/sampling/primary_sample_sampler.h): a
// chain replays a bootstrap sample exactly, rejected proposals leave no trace, every value stays in [0, 1), the
// mutations keep the uniform density stationary, and a Metropolis–Hastings chain built on them samples a target
// density, also in a dimension it reads only on some iterations (the lazy mutation a path of varying length needs).
#include "transport/sampling/primary_sample_sampler.h"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "statistics.h"

using namespace rimu;

namespace {

constexpr double kAlpha = 1e-4;  // the suite's family-wise level for chi-square tests of fixed seeds

// Counts of `values` in `bins` equal bins of [0, 1).
std::vector<double> histogram(const std::vector<float>& values, int bins) {
  std::vector<double> counts(size_t(bins), 0.0);
  for (float v : values) counts[size_t(std::min(bins - 1, int(v * float(bins))))] += 1.0;
  return counts;
}

// Expected counts of n draws from the density ∝ 0.5 + u on [0, 1) (normalised: 0.5 + u) in equal bins.
std::vector<double> expected_ramp(double n, int bins) {
  std::vector<double> e(static_cast<size_t>(bins));
  for (int b = 0; b < bins; ++b) {
    const double lo = double(b) / bins, hi = double(b + 1) / bins;
    e[size_t(b)] = n * (0.5 * (hi - lo) + 0.5 * (hi * hi - lo * lo));
  }
  return e;
}

}  // namespace

TEST_CASE("primary sample space: a chain's first point replays its bootstrap stream exactly") {
  PrimarySampleSampler bootstrap(7, 42, 0.01f, 0.3f), chain(7, 42, 0.01f, 0.3f), other(7, 43, 0.01f, 0.3f);
  bootstrap.start_iteration();
  chain.start_iteration();
  other.start_iteration();
  int differ = 0;
  for (int d = 0; d < 64; ++d) {
    const float a = bootstrap.next_1d(), b = chain.next_1d();
    CHECK(a == b);
    CHECK(a >= 0.0f);
    CHECK(a < 1.0f);
    differ += other.next_1d() != a;
  }
  CHECK(differ == 64);
  // Two chains that start from one bootstrap sample part after it.
  PrimarySampleSampler twin(7, 42, 0.01f, 0.3f);
  twin.start_iteration();
  for (int d = 0; d < 8; ++d) twin.next_1d();
  chain.accept();
  twin.accept();
  chain.continue_in_stream(1000);
  twin.continue_in_stream(1001);
  chain.start_iteration();
  twin.start_iteration();
  int same = 0;
  for (int d = 0; d < 8; ++d) same += chain.next_1d() == twin.next_1d();
  CHECK(same < 8);
}

TEST_CASE("primary sample space: a rejected proposal restores the point, and the next mutates from it") {
  PrimarySampleSampler s(3, 5, 0.05f, 0.0f);
  s.start_iteration();
  std::vector<float> start(20);
  for (float& v : start) v = s.next_1d();
  s.accept();
  for (int round = 0; round < 50; ++round) {
    s.start_iteration();
    int moved = 0;
    for (size_t d = 0; d < start.size(); ++d) moved += s.next_1d() != start[d];
    CHECK(moved == int(start.size()));  // a small step moves every dimension it reads
    s.reject();
    for (size_t d = 0; d < start.size(); ++d) CHECK(s.value(d) == start[d]);
  }
  // Accepted, the proposal becomes the point.
  s.start_iteration();
  std::vector<float> proposal(start.size());
  for (float& v : proposal) v = s.next_1d();
  s.accept();
  for (size_t d = 0; d < start.size(); ++d) CHECK(s.value(d) == proposal[d]);
}

TEST_CASE("primary sample space: values stay below 1 and at or above 0 under small and large steps") {
  for (float sigma : {1e-6f, 0.01f, 0.3f, 2.0f}) {
    PrimarySampleSampler s(11, 1, sigma, 0.1f);
    bool inside = true;
    for (int i = 0; i < 20000; ++i) {
      s.start_iteration();
      for (int d = 0; d < 6; ++d) {
        const float v = s.next_1d();
        inside = inside && v >= 0.0f && v < 1.0f;
      }
      if (i % 3 == 0)
        s.reject();
      else
        s.accept();
    }
    INFO("sigma " << sigma);
    CHECK(inside);
  }
}

TEST_CASE("primary sample space: small steps keep the uniform density stationary (chi-square)") {
  // Independent chains started uniformly, each after 6 accepted small steps: still uniform, the wrapped symmetric
  // kernel's stationary density; dimension 1 is read only on every other step (mutated lazily by √n σ).
  const int chains = 20000, bins = 20;
  std::vector<float> d0, d1;
  for (int c = 0; c < chains; ++c) {
    PrimarySampleSampler s(5, uint64_t(c), 0.2f, 0.0f);
    for (int step = 0; step < 7; ++step) {
      s.start_iteration();
      s.next_1d();
      if (step % 2 == 0) s.next_1d();
      s.accept();
    }
    d0.push_back(s.value(0));
    d1.push_back(s.value(1));
  }
  const std::vector<double> expected(size_t(bins), double(chains) / bins);
  for (const auto* values : {&d0, &d1}) {
    const test::ChiSquareResult r =
        test::pearson_chi_square(histogram(*values, bins), expected, test::Pooling::adjacent);
    INFO("chi-square " << r.statistic << ", p " << r.p_value);
    CHECK(r.p_value > test::sidak_threshold(kAlpha, 2));
  }
}

TEST_CASE("primary sample space: a Metropolis chain samples its target, also in a dimension read on some steps only") {
  // Target f(u₀, u₁) = (0.5 + u₀)·(0.5 + u₁) where u₀ < 0.5, else 0.5 + u₀, with u₁ read only where u₀ < 0.5 (as a
  // path reads the dimensions of bounces it takes). Marginals: u₀ ∝ 0.5 + u₀; u₁ given u₀ < 0.5 ∝ 0.5 + u₁.
  const int chains = 20000, steps = 200, bins = 10;
  std::vector<float> first, second;
  for (int c = 0; c < chains; ++c) {
    PrimarySampleSampler s(9, uint64_t(c), 0.1f, 0.3f);
    const auto target = [&] {
      const float u0 = s.next_1d();
      return u0 < 0.5f ? (0.5f + u0) * (0.5f + s.next_1d()) : 0.5f + u0;
    };
    s.start_iteration();
    float current = target();
    s.accept();
    Pcg32 accept_random{uint64_t(c) * 2654435761u, 1};
    for (int step = 0; step < steps; ++step) {
      s.start_iteration();
      const float proposal = target();
      if (accept_random.next_1d() < std::min(1.0f, proposal / current)) {
        s.accept();
        current = proposal;
      } else {
        s.reject();
      }
    }
    first.push_back(s.value(0));
    if (s.value(0) < 0.5f) second.push_back(s.value(1));
  }
  const test::ChiSquareResult r0 = test::pearson_chi_square(
      histogram(first, bins), expected_ramp(double(first.size()), bins), test::Pooling::adjacent);
  const test::ChiSquareResult r1 = test::pearson_chi_square(
      histogram(second, bins), expected_ramp(double(second.size()), bins), test::Pooling::adjacent);
  INFO("u0: chi-square " << r0.statistic << ", p " << r0.p_value << "; u1: " << r1.statistic << ", p " << r1.p_value);
  CHECK(r0.p_value > test::sidak_threshold(kAlpha, 2));
  CHECK(r1.p_value > test::sidak_threshold(kAlpha, 2));
}
