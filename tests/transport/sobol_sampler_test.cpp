// The SobolSampler as the render loop uses it: values in [0,1), every decision stratified per pixel (the draws
// in the documented dimension order of path_integrator.h), pixels and draws decorrelated, and results that do
// not depend on the order in which pixels and samples are visited.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "sobol_net_check.h"
#include "transport/sampling/sobol_sampler.h"

using namespace rimu;

namespace {

// One camera sample's first two bounces in the integrator's order: film 2, lens 2, wavelength 1; then per
// bounce light choice 1, light position 2, BSDF lobe 1, BSDF direction 2, Russian roulette 1.
constexpr int kDraws = 15;
constexpr int kDrawSize[kDraws] = {2, 2, 1, 1, 2, 1, 2, 1, 1, 2, 1, 2, 1, 1, 1};

struct Draw {
  float u = 0, v = 0;
};

std::vector<Draw> camera_sample(Sampler& sampler, int x, int y, uint32_t index) {
  sampler.start_pixel_sample(x, y, index);
  std::vector<Draw> draws;
  for (int size : kDrawSize) {
    if (size == 2) {
      const Vec2 p = sampler.next_2d();
      draws.push_back({p.x, p.y});
    } else {
      draws.push_back({sampler.next_1d(), 0.0f});
    }
  }
  return draws;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = double(a.size());
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

}  // namespace

TEST_CASE("SobolSampler values lie in 0 to 1, excluding 1, and dimensions advance as documented") {
  SobolSampler sampler(7);
  for (int p = 0; p < 64; ++p)
    for (uint32_t i = 0; i < 64; ++i) {
      for (const Draw& d : camera_sample(sampler, p % 8, p / 8, i * 977u)) {
        CHECK((d.u >= 0.0f && d.u < 1.0f));
        CHECK((d.v >= 0.0f && d.v < 1.0f));
      }
    }
  sampler.start_pixel_sample(0, 0, 0);
  sampler.next_2d();
  sampler.next_2d();
  sampler.next_1d();
  CHECK(sampler.dimension() == 5);  // film 0-1, lens 2-3, wavelength 4: the integrator starts at 5
}

TEST_CASE("Every decision of a pixel is stratified: 2D draws are (0,k,2)-nets, 1D draws hit every interval") {
  // The padded construction gives each draw its own scrambled, shuffled copy of a (0,2)-sequence, so in every
  // pixel the samples of any aligned block of 2^k (the render's passes end on such blocks at 2^k spp) stratify
  // every 2D decision in all elementary-interval shapes and every 1D decision into 2^k equal intervals.
  SobolSampler sampler(3);
  const int k = 8;
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{17, 5}, std::pair{1023, 767}}) {
    for (uint32_t first : {0u, 256u}) {
      std::vector<std::vector<Draw>> samples;
      for (uint32_t i = first; i < first + (1u << k); ++i) samples.push_back(camera_sample(sampler, x, y, i));
      for (int d = 0; d < kDraws; ++d) {
        INFO("pixel (", x, ", ", y, "), samples from ", first, ", draw ", d);
        if (kDrawSize[d] == 2) {
          std::vector<std::pair<uint32_t, uint32_t>> points;
          for (const auto& s : samples)
            points.emplace_back(test::unit_float_to_bits(s[size_t(d)].u), test::unit_float_to_bits(s[size_t(d)].v));
          CHECK(test::check_02_net(points, k) == "");
        } else {
          std::set<int> cells;
          for (const auto& s : samples) cells.insert(int(s[size_t(d)].u * float(1 << k)));
          CHECK(cells.size() == (size_t(1) << k));
        }
      }
    }
  }
}

TEST_CASE("Neighbouring pixels and different draws are decorrelated") {
  // Per-pixel scrambling seeds make the sequences of two pixels independent randomisations, and the per-draw
  // shuffles pair the draws of one sample at random. Over n pairs of independent uniforms the sample correlation
  // has standard deviation 1/√(n−1); with n = 32·32·16 = 16384 the bound 5/√n = 0.039 is exceeded by chance with
  // probability 6e-7 per statistic. Without per-pixel scrambling the correlation would be exactly 1.
  SobolSampler sampler(11);
  const int size = 32, spp = 16;
  std::vector<double> film_u, film_u_right, film_v, film_v_below, lambda, lambda_right, lobe, light_u;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (uint32_t i = 0; i < uint32_t(spp); ++i) {
        const std::vector<Draw> here = camera_sample(sampler, x, y, i);
        const std::vector<Draw> right = camera_sample(sampler, x + 1, y, i);
        const std::vector<Draw> below = camera_sample(sampler, x, y + 1, i);
        film_u.push_back(here[0].u), film_u_right.push_back(right[0].u);
        film_v.push_back(here[0].v), film_v_below.push_back(below[0].v);
        lambda.push_back(here[2].u), lambda_right.push_back(right[2].u);
        lobe.push_back(here[5].u), light_u.push_back(here[4].u);
      }
  const double bound = 5.0 / std::sqrt(double(film_u.size()));
  CHECK(std::fabs(correlation(film_u, film_u_right)) < bound);
  CHECK(std::fabs(correlation(film_v, film_v_below)) < bound);
  CHECK(std::fabs(correlation(lambda, lambda_right)) < bound);
  CHECK(std::fabs(correlation(film_u, lambda)) < bound);  // different draws of the same sample
  CHECK(std::fabs(correlation(lobe, light_u)) < bound);
}

TEST_CASE("SobolSampler results do not depend on the order of pixels, samples or instances") {
  // What makes renders independent of the thread count and tile order: each value is a function of
  // (seed, pixel, sample index, dimension) only. Compared bit for bit.
  const SobolSampler prototype(42);
  auto forward = prototype.clone();
  std::vector<std::vector<Draw>> reference;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (uint32_t i = 0; i < 8; ++i) reference.push_back(camera_sample(*forward, x, y, i));
  // Another instance, visiting pixels and samples in reverse order, interleaved with unrelated draws.
  auto backward = prototype.clone();
  for (int n = 127; n >= 0; --n) {
    camera_sample(*backward, 1000 + n, 3, uint32_t(n));
    const std::vector<Draw> again = camera_sample(*backward, (n / 8) % 4, n / 32, uint32_t(n % 8));
    for (int d = 0; d < kDraws; ++d) {
      CHECK(again[size_t(d)].u == reference[size_t(n)][size_t(d)].u);
      CHECK(again[size_t(d)].v == reference[size_t(n)][size_t(d)].v);
    }
  }
  // A different seed gives different numbers.
  SobolSampler other(43);
  CHECK(camera_sample(other, 0, 0, 0)[0].u != reference[0][0].u);
}
