// Loop subdivision (see loop_subdivision.h for the rules and their sources).
#include "render/scene/loop_subdivision.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace rimu {

namespace {

using P3 = std::array<double, 3>;

P3 operator+(const P3& a, const P3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
P3 operator-(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 operator*(double s, const P3& a) { return {s * a[0], s * a[1], s * a[2]}; }
P3 cross(const P3& a, const P3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

constexpr uint32_t kNone = UINT32_MAX;

struct Edge {
  uint32_t a, b;          ///< endpoints, in the winding of the first triangle that has the edge
  uint32_t c, d = kNone;  ///< the vertex opposite the edge in the first and second triangle (kNone: boundary)
};

// The edges of a level and, per vertex, the sums its rules need.
struct Topology {
  std::vector<Edge> edges;
  std::vector<uint32_t> face_edges;  ///< per triangle corner k: the edge from corner k to corner k+1
  std::vector<P3> neighbour_sum, boundary_sum;
  std::vector<uint32_t> valence, boundary_valence;
};

Topology topology_of(const std::vector<P3>& p, const std::vector<uint32_t>& indices) {
  Topology t;
  const size_t faces = indices.size() / 3;
  std::unordered_map<uint64_t, uint32_t> edge_of;
  edge_of.reserve(indices.size());
  t.face_edges.resize(indices.size());
  for (size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = indices[3 * f + k], b = indices[3 * f + (k + 1) % 3], c = indices[3 * f + (k + 2) % 3];
      if (a == b || b == c || a == c) throw std::invalid_argument("triangle " + std::to_string(f) + " repeats a vertex");
      const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      const auto [it, added] = edge_of.emplace(key, uint32_t(t.edges.size()));
      if (added) {
        t.edges.push_back({a, b, c});
      } else {
        Edge& e = t.edges[it->second];
        if (e.d != kNone)
          throw std::invalid_argument("the edge " + std::to_string(a) + "-" + std::to_string(b) + " belongs to more than two triangles");
        if (e.a == a)
          throw std::invalid_argument("triangle " + std::to_string(f) + " is wound against its neighbour across the edge " +
                                      std::to_string(a) + "-" + std::to_string(b) + " (inconsistent orientation)");
        e.d = c;
      }
      t.face_edges[3 * f + k] = it->second;
    }
  t.neighbour_sum.assign(p.size(), P3{0, 0, 0});
  t.boundary_sum.assign(p.size(), P3{0, 0, 0});
  t.valence.assign(p.size(), 0);
  t.boundary_valence.assign(p.size(), 0);
  for (const Edge& e : t.edges) {
    t.neighbour_sum[e.a] = t.neighbour_sum[e.a] + p[e.b];
    t.neighbour_sum[e.b] = t.neighbour_sum[e.b] + p[e.a];
    ++t.valence[e.a];
    ++t.valence[e.b];
    if (e.d == kNone) {
      t.boundary_sum[e.a] = t.boundary_sum[e.a] + p[e.b];
      t.boundary_sum[e.b] = t.boundary_sum[e.b] + p[e.a];
      ++t.boundary_valence[e.a];
      ++t.boundary_valence[e.b];
    }
  }
  for (size_t v = 0; v < p.size(); ++v)
    if (t.boundary_valence[v] != 0 && t.boundary_valence[v] != 2)
      throw std::invalid_argument("vertex " + std::to_string(v) + " joins separate fans of triangles (non-manifold)");
  return t;
}

// Warren's β (as pbrt-v4): 3/16 for valence 3, else 3/(8n).
double beta(uint32_t n) { return n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n); }

void subdivide_once(std::vector<P3>& p, std::vector<uint32_t>& indices) {
  const Topology t = topology_of(p, indices);
  const size_t vertex_count = p.size();
  std::vector<P3> next(vertex_count + t.edges.size());
  for (size_t v = 0; v < vertex_count; ++v) {
    if (t.valence[v] == 0) {
      next[v] = p[v];  // a point no triangle uses
    } else if (t.boundary_valence[v] == 2) {
      next[v] = 0.75 * p[v] + 0.125 * t.boundary_sum[v];
    } else {
      const double b = beta(t.valence[v]);
      next[v] = (1.0 - t.valence[v] * b) * p[v] + b * t.neighbour_sum[v];
    }
  }
  for (size_t e = 0; e < t.edges.size(); ++e) {
    const Edge& edge = t.edges[e];
    next[vertex_count + e] = edge.d == kNone ? 0.5 * (p[edge.a] + p[edge.b])
                                             : 0.375 * (p[edge.a] + p[edge.b]) + 0.125 * (p[edge.c] + p[edge.d]);
  }
  std::vector<uint32_t> split;
  split.reserve(indices.size() * 4);
  for (size_t f = 0; f < indices.size() / 3; ++f) {
    const uint32_t v0 = indices[3 * f], v1 = indices[3 * f + 1], v2 = indices[3 * f + 2];
    const uint32_t m01 = uint32_t(vertex_count + t.face_edges[3 * f]), m12 = uint32_t(vertex_count + t.face_edges[3 * f + 1]),
                   m20 = uint32_t(vertex_count + t.face_edges[3 * f + 2]);
    // Three corner triangles and the middle one, each wound as the parent.
    for (uint32_t i : {v0, m01, m20, m01, v1, m12, m20, m12, v2, m01, m12, m20}) split.push_back(i);
  }
  p = std::move(next);
  indices = std::move(split);
}

// The neighbours of each vertex in order around it: q₀, q₁, … such that (v, qᵢ, qᵢ₊₁) are triangles of the mesh in
// their winding; a boundary vertex's ring starts and ends at its boundary neighbours.
std::vector<std::vector<uint32_t>> rings_of(size_t vertex_count, const std::vector<uint32_t>& indices, const Topology& t) {
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> fans(vertex_count);  // per vertex: (x, y) of its triangles (v, x, y)
  for (size_t f = 0; f < indices.size() / 3; ++f)
    for (int k = 0; k < 3; ++k)
      fans[indices[3 * f + k]].push_back({indices[3 * f + (k + 1) % 3], indices[3 * f + (k + 2) % 3]});
  std::vector<std::vector<uint32_t>> rings(vertex_count);
  for (size_t v = 0; v < vertex_count; ++v) {
    const auto& fan = fans[v];
    if (fan.empty()) continue;
    uint32_t start = fan[0].first;
    if (t.boundary_valence[v] == 2)  // the fan's first x is the one that is no triangle's y
      for (const auto& [x, unused] : fan) {
        bool is_y = false;
        for (const auto& [unused2, y] : fan) is_y = is_y || y == x;
        if (!is_y) start = x;
      }
    std::vector<uint32_t>& ring = rings[v];
    ring.push_back(start);
    for (size_t steps = 0; steps < fan.size(); ++steps) {
      uint32_t next = kNone;
      for (const auto& [x, y] : fan)
        if (x == ring.back()) next = y;
      if (next == kNone) break;
      if (next == start) break;  // around an interior vertex
      ring.push_back(next);
    }
    const size_t walked = t.boundary_valence[v] == 2 ? ring.size() - 1 : ring.size();
    if (walked != fan.size()) throw std::invalid_argument("vertex " + std::to_string(v) + " joins separate fans of triangles (non-manifold)");
  }
  return rings;
}

P3 limit_normal(const P3& v, const std::vector<uint32_t>& ring, bool boundary, const std::vector<P3>& p) {
  const size_t n = ring.size();
  const auto q = [&](size_t i) { return p[ring[i]]; };
  P3 s{0, 0, 0}, t{0, 0, 0};
  if (!boundary) {
    for (size_t i = 0; i < n; ++i) {
      const double angle = 2.0 * M_PI * double(i) / double(n);
      s = s + std::cos(angle) * q(i);
      t = t + std::sin(angle) * q(i);
    }
  } else {
    s = q(n - 1) - q(0);  // along the boundary curve
    if (n == 2) {
      t = q(0) + q(1) - 2.0 * v;
    } else if (n == 3) {
      t = q(1) - v;
    } else if (n == 4) {
      t = -1.0 * q(0) + 2.0 * q(1) + 2.0 * q(2) - 1.0 * q(3) - 2.0 * v;
    } else {
      const double theta = M_PI / double(n - 1);
      t = std::sin(theta) * (q(0) + q(n - 1));
      for (size_t i = 1; i + 1 < n; ++i) t = t + (2.0 * std::cos(theta) - 2.0) * std::sin(double(i) * theta) * q(i);
    }
  }
  // The ring's triangles say which side is the front.
  P3 facing{0, 0, 0};
  for (size_t i = 0; i + (boundary ? 1 : 0) < n; ++i) facing = facing + cross(q(i) - v, q((i + 1) % n) - v);
  P3 normal = cross(s, t);
  if (dot(normal, facing) < 0) normal = -1.0 * normal;
  double length = std::sqrt(dot(normal, normal));
  if (!(length > 0) || !std::isfinite(length)) {
    normal = facing;
    length = std::sqrt(dot(normal, normal));
  }
  return length > 0 ? (1.0 / length) * normal : P3{0, 0, 1};
}

}  // namespace

LoopMesh loop_subdivide(const std::vector<std::array<double, 3>>& positions, const std::vector<uint32_t>& indices, int levels,
                        size_t max_triangles) {
  if (levels < 0 || levels > 10) throw std::invalid_argument("levels must be 0-10, not " + std::to_string(levels));
  if (indices.size() % 3 != 0) throw std::invalid_argument("the index count is not a multiple of 3");
  for (uint32_t i : indices)
    if (i >= positions.size()) throw std::invalid_argument("index " + std::to_string(i) + " is out of range");
  const double triangles = double(indices.size() / 3) * std::pow(4.0, levels);
  if (triangles > double(max_triangles))
    throw std::length_error(std::to_string(levels) + " levels would make " + std::to_string(int64_t(triangles)) +
                            " triangles (at most " + std::to_string(max_triangles) + ")");
  std::vector<P3> p = positions;
  LoopMesh mesh;
  mesh.indices = indices;
  for (int level = 0; level < levels; ++level) subdivide_once(p, mesh.indices);
  const Topology t = topology_of(p, mesh.indices);
  const std::vector<std::vector<uint32_t>> rings = rings_of(p.size(), mesh.indices, t);
  mesh.positions.resize(p.size());
  mesh.normals.resize(p.size());
  for (size_t v = 0; v < p.size(); ++v) {
    const bool boundary = t.boundary_valence[v] == 2;
    if (t.valence[v] == 0) {
      mesh.positions[v] = p[v];
      mesh.normals[v] = {0, 0, 1};
      continue;
    }
    if (boundary) {
      mesh.positions[v] = (1.0 / 6.0) * (4.0 * p[v] + t.boundary_sum[v]);
    } else {
      const uint32_t n = t.valence[v];
      const double gamma = 1.0 / (n + 3.0 / (8.0 * beta(n)));
      mesh.positions[v] = (1.0 - n * gamma) * p[v] + gamma * t.neighbour_sum[v];
    }
    mesh.normals[v] = limit_normal(p[v], rings[v], boundary, p);
  }
  return mesh;
}

}  // namespace rimu
