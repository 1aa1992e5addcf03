// Loop subdivision (src/render/scene/loop_subdivision.h), for pbrt-v4's "loopsubdiv": closed meshes stay closed,
// limit positions are the published closed forms (a regular tetrahedron's vertex goes to 1/5 of its radius; a
// regular grid sampling z = x² has its limit on z = x² + h²/3 with normal ∝ (−2x, 0, 1)), the limit masks are
// the rules' eigenvectors (the same limit point from any level), normals face outwards, bad meshes are refused.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <stdexcept>

#include "render/scene/loop_subdivision.h"

using namespace rimu;
using P3 = std::array<double, 3>;

namespace {

// A regular tetrahedron centred on the origin, circumradius √3, faces wound outwards.
const std::vector<P3> kTetra = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
const std::vector<uint32_t> kTetraFaces = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};

double distance(const P3& a, const P3& b) { return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])); }

// Every undirected edge → how often each direction is used.
std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> edge_uses(const std::vector<uint32_t>& indices) {
  std::map<std::pair<uint32_t, uint32_t>, std::pair<int, int>> uses;
  for (size_t f = 0; f < indices.size(); f += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = indices[f + k], b = indices[f + (k + 1) % 3];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      (a < b ? u.first : u.second) += 1;
    }
  return uses;
}

P3 face_normal(const LoopMesh& m, size_t f) {
  const P3 &a = m.positions[m.indices[f]], &b = m.positions[m.indices[f + 1]], &c = m.positions[m.indices[f + 2]];
  const P3 u = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

}  // namespace

TEST_CASE("Loop subdivision: a tetrahedron stays closed and consistently wound at every level") {
  for (int levels = 0; levels <= 4; ++levels) {
    CAPTURE(levels);
    const LoopMesh m = loop_subdivide(kTetra, kTetraFaces, levels);
    const size_t faces = m.indices.size() / 3;
    CHECK(faces == size_t(4) << (2 * levels));
    const auto uses = edge_uses(m.indices);
    bool watertight = true;
    for (const auto& [edge, u] : uses) watertight = watertight && u.first == 1 && u.second == 1;  // once each way
    CHECK(watertight);
    // Euler characteristic of a sphere: V − E + F = 2, with no unused vertex.
    CHECK(int64_t(m.positions.size()) - int64_t(uses.size()) + int64_t(faces) == 2);
  }
}

TEST_CASE("Loop subdivision: the limit of a regular tetrahedron's vertex is 1/5 of the way out, from any level") {
  // Valence 3: β = 3/16, γ = 1/(3 + 3/(8β)) = 1/5, so the limit is (2/5) v + (1/5) Σ others = (1/5) v when the
  // vertices sum to 0.
  for (int levels : {0, 1, 3, 5}) {
    const LoopMesh m = loop_subdivide(kTetra, kTetraFaces, levels);
    for (size_t v = 0; v < 4; ++v)
      for (int i = 0; i < 3; ++i) CHECK(m.positions[v][i] == doctest::Approx(kTetra[v][i] / 5.0).epsilon(1e-12));
  }
  // The same for every vertex of level 1 (edge points, valence 6): the limit masks are left eigenvectors of the
  // rules, so a vertex's limit does not depend on the level at which it is taken. (A wrong mask, e.g. pbrt-v4's
  // boundary 1/5-3/5-1/5, fails this; tested on a boundary below.)
  const LoopMesh one = loop_subdivide(kTetra, kTetraFaces, 1), four = loop_subdivide(kTetra, kTetraFaces, 4);
  double worst = 0;
  for (size_t v = 0; v < one.positions.size(); ++v) worst = std::max(worst, distance(one.positions[v], four.positions[v]));
  CHECK(worst < 1e-12);
  // Converging: the level-4 surface is round — every vertex lies within a narrow shell (control mesh: radii from
  // 0.58 to 1.73).
  double r_min = 1e9, r_max = 0;
  for (const P3& p : four.positions) {
    const double r = distance(p, {0, 0, 0});
    r_min = std::min(r_min, r);
    r_max = std::max(r_max, r);
  }
  CHECK(r_max / r_min < 1.6);
}

TEST_CASE("Loop subdivision: normals face outwards and follow the surface") {
  const LoopMesh m = loop_subdivide(kTetra, kTetraFaces, 3);
  std::vector<P3> face_sum(m.positions.size(), P3{0, 0, 0});
  for (size_t f = 0; f < m.indices.size(); f += 3) {
    const P3 n = face_normal(m, f);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i) face_sum[m.indices[f + k]][i] += n[i];
  }
  double worst_cos = 1;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const P3& n = m.normals[v];
    CHECK(std::abs(distance(n, {0, 0, 0}) - 1) < 1e-12);
    const double outward = n[0] * m.positions[v][0] + n[1] * m.positions[v][1] + n[2] * m.positions[v][2];
    CHECK(outward > 0);
    const double len = distance(face_sum[v], {0, 0, 0});
    worst_cos = std::min(worst_cos, (n[0] * face_sum[v][0] + n[1] * face_sum[v][1] + n[2] * face_sum[v][2]) / len);
  }
  CHECK(worst_cos > std::cos(15.0 * M_PI / 180.0));  // the limit normal against the neighbouring facets' mean
}

TEST_CASE("Loop subdivision: a regular grid sampling z = x² has its limit on z = x² + h²/3, normal ∝ (−2x, 0, 1)") {
  // Interior vertices of valence 6 with ring offsets (±1, 0), (0, ±1), ±(1, 1) (times h): the limit mask
  // v/2 + Σ q/12 adds Σ dx² h²/12 = 4h²/12 to x². The regular tangent masks give the slope 2x exactly.
  const int n = 9;
  const double h = 0.125;
  std::vector<P3> p;
  std::vector<uint32_t> faces;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) p.push_back({i * h - 0.5, j * h - 0.5, (i * h - 0.5) * (i * h - 0.5)});
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const uint32_t a = uint32_t(j * n + i), b = a + 1, c = a + uint32_t(n) + 1, d = a + uint32_t(n);
      for (uint32_t k : {a, b, c, a, c, d}) faces.push_back(k);
    }
  for (int levels : {0, 2}) {
    const LoopMesh m = loop_subdivide(p, faces, levels);
    for (int j = 2; j <= n - 3; ++j)
      for (int i = 2; i <= n - 3; ++i) {
        const size_t v = size_t(j * n + i);
        const double x = p[v][0];
        CHECK(m.positions[v][0] == doctest::Approx(x).epsilon(1e-12));
        CHECK(m.positions[v][1] == doctest::Approx(p[v][1]).epsilon(1e-12));
        CHECK(m.positions[v][2] == doctest::Approx(x * x + h * h / 3).epsilon(1e-12));
        const double len = std::sqrt(4 * x * x + 1);
        CHECK(m.normals[v][0] == doctest::Approx(-2 * x / len).epsilon(1e-9));
        CHECK(std::abs(m.normals[v][1]) < 1e-9);
        CHECK(m.normals[v][2] == doctest::Approx(1 / len).epsilon(1e-9));
      }
  }
}

TEST_CASE("Loop subdivision: boundaries are cubic B-spline curves of the boundary polygon, limit (b0 + 4v + b1)/6") {
  // A fan of 5 triangles around a centre (an open, non-planar patch): its rim vertices are boundary vertices.
  std::vector<P3> p = {{0, 0, 0.5}};
  std::vector<uint32_t> faces;
  for (int k = 0; k < 6; ++k) p.push_back({std::cos(k * M_PI / 3.5), std::sin(k * M_PI / 3.5), 0.2 * k});
  for (uint32_t k = 1; k <= 5; ++k) faces.insert(faces.end(), {0, k, k + 1});
  const LoopMesh zero = loop_subdivide(p, faces, 0), one = loop_subdivide(p, faces, 1), four = loop_subdivide(p, faces, 4);
  for (size_t v = 2; v <= 5; ++v)  // rim vertices with two rim neighbours: the B-spline limit mask
    for (int i = 0; i < 3; ++i) CHECK(zero.positions[v][i] == doctest::Approx((p[v - 1][i] + 4 * p[v][i] + p[v + 1][i]) / 6).epsilon(1e-12));
  // The limit of every level-1 vertex, boundary ones included, is the same from level 4: the masks are exact.
  double worst = 0;
  for (size_t v = 0; v < one.positions.size(); ++v) worst = std::max(worst, distance(one.positions[v], four.positions[v]));
  CHECK(worst < 1e-12);
  // pbrt-v4's boundary limit weights (1/5, 3/5, 1/5) are not the rule's eigenvector: the same vertex's "limit"
  // would move between levels. Worked here at the rim vertex 3 from level 0 and from level 1 (its new position and
  // new boundary neighbours, the edge midpoints).
  const auto fifth = [](const P3& a, const P3& v, const P3& b) {
    return P3{(a[0] + 3 * v[0] + b[0]) / 5, (a[1] + 3 * v[1] + b[1]) / 5, (a[2] + 3 * v[2] + b[2]) / 5};
  };
  P3 v1, a1, b1;
  for (int i = 0; i < 3; ++i) {
    v1[i] = 0.75 * p[3][i] + 0.125 * (p[2][i] + p[4][i]);
    a1[i] = 0.5 * (p[2][i] + p[3][i]);
    b1[i] = 0.5 * (p[3][i] + p[4][i]);
  }
  CHECK(distance(fifth(p[2], p[3], p[4]), fifth(a1, v1, b1)) > 1e-3);
}

TEST_CASE("Loop subdivision: meshes Loop's rules do not apply to are refused") {
  // Three triangles on one edge.
  CHECK_THROWS_AS(loop_subdivide({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}}, {0, 1, 2, 1, 0, 3, 0, 1, 4}, 1),
                  std::invalid_argument);
  // Two triangles winding their shared edge the same way.
  CHECK_THROWS_AS(loop_subdivide({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}}, {0, 1, 2, 0, 1, 3}, 1), std::invalid_argument);
  // Two fans meeting at one vertex (a bow tie).
  CHECK_THROWS_AS(loop_subdivide({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {0, 1, 2, 0, 3, 4}, 1), std::invalid_argument);
  CHECK_THROWS_AS(loop_subdivide(kTetra, kTetraFaces, 11), std::invalid_argument);
  CHECK_THROWS_AS(loop_subdivide(kTetra, kTetraFaces, 5, 1000), std::length_error);
}
