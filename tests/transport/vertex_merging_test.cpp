// Vertex merging's pass of light vertices (transport/integrators/vertex_merging.h): the grid must find exactly the
// vertices of a bucket within the radius (checked against a search of them all), the merge factor must count the
// bucket's subpaths, and the radius must shrink as i^{(α−1)/2}.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "transport/integrators/vertex_merging.h"

using namespace rimu;

TEST_CASE("vertex merging: the grid finds exactly the light vertices of a bucket within the radius") {
  std::mt19937 rng(20261207);
  for (const float radius : {0.003f, 0.05f, 0.4f}) {
    VertexMergingPass pass;
    const int buckets = 3, subpaths = 700;
    std::vector<SampledWavelengths> sets(size_t(buckets), SampledWavelengths::sample_visible(0.5f));
    pass.start(radius, sets, subpaths);
    // Clustered and spread points, negative coordinates included (cells either side of 0), in several batches.
    std::normal_distribution<float> cluster(0.0f, 2.0f * radius);
    std::uniform_real_distribution<float> spread(-3.0f, 3.0f);
    std::vector<Vec3> positions;
    std::vector<int> bucket_of;
    std::vector<MergeVertexBatch>& batches = pass.batches(4);
    for (int b = 0; b < 4; ++b) {
      MergeVertexBatch& batch = batches[size_t(b)];
      for (int j = 0; j < subpaths / 4; ++j) {
        batch.subpaths.push_back(MergeSubpath{});
        batch.stored_start.push_back(uint32_t(batch.stored.size()));
        batch.stored.push_back(StoredLightVertex{});  // one stored vertex per subpath, its light the subpath's index
        batch.stored.back().light = b * (subpaths / 4) + j;
        for (int v = 0; v < 3; ++v) {
          MergeVertex m;
          m.position = j % 2 ? Vec3{cluster(rng) - 1.0f, cluster(rng), cluster(rng) + 0.5f}
                             : Vec3{spread(rng), spread(rng), spread(rng)};
          m.subpath = uint32_t(batch.subpaths.size() - 1);
          m.bucket = uint16_t((b * subpaths / 4 + j) % buckets);
          batch.vertices.push_back(m);
          positions.push_back(m.position);
          bucket_of.push_back(m.bucket);
        }
      }
    }
    pass.build();
    REQUIRE(pass.vertex_count() == positions.size());
    // Each subpath is found whole by its index, across the batches.
    for (int j = 0; j < 4 * (subpaths / 4); j += 37) {
      int length = 0;
      const StoredLightVertex* stored = pass.light_subpath(j, length);
      REQUIRE(length == 1);
      CHECK(stored->light == j);
    }
    int found_total = 0;
    for (int q = 0; q < 300; ++q) {
      const Vec3 p = q % 2 ? Vec3{cluster(rng) - 1.0f, cluster(rng), cluster(rng) + 0.5f}
                           : Vec3{spread(rng), spread(rng), spread(rng)};
      const int bucket = q % buckets;
      std::multiset<std::tuple<float, float, float>> expected, found;
      for (size_t i = 0; i < positions.size(); ++i)
        if (bucket_of[i] == bucket && length_squared(positions[i] - p) <= radius * radius)
          expected.insert({positions[i].x, positions[i].y, positions[i].z});
      pass.for_each_within(p, bucket, [&](const MergeVertex& m, const MergeSubpath&, const JoinedVertex*) {
        found.insert({m.position.x, m.position.y, m.position.z});
      });
      CHECK(found == expected);
      found_total += int(found.size());
    }
    CHECK(found_total > 50);  // the queries did meet vertices
  }
}

TEST_CASE("vertex merging: the merge factor counts the bucket's subpaths, and the radius shrinks by the passes") {
  VertexMergingPass pass;
  std::vector<SampledWavelengths> sets(4, SampledWavelengths::sample_visible(0.25f));
  pass.start(0.01f, sets, 10);  // subpaths 0..9 in buckets 0,1,2,3,0,1,2,3,0,1: 3, 3, 2, 2
  const float disc = std::numbers::pi_v<float> * 0.01f * 0.01f;
  CHECK(pass.merge_factor(0) == doctest::Approx(3.0f * disc));
  CHECK(pass.merge_factor(2) == doctest::Approx(2.0f * disc));
  VertexMergingSettings settings;
  settings.radius_m = 0.02f;
  CHECK(settings.radius(0, 100.0f) == doctest::Approx(0.02f));
  // α = 0.75: r_i = r₁ i^{−1/8}; the 256th pass has half the first radius.
  CHECK(settings.radius(255, 100.0f) == doctest::Approx(0.01f));
  settings.radius_m = 0.0f;  // default: 0.002 × the scene's diagonal
  CHECK(settings.radius(0, 10.0f) == doctest::Approx(0.02f));
  // Every pixel lands in a bucket, and the buckets of a pass are used alike.
  std::vector<int> used(4, 0);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ++used[size_t(pass.pixel_bucket(x, y, 7))];
  for (int count : used) CHECK(std::abs(count - 1024) < 150);
}
