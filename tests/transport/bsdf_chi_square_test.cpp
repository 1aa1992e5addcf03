// Chi-square goodness-of-fit of every BSDF's sample() against its pdf() (pbrt-v4's bsdfs_test and Mitsuba 3's
// chi2 tests do the same): if sample() draws from a density other than the one pdf() reports, MIS and the
// estimator weights are wrong, and this test sees it as a histogram that does not fit.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "bsdf_chi_square.h"
#include "spectral/library/optical_constants.h"
#include "statistics.h"
#include "transport/bsdfs/fresnel.h"
#include "test_support.h"

using namespace rimu;

namespace {

// 50 000 samples: a lobe holding a tenth of them that is off by 5% gives a chi-square excess of ~12 on its own,
// against a Šidák threshold near p = 4e-4; each configuration runs in tens of milliseconds.
constexpr int kSamples = 50000;
// Family-wise significance per TEST_CASE; the Šidák correction divides it over the configurations tested.
constexpr double kAlpha = 0.01;

/// Four wavelengths, the hero first and the partners 100 nm apart, wrapping inside 450-750 nm.
SampledWavelengths wavelengths_with_hero(float hero_nm) {
  const float all[4] = {450.0f, 550.0f, 650.0f, 750.0f};
  int first = 0;
  while (all[first] != hero_nm) ++first;
  return SampledWavelengths(Float4(all[first], all[(first + 1) % 4], all[(first + 2) % 4], all[(first + 3) % 4]),
                            Float4(1.0f / 300.0f));
}

/// A unit direction with the given cos θ (sign = side) at an azimuth off the frame's axes.
Vec3 direction(float cos_theta) {
  const float sin_theta = std::sqrt(std::fmax(0.0f, 1.0f - cos_theta * cos_theta));
  return {sin_theta * std::cos(0.7f), sin_theta * std::sin(0.7f), cos_theta};
}

const float kCosines[] = {0.9f, 0.5f, 0.05f, 0.01f};  // including the grazing 0.05 and 0.01
const float kHeroes[] = {450.0f, 550.0f, 650.0f};

struct Case {
  Bsdf bsdf;
  Vec3 wo;
  std::string label;
};

void run_all(const std::vector<Case>& cases) {
  const double threshold = test::sidak_threshold(kAlpha, int(cases.size()));
  uint64_t seed = 1;
  for (const Case& c : cases) {
    CAPTURE(c.label);
    const auto outcome = test::bsdf_chi_square(c.bsdf, c.wo, kSamples, seed++);
    CAPTURE(outcome.failure);
    CAPTURE(outcome.chi_square);
    CAPTURE(outcome.degrees_of_freedom);
    CHECK(outcome.failure.empty());
    CHECK(outcome.p_value > threshold);
  }
}

/// f(η) per lane, for a BSDF's per-lane inputs that are functions of its index (tabulated Fresnel averages).
template <typename F>
Float4 per_lane(Float4 eta, F&& f) {
  Float4 out;
  for (int lane = 0; lane < 4; ++lane) out.set(lane, float(f(double(eta[lane]))));
  return out;
}

std::string label(const std::string& what, float alpha, float cos_theta, float hero_nm) {
  return std::string(what) + " alpha " + std::to_string(alpha) + " cos(wo) " + std::to_string(cos_theta) + " hero " +
         std::to_string(hero_nm) + " nm";
}

std::vector<Case> rough_dielectric_cases(float alpha, float side) {
  const SpectrumPtr bk7 = dielectric_ior(test::library(), "bk7");
  std::vector<Case> cases;
  for (float hero : kHeroes) {
    const Float4 eta = bk7->sample(wavelengths_with_hero(hero));
    for (float c : kCosines)
      cases.push_back({DielectricBsdf(eta, TrowbridgeReitz(alpha, alpha)), direction(side * c),
                       label(side > 0 ? "BK7 from outside" : "BK7 from inside", alpha, side * c, hero)});
  }
  return cases;
}

}  // namespace

TEST_CASE("chi-square: Lambertian sample() matches pdf() on both sides and at grazing wo") {
  std::vector<Case> cases;
  for (float c : kCosines)
    for (float side : {1.0f, -1.0f})
      cases.push_back({DiffuseBsdf(Float4(0.8f, 0.5f, 0.3f, 0.1f)), direction(side * c), label("diffuse", 0, side * c, 0)});
  run_all(cases);
}

TEST_CASE("chi-square: rough gold, isotropic and anisotropic GGX, matches pdf()") {
  const ComplexIorSpectra gold = conductor_ior(test::library(), "gold");
  const SampledWavelengths lambda = wavelengths_with_hero(550.0f);
  const struct {
    float alpha_x, alpha_y;
  } widths[] = {{0.05f, 0.05f}, {0.3f, 0.3f}, {0.8f, 0.8f}, {0.05f, 0.3f}};
  std::vector<Case> cases;
  for (const auto& w : widths)
    for (float c : kCosines)
      cases.push_back({ConductorBsdf(gold.n->sample(lambda), gold.k->sample(lambda), TrowbridgeReitz(w.alpha_x, w.alpha_y)),
                       direction(c), label("gold, alpha_y " + std::to_string(w.alpha_y), w.alpha_x, c, 550)});
  run_all(cases);
}

TEST_CASE("chi-square: rough BK7 with alpha 0.05, reflection and transmission from outside") {
  run_all(rough_dielectric_cases(0.05f, 1.0f));
}
TEST_CASE("chi-square: rough BK7 with alpha 0.05, reflection and transmission from inside") {
  run_all(rough_dielectric_cases(0.05f, -1.0f));
}
TEST_CASE("chi-square: rough BK7 with alpha 0.3, reflection and transmission from outside") {
  run_all(rough_dielectric_cases(0.3f, 1.0f));
}
TEST_CASE("chi-square: rough BK7 with alpha 0.3, reflection and transmission from inside") {
  run_all(rough_dielectric_cases(0.3f, -1.0f));
}
TEST_CASE("chi-square: rough BK7 with alpha 0.8, reflection and transmission from outside") {
  run_all(rough_dielectric_cases(0.8f, 1.0f));
}
TEST_CASE("chi-square: rough BK7 with alpha 0.8, reflection and transmission from inside") {
  run_all(rough_dielectric_cases(0.8f, -1.0f));
}

TEST_CASE("chi-square: smooth BK7 reflects and refracts with the probabilities it reports") {
  // Two delta cells: the frequency of reflection must match R(hero) and of refraction 1 − R(hero), including
  // beyond the critical angle from inside (cos θ = 0.5, 0.05, 0.01 < cos θc = 0.75 for BK7), where R = 1.
  const SpectrumPtr bk7 = dielectric_ior(test::library(), "bk7");
  std::vector<Case> cases;
  for (float hero : kHeroes)
    for (float c : kCosines)
      for (float side : {1.0f, -1.0f})
        cases.push_back({DielectricBsdf(bk7->sample(wavelengths_with_hero(hero)), TrowbridgeReitz(0, 0)),
                         direction(side * c), label("smooth BK7", 0, side * c, hero)});
  run_all(cases);
}

TEST_CASE("chi-square: a thin BK7 sheet reflects and transmits with the probabilities it reports") {
  // Two delta cells, the mirror and the straight-through direction, with frequencies R(hero) and 1 − R(hero).
  const SpectrumPtr bk7 = dielectric_ior(test::library(), "bk7");
  std::vector<Case> cases;
  for (float hero : kHeroes)
    for (float c : kCosines)
      for (float side : {1.0f, -1.0f})
        cases.push_back({ThinDielectricBsdf(bk7->sample(wavelengths_with_hero(hero))), direction(side * c),
                         label("thin BK7", 0, side * c, hero)});
  run_all(cases);
}

TEST_CASE("chi-square: coated diffuse chooses coat and base with the probabilities and density it reports") {
  const SpectrumPtr bk7 = dielectric_ior(test::library(), "bk7");
  std::vector<Case> cases;
  for (float hero : kHeroes) {
    const Float4 eta = bk7->sample(wavelengths_with_hero(hero));
    const Float4 diffuse_fresnel = per_lane(eta, [](double e) { return fresnel_diffuse_reflectance(e); });
    for (float c : kCosines)
      cases.push_back({CoatedDiffuseBsdf(Float4(0.7f, 0.4f, 0.2f, 0.05f), eta, diffuse_fresnel), direction(c),
                       label("coated diffuse", 0, c, hero)});
  }
  run_all(cases);
}

TEST_CASE("chi-square: a diffuse-entry boundary, from inside: the mirror and the way out with the density it reports") {
  // From inside: a delta cell (the mirror, R(hero), all of it beyond the critical angle: cos θ < 0.75 for BK7)
  // and the Fresnel-weighted cosine lobe outside; from outside: the smooth dielectric's two delta cells.
  const SpectrumPtr bk7 = dielectric_ior(test::library(), "bk7");
  std::vector<Case> cases;
  for (float hero : kHeroes) {
    const Float4 eta = bk7->sample(wavelengths_with_hero(hero));
    const Float4 norm = per_lane(eta, DielectricBsdf::diffuse_entry_normalisation);
    for (float c : kCosines)
      for (float side : {-1.0f, 1.0f})
        for (float alpha : {0.0f, 0.3f})
          cases.push_back({DielectricBsdf(eta, TrowbridgeReitz(alpha, alpha), norm), direction(side * c),
                           label("diffuse-entry BK7", alpha, side * c, hero)});
  }
  run_all(cases);
}
