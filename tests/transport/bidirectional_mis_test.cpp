// The bidirectional MIS weights (transport/integrators/bidirectional_mis.h): the ratio walk must give each technique
// the balance heuristic's weight p_s / Σ p_s', written out here as products of all densities, and the weights of
// the techniques that can make a path must sum to one in every lane.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include "transport/integrators/bidirectional_mis.h"

using namespace rimu;

namespace {

struct RandomPath {
  std::vector<JoinedVertex> x;
  float p_nee = 0.0f, p_emit = 0.0f;
  bool hittable = false;
};

RandomPath random_path(std::mt19937& rng, int n) {
  std::uniform_real_distribution<float> density(0.01f, 10.0f);
  std::bernoulli_distribution coin(0.75);
  RandomPath path;
  path.x.resize(size_t(n));
  for (JoinedVertex& v : path.x) {
    v.pf = Float4(density(rng), density(rng), density(rng), density(rng));
    v.pc = Float4(density(rng), density(rng), density(rng), density(rng));
    v.connectible = coin(rng);
  }
  path.p_nee = density(rng);
  path.p_emit = density(rng);
  path.hittable = coin(rng);
  return path;
}

bool possible(const RandomPath& path, int s) {
  const int n = int(path.x.size());
  if (s == 0) return path.hittable;
  if (s == 1) return n >= 3 && path.x[1].connectible;
  if (s == n - 1) return path.x[size_t(n - 2)].connectible;
  return path.x[size_t(s - 1)].connectible && path.x[size_t(s)].connectible;
}

// Technique s's density of the path in one lane, as the product the walk avoids forming.
double density_of(const RandomPath& path, int s, int lane) {
  const int n = int(path.x.size());
  double p = s == 0 ? path.x[0].pc[lane] : s == 1 ? path.p_nee : path.p_emit;
  for (int i = 1; i <= s - 1; ++i) p *= path.x[size_t(i)].pf[lane];
  for (int i = std::max(s, 1); i <= n - 2; ++i) p *= path.x[size_t(i)].pc[lane];
  return p;
}

}  // namespace

TEST_CASE("bidirectional MIS: the ratio walk gives the balance heuristic, and the weights sum to one") {
  std::mt19937 rng(20261206);
  int paths_checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 2 + trial % 9;
    const RandomPath path = random_path(rng, n);
    for (int lane = 0; lane < 4; ++lane) {
      double total = 0.0, weights = 0.0;
      bool any = false;
      for (int s = 0; s <= n - 1; ++s)
        if (possible(path, s)) total += density_of(path, s, lane);
      for (int s = 0; s <= n - 1; ++s) {
        if (!possible(path, s)) continue;
        any = true;
        const SampledSpectrum sum = technique_sum(path.x.data(), n, s, path.p_nee, path.p_emit, path.hittable);
        const double weight = 1.0 / double(sum[lane]);
        CHECK(weight == doctest::Approx(density_of(path, s, lane) / total).epsilon(2e-5));
        weights += weight;
      }
      if (!any) continue;
      ++paths_checked;
      CHECK(weights == doctest::Approx(1.0).epsilon(1e-5));
    }
  }
  CHECK(paths_checked > 4000);
}

TEST_CASE("bidirectional MIS: a technique that cannot make the path (a zero density) takes no weight") {
  // Four vertices: a light, two surfaces, the lens. The light subpaths cannot start at this light (p_emit = 0):
  // techniques s = 2 and s = 3 have density 0, so s = 0 and s = 1 share the path by their densities alone.
  std::vector<JoinedVertex> x(4);
  for (JoinedVertex& v : x) {
    v.pf = Float4(2.0f);
    v.pc = Float4(3.0f);
    v.connectible = true;
  }
  const float p_nee = 5.0f;
  const SampledSpectrum hit = technique_sum(x.data(), 4, 0, p_nee, 0.0f, true);
  const SampledSpectrum nee = technique_sum(x.data(), 4, 1, p_nee, 0.0f, true);
  // p_0 = pc₀ pc₁ pc₂ = 27, p_1 = p_nee pc₁ pc₂ = 45.
  CHECK(hit[0] == doctest::Approx(72.0 / 27.0));
  CHECK(nee[0] == doctest::Approx(72.0 / 45.0));
  CHECK(1.0 / hit[0] + 1.0 / nee[0] == doctest::Approx(1.0));
}
