// Path guiding's learned distributions (transport/guiding/): for several trained fields, the directional pdf
// integrates to one over the sphere and sample_direction() follows it (Pearson's chi-square over cells of the
// equal-area square); the BSDF/guide mixture's density integrates to one; the spatial tree keeps what it learned
// apart in space.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "light_test_support.h"
#include "square_chi_square.h"
#include "transport/bsdfs/diffuse_bsdf.h"
#include "transport/guiding/directional_quadtree.h"
#include "transport/guiding/guided_bsdf.h"
#include "transport/guiding/guiding_field.h"
#include "transport/guiding/path_guiding_record.h"
#include "transport/sampling/equal_area_square.h"
#include "test_support.h"

using namespace rimu;

namespace {

using rimu::test::kPi;

// Uniform directions over the sphere weighted by `radiance`: the samples a path tracer with uniform sampling would
// record (weight = radiance / (1/4π)).
std::vector<DirectionalSample> training_samples(const std::function<double(Vec3)>& radiance, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<DirectionalSample> samples;
  for (int i = 0; i < count; ++i) {
    const Vec2 p{test::uniform01(rng), test::uniform01(rng)};
    samples.push_back({p, float(radiance(equal_area_square_to_sphere(p)) * 4.0 * kPi)});
  }
  return samples;
}

struct TrainedField {
  std::string name;
  std::function<double(Vec3)> radiance;
};

// A sun (5° disc, 2000× brighter) over a sky, a hemisphere of cosine-weighted light, two small lamps and a sky
// band: narrow peaks, a half-empty sphere, and smooth variation.
std::vector<TrainedField> trained_fields() {
  const Vec3 sun = normalize(Vec3{0.3f, 0.4f, 0.8f});
  return {
      {"sun and sky", [sun](Vec3 d) { return 1.0 + (dot(d, sun) > std::cos(5.0 * kPi / 180.0) ? 2000.0 : 0.0); }},
      {"upper hemisphere, cosine", [](Vec3 d) { return std::fmax(0.0, double(d.z)); }},
      {"two lamps",
       [](Vec3 d) {
         return (d.x > 0.97f ? 50.0 : 0.0) + (dot(d, normalize(Vec3{-1.0f, -1.0f, 0.2f})) > 0.99f ? 200.0 : 0.0);
       }},
      {"sky band", [](Vec3 d) { return std::exp(-8.0 * double(d.z * d.z)) + 0.01; }},
  };
}

// Σ over a uniform grid of `n`² cell centres of pdf_square × cell area: the integral over the square, exact when
// every leaf is a union of grid cells (trees no deeper than log2 n).
double square_integral(const DirectionalQuadtree& tree, int n) {
  double total = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      total += tree.pdf_square({(float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)});
  return total / (double(n) * double(n));
}

}  // namespace

TEST_CASE("A learned directional distribution's pdf integrates to one and its samples follow it (chi-square)") {
  QuadtreeSettings settings;
  settings.max_depth = 8;  // leaves of 2⁻⁸: a 256² grid of cell centres integrates the pdf exactly
  const auto fields = trained_fields();
  for (size_t f = 0; f < fields.size(); ++f) {
    CAPTURE(fields[f].name);
    std::vector<DirectionalSample> samples = training_samples(fields[f].radiance, 200000, uint32_t(10 + f));
    const DirectionalQuadtree tree = DirectionalQuadtree::build(samples, settings);
    REQUIRE(!tree.empty());
    CHECK(tree.node_count() > 4);  // it learned something
    CHECK(square_integral(tree, 256) == doctest::Approx(1.0).epsilon(1e-5));

    // Solid angle: the equal-area map makes the direction pdf the square's over 4π; a Monte Carlo integral of
    // pdf_direction over uniform directions must give 1 within its standard error.
    std::mt19937 rng(uint32_t(100 + f));
    const int n_mc = 200000;
    std::vector<double> values;
    for (int i = 0; i < n_mc; ++i)
      values.push_back(double(tree.pdf_direction(test::uniform_sphere_direction(rng))) * 4.0 * kPi);
    const auto [mean, standard_error] = test::mean_and_standard_error(values);
    CHECK(std::fabs(mean - 1.0) <= 4.5 * standard_error);

    // Chi-square: 64² cells of the square; the expected count of a cell is its pdf integral (sub-grid of 4², exact).
    const int cells = 64, sub = 4, draws = 400000;
    std::vector<double> observed(size_t(cells * cells), 0.0);
    const std::vector<double> expected =
        test::square_expected_counts([&](Vec2 p) { return tree.pdf_square(p); }, cells, sub, draws);
    int round_trip_mismatches = 0;
    for (int i = 0; i < draws; ++i) {
      const Vec2 u{test::uniform01(rng), test::uniform01(rng)};
      const Vec2 p = tree.sample_square(u);
      REQUIRE(tree.pdf_square(p) > 0.0f);
      // The direction round trip: what sample_direction() gives is where pdf_direction() looks, except for points
      // within float rounding of a leaf's edge, which the square → sphere → square round trip may move across it.
      if (std::fabs(tree.pdf_direction(tree.sample_direction(u)) * 4.0 * kPi / tree.pdf_square(p) - 1.0) > 1e-4)
        ++round_trip_mismatches;
      observed[test::square_cell(p, cells)] += 1.0;
    }
    CHECK(round_trip_mismatches <= draws / 10000);
    const auto chi = test::pearson_chi_square(observed, expected, test::Pooling::sparse_into_one);
    CHECK(chi.p_value > test::sidak_threshold(test::kChiSquareAlpha, int(fields.size())));
  }
}

TEST_CASE("A learned distribution of the default depth concentrates on a sun and still integrates to one") {
  const auto fields = trained_fields();
  std::vector<DirectionalSample> samples = training_samples(fields[0].radiance, 200000, 7);
  const DirectionalQuadtree tree = DirectionalQuadtree::build(samples, QuadtreeSettings{});
  // Leaves may be deeper than any grid: integrate leaf by leaf through a grid fine enough near the sun (2¹²).
  CHECK(square_integral(tree, 4096) == doctest::Approx(1.0).epsilon(2e-3));
  // The 5° sun (0.19 % of the sphere) brings 2000·0.0019/(2000·0.0019 + 1) ≈ 79 % of the light: the guide's
  // density there is hundreds of times the uniform 1/4π.
  const Vec3 sun = normalize(Vec3{0.3f, 0.4f, 0.8f});
  CHECK(tree.pdf_direction(sun) * 4.0 * kPi > 100.0);
  CHECK(tree.node_count() <= size_t(QuadtreeSettings{}.max_nodes));
}

TEST_CASE("No energy, no distribution: a field without light guides nowhere") {
  std::vector<DirectionalSample> samples(100, DirectionalSample{{0.5f, 0.5f}, 0.0f});
  CHECK(DirectionalQuadtree::build(samples, QuadtreeSettings{}).empty());
  std::vector<GuidingSample> field_samples(100, GuidingSample{{0, 0, 0}, {{0.5f, 0.5f}, 0.0f}});
  const GuidingField field = GuidingField::build(field_samples, 1, GuidingFieldSettings{});
  for (int facing = 0; facing < kFacings; ++facing) CHECK(!field.distribution_at({0, 0, 0}, facing));
}

TEST_CASE("The spatial tree keeps two places' light apart, within its leaf bound") {
  // Points near x = −1 see light from +z, points near x = +1 from −z.
  std::mt19937 rng(3);
  std::vector<GuidingSample> samples;
  for (int i = 0; i < 40000; ++i) {
    const bool right = i % 2 == 1;
    const Vec3 position{(right ? 1.0f : -1.0f) + 0.1f * test::uniform01(rng), test::uniform01(rng), 0.0f};
    const Vec2 p{test::uniform01(rng), test::uniform01(rng)};
    const Vec3 d = equal_area_square_to_sphere(p);
    samples.push_back({position, {p, (right ? d.z < -0.9f : d.z > 0.9f) ? 1.0f : 0.0f}});
  }
  GuidingFieldSettings settings;
  settings.split_samples = 1000.0;
  settings.max_leaves = 16;
  const GuidingField field = GuidingField::build(samples, 1, settings);
  CHECK(field.leaf_count() <= 16);
  CHECK(field.leaf_count() >= 2);
  const DirectionalQuadtree* left = field.distribution_at({-0.95f, 0.5f, 0.0f}, 0).tree;
  const DirectionalQuadtree* right = field.distribution_at({1.05f, 0.5f, 0.0f}, 0).tree;
  CHECK(!field.distribution_at({-0.95f, 0.5f, 0.0f}, 1));  // nothing learned facing −x
  REQUIRE(left != nullptr);
  REQUIRE(right != nullptr);
  // The light fills a cap of 2π·0.1 sr: a density of ~1.6/sr there (uniform would be 1/4π ≈ 0.08).
  CHECK(left->pdf_direction({0, 0, 1}) > 1.0f);
  CHECK(left->pdf_direction({0, 0, -1}) == 0.0f);
  CHECK(right->pdf_direction({0, 0, -1}) > 1.0f);
  CHECK(right->pdf_direction({0, 0, 1}) == 0.0f);
  CHECK(field.memory_bytes() > 0);
}

TEST_CASE("The guide/BSDF mixture's density integrates to one and samples with the density it reports") {
  std::vector<DirectionalSample> samples = training_samples(trained_fields()[0].radiance, 100000, 5);
  const DirectionalQuadtree tree = DirectionalQuadtree::build(samples, QuadtreeSettings{});
  const Bsdf bsdf{DiffuseBsdf(SampledSpectrum(0.5f))};
  const Frame frame = Frame::from_normal(normalize(Vec3{0.2f, -0.1f, 1.0f}));
  const VertexGuide guide(LeafGuide{&tree, nullptr}, Vec3{0, 0, 0});
  const GuidedBsdf guided(bsdf, frame, &guide, 0.5f);
  REQUIRE(guided.guided());
  const Vec3 wo = normalize(Vec3{0.3f, 0.1f, 0.9f});
  // ∫ p dω by importance sampling from the mixture itself: E[p_reported(wi)/p_true(wi)] = 1 only if they agree;
  // and ∫ p dω over uniform directions = 1.
  std::mt19937 rng(9);
  std::vector<double> uniform_values;
  for (int i = 0; i < 200000; ++i)
    uniform_values.push_back(double(guided.pdf(wo, test::uniform_sphere_direction(rng))[0]) * 4.0 * kPi);
  const auto [mean, standard_error] = test::mean_and_standard_error(uniform_values);
  CHECK(std::fabs(mean - 1.0) <= 4.5 * standard_error);
  for (int i = 0; i < 2000; ++i) {
    const auto s = guided.sample(wo, test::uniform01(rng), {test::uniform01(rng), test::uniform01(rng)});
    if (!s) continue;
    CHECK(s->pdf[0] == doctest::Approx(guided.pdf(wo, s->wi)[0]).epsilon(1e-3));
  }
}

TEST_CASE("A few lucky samples among empty ones: the tree does not split down onto them") {
  // 10⁵ directions that found nothing and three that found a lamp (a door ajar seen from a dark room): the energy
  // rests on three effective samples, too few to say where the lamp is from the rest of the spatial leaf.
  std::mt19937 rng(21);
  std::vector<DirectionalSample> samples;
  for (int i = 0; i < 100000; ++i) samples.push_back({{test::uniform01(rng), test::uniform01(rng)}, 0.0f});
  for (float dx : {0.0f, 0.001f, 0.002f}) samples.push_back({{0.3f + dx, 0.6f}, 1000.0f});
  std::vector<DirectionalSample> lucky = samples;
  const DirectionalQuadtree sparse = DirectionalQuadtree::build(lucky, QuadtreeSettings{});
  REQUIRE(!sparse.empty());
  CHECK(sparse.effective_samples() == doctest::Approx(3.0));
  CHECK(sparse.node_count() == 1);  // one level: the lamp's quadrant gets all the density, no narrower spike
  CHECK(sparse.pdf_square({0.3f, 0.6f}) <= 4.0f);

  // The same light found by 200 paths (a cap of 0.02 around the same point): now it is learned, deep and narrow.
  for (int i = 0; i < 200; ++i)
    samples.push_back({{0.3f + 0.02f * test::uniform01(rng), 0.6f + 0.02f * test::uniform01(rng)}, 1000.0f});
  const DirectionalQuadtree supported = DirectionalQuadtree::build(samples, QuadtreeSettings{});
  CHECK(supported.effective_samples() > 150.0f);
  CHECK(supported.node_count() > 4);
  CHECK(supported.pdf_square({0.31f, 0.61f}) > 100.0f);
  CHECK(square_integral(supported, 4096) == doctest::Approx(1.0).epsilon(2e-3));
}

TEST_CASE("A spatial leaf whose light rests on too few samples does not guide") {
  GuidingFieldSettings settings;  // min_effective_samples = 32
  std::mt19937 rng(5);
  auto field_with_lucky = [&](int lucky) {
    std::vector<GuidingSample> samples;
    for (int i = 0; i < 5000; ++i) {
      const Vec2 p{test::uniform01(rng), test::uniform01(rng)};
      samples.push_back({{test::uniform01(rng), test::uniform01(rng), 0.0f}, {p, i < lucky ? 1.0f : 0.0f}, 4});
    }
    return GuidingField::build(samples, 1, settings);
  };
  CHECK(!field_with_lucky(5).distribution_at({0.5f, 0.5f, 0.0f}, 4));
  const GuidingField learned = field_with_lucky(500);
  const DirectionalQuadtree* leaf = learned.distribution_at({0.5f, 0.5f, 0.0f}, 4).tree;
  REQUIRE(leaf != nullptr);
  CHECK(leaf->effective_samples() >= settings.min_effective_samples);
}

TEST_CASE("A path's record weighs the light it brought by the cosine over the density it was sampled with") {
  PathGuidingRecord record(Float4(0.25f));  // lane weights: the luminance of (1, 1, 1, 1) is 1
  record.add_vertex({1, 2, 3}, 2, {0, 1, 0}, 0.5f, 0.25f, SampledSpectrum(2.0f));
  record.add_radiance(SampledSpectrum(4.0f));  // arrives through a throughput of 2: incident radiance 2
  std::vector<GuidingSample> out;
  record.flush(out);
  REQUIRE(out.size() == 1);
  CHECK(out[0].direction.weight == doctest::Approx(2.0 * 0.25 / 0.5));
  CHECK(out[0].facing == 2);
}

TEST_CASE("An emitter a vertex's own ray hit is indirect light for the vertices before it, not direct for it") {
  // Two vertices; the second one's ray hits a light (MIS-weighted against next-event estimation: skip_last). The
  // first vertex learns it (it arrived there by a bounce), the second does not (NEE samples it).
  PathGuidingRecord record(Float4(0.25f));
  REQUIRE(record.add_vertex({0, 0, 0}, 2, {0, 1, 0}, 1.0f, 1.0f, SampledSpectrum(1.0f)));
  REQUIRE(record.add_vertex({0, 1, 0}, 3, {0, -1, 0}, 1.0f, 1.0f, SampledSpectrum(0.5f)));
  record.add_radiance(SampledSpectrum(3.0f), true);
  record.add_radiance(SampledSpectrum(1.0f));  // later light (say, NEE at a third vertex) reaches both
  std::vector<GuidingSample> out;
  record.flush(out);
  REQUIRE(out.size() == 2);
  CHECK(out[0].direction.weight == doctest::Approx(4.0));  // (3 + 1) / throughput 1
  CHECK(out[1].direction.weight == doctest::Approx(2.0));  // 1 / throughput 0.5: the hit light is left out
}

TEST_CASE("A full record takes no more vertices and says so") {
  PathGuidingRecord record(Float4(0.25f));
  for (int i = 0; i < PathGuidingRecord::kMaxVertices; ++i)
    REQUIRE(record.add_vertex({0, 0, 0}, 2, {0, 1, 0}, 1.0f, 1.0f, SampledSpectrum(1.0f)));
  CHECK_FALSE(record.add_vertex({0, 0, 0}, 2, {0, 1, 0}, 1.0f, 1.0f, SampledSpectrum(1.0f)));
}
