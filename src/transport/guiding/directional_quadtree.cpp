#include "transport/guiding/directional_quadtree.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/sampling/equal_area_square.h"

namespace rimu {
namespace {

// The equal-area square covers the sphere's 4π sr with unit area: a density on the square is 4π times the density per sr.
constexpr float kSquareToSphereDensity = float(0.25 / std::numbers::pi);

constexpr float kBelowOne = 0x1.fffffep-1f;

int quadrant_of(Vec2 p) { return (p.x >= 0.5f ? 1 : 0) + (p.y >= 0.5f ? 2 : 0); }

// std::min, not std::fmin: without -ffast-math fmin is a libm call, and these run at every guided vertex.
float below_one(float x) { return std::min(x, kBelowOne); }

// The point's coordinates inside quadrant q, rescaled to [0, 1)².
Vec2 into_quadrant(Vec2 p, int q) {
  return {below_one(2.0f * p.x - float(q & 1)), below_one(2.0f * p.y - float(q >> 1))};
}

using DirectionalSampleIterator = std::vector<DirectionalSample>::iterator;

struct Builder {
  const QuadtreeSettings& settings;
  std::vector<DirectionalSample>& samples;
  double total = 0.0;

  // Builds the node for samples [first, last) (already in this node's own [0,1)² coordinates) into `nodes`.
  template <typename Nodes>
  void build(Nodes& nodes, size_t node, DirectionalSampleIterator first, DirectionalSampleIterator last, int depth) {
    // Split the range into the four quadrants. std::partition, not stable_partition: both are deterministic (the
    // result depends on the input order only), and the stable one allocates a buffer of the range at every node,
    // which was 30 % of a guided render's time (page faults included; perf, daylit room 160×90, 64 spp).
    DirectionalSampleIterator bounds[5];
    bounds[0] = first;
    bounds[4] = last;
    bounds[2] = std::partition(first, last, [](const DirectionalSample& s) { return s.square.y < 0.5f; });
    bounds[1] = std::partition(first, bounds[2], [](const DirectionalSample& s) { return s.square.x < 0.5f; });
    bounds[3] = std::partition(bounds[2], last, [](const DirectionalSample& s) { return s.square.x < 0.5f; });
    double energy[4], squares[4], node_energy = 0.0;
    for (int q = 0; q < 4; ++q) {
      energy[q] = squares[q] = 0.0;
      for (auto it = bounds[q]; it != bounds[q + 1]; ++it) {
        energy[q] += double(it->weight);
        squares[q] += double(it->weight) * double(it->weight);
      }
      node_energy += energy[q];
    }
    for (int q = 0; q < 4; ++q) nodes[node].density[q] = float(4.0 * energy[q] / node_energy);
    for (int q = 0; q < 4; ++q) {
      const bool split = depth < settings.max_depth && energy[q] > settings.subdivision_threshold * total &&
                         energy[q] * energy[q] >= double(settings.min_effective_samples_to_split) * squares[q] &&
                         nodes.size() < size_t(settings.max_nodes);
      if (!split) continue;
      for (auto it = bounds[q]; it != bounds[q + 1]; ++it) it->square = into_quadrant(it->square, q);
      const size_t child = nodes.size();
      nodes.emplace_back();
      nodes[node].child[q] = uint32_t(child);
      build(nodes, child, bounds[q], bounds[q + 1], depth + 1);
    }
  }
};

}  // namespace

DirectionalQuadtree DirectionalQuadtree::build(std::vector<DirectionalSample>& samples,
                                               const QuadtreeSettings& settings) {
  DirectionalQuadtree tree;
  Builder builder{settings, samples};
  double squares = 0.0;
  for (const DirectionalSample& s : samples) {
    builder.total += double(s.weight);
    squares += double(s.weight) * double(s.weight);
  }
  if (!(builder.total > 0.0) || !std::isfinite(builder.total) || !std::isfinite(squares)) return tree;
  tree.effective_samples_ = float(builder.total * builder.total / squares);
  tree.nodes_.emplace_back();
  builder.build(tree.nodes_, 0, samples.begin(), samples.end(), 1);
  tree.nodes_.shrink_to_fit();
  return tree;
}

Vec2 DirectionalQuadtree::sample_square(Vec2 u) const {
  // Descend: choose the quadrant by its energy (first the row, then the column within it), reusing u rescaled.
  Vec2 origin{0.0f, 0.0f};
  float size = 1.0f;
  size_t node = 0;
  for (;;) {
    const float* d = nodes_[node].density;  // sums to 4
    const float p_bottom = 0.25f * (d[0] + d[1]);
    int q = 0;
    if (u.y < p_bottom) {
      u.y = below_one(u.y / p_bottom);
    } else {
      u.y = below_one((u.y - p_bottom) / (1.0f - p_bottom));
      q = 2;
    }
    const float p_left = d[q] / (d[q] + d[q + 1]);
    if (u.x < p_left) {
      u.x = below_one(u.x / p_left);
    } else {
      u.x = below_one((u.x - p_left) / (1.0f - p_left));
      q += 1;
    }
    size *= 0.5f;
    origin.x += size * float(q & 1);
    origin.y += size * float(q >> 1);
    const uint32_t child = nodes_[node].child[q];
    if (child == 0) return {origin.x + size * u.x, origin.y + size * u.y};
    node = child;
  }
}

float DirectionalQuadtree::pdf_square(Vec2 p) const {
  if (nodes_.empty()) return 0.0f;
  float density = 1.0f;
  size_t node = 0;
  p = {std::clamp(p.x, 0.0f, kBelowOne), std::clamp(p.y, 0.0f, kBelowOne)};
  for (;;) {
    const int q = quadrant_of(p);
    const float factor = nodes_[node].density[q];
    if (!(factor > 0.0f)) return 0.0f;
    density *= factor;
    const uint32_t child = nodes_[node].child[q];
    if (child == 0) return density;
    p = into_quadrant(p, q);
    node = child;
  }
}

Vec3 DirectionalQuadtree::sample_direction(Vec2 u) const { return equal_area_square_to_sphere(sample_square(u)); }

float DirectionalQuadtree::pdf_direction(Vec3 direction) const {
  return pdf_square(equal_area_sphere_to_square(direction)) * kSquareToSphereDensity;
}

float DirectionalQuadtree::pdf_direction_at_square(Vec2 square) const { return pdf_square(square) * kSquareToSphereDensity; }

}  // namespace rimu
