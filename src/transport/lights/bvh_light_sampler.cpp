#include "transport/lights/bvh_light_sampler.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/lights/light.h"

namespace rimu {

struct BvhLightSampler::BuildItem {
  LightBounds bounds;
  Vec3 centroid;
  uint32_t leaf;
  uint32_t spectrum;  // spectral only: index into the per-light band shapes
};

namespace {

constexpr int kBins = 12;
// Below this depth splits minimise the cost; deeper (pathological inputs: thousands of coincident emitters) the
// items are halved by count, so no leaf is deeper than kCostDepth + log2(n) ≤ 62 and its trail fits 64 bits.
constexpr int kCostDepth = 30;

// The bounds of a set of members without a cone union per member (each costs an acos and a rotation), in two
// sequential passes: the first gathers box, intensity and the mean axis; the second the largest angle from that axis
// to a member's cone edge, in cosines: cos(α + θo) = cos α cos θo − sin α sin θo, and the lit cone θl (light_bounds.h):
// the smallest θl_m − α, cos(θl_m − α) = cos θl_m cos α + sin θl_m sin α. Conservative, like unite().
class BoundsAccumulator {
 public:
  void add_first_pass(const LightBounds& m) {
    if (empty_) {
      b_ = m;
      empty_ = false;
    } else {
      b_.lower_m = {std::fmin(b_.lower_m.x, m.lower_m.x), std::fmin(b_.lower_m.y, m.lower_m.y), std::fmin(b_.lower_m.z, m.lower_m.z)};
      b_.upper_m = {std::fmax(b_.upper_m.x, m.upper_m.x), std::fmax(b_.upper_m.y, m.upper_m.y), std::fmax(b_.upper_m.z, m.upper_m.z)};
      b_.intensity_w_sr += m.intensity_w_sr;
      b_.cos_theta_e = std::fmin(b_.cos_theta_e, m.cos_theta_e);
      b_.two_sided = b_.two_sided || m.two_sided;
      same_axis_ = same_axis_ && m.axis == b_.axis && m.half_space && b_.half_space;
      if (same_axis_) {
        // Valid only while every member shares the axis; otherwise the second pass replaces both.
        b_.plane_offset_m = std::fmin(b_.plane_offset_m, m.plane_offset_m);
        b_.cos_theta_o = std::fmin(b_.cos_theta_o, m.cos_theta_o);
        b_.cos_theta_lit = std::fmax(b_.cos_theta_lit, m.cos_theta_lit);
      }
    }
    axis_sum_ += m.axis;
  }
  /// Between the passes. Returns false when the second pass is not needed (one member, or all facing one way).
  bool needs_second_pass() {
    if (empty_ || same_axis_) return false;
    b_.half_space = false;
    const float axis_length = length(axis_sum_);
    if (axis_length > 1e-6f) b_.axis = axis_sum_ / axis_length;
    second_ = true;
    return true;
  }
  void add_second_pass(const LightBounds& m) {
    const float c = std::clamp(dot(b_.axis, m.axis), -1.0f, 1.0f);
    const float s = std::sqrt(std::fmax(0.0f, 1.0f - c * c));
    if (cos_lit_ <= 1.0f) {
      // θl_m − α ≤ 0 (cos θl_m ≥ cos α, or no lit cone): nothing is certain.
      if (!(m.cos_theta_lit < c))
        cos_lit_ = kNoLitCone;
      else
        cos_lit_ = std::fmax(cos_lit_, m.cos_theta_lit * c + std::sqrt(std::fmax(0.0f, 1.0f - m.cos_theta_lit * m.cos_theta_lit)) * s);
    }
    if (cos_o_ <= -1.0f) return;
    if (c < -m.cos_theta_o) {  // α + θo ≥ π: the whole sphere
      cos_o_ = -1.0f;
      return;
    }
    const float sin_o = std::sqrt(std::fmax(0.0f, 1.0f - m.cos_theta_o * m.cos_theta_o));
    cos_o_ = std::fmin(cos_o_, c * m.cos_theta_o - s * sin_o);
  }
  LightBounds result() const {
    LightBounds out = b_;
    if (second_) {
      // Widened by 1e-4 rad against rounding in the cosines above (θl narrowed by as much).
      const double theta = std::min(std::acos(std::clamp(double(cos_o_), -1.0, 1.0)) + 1e-4, 3.14159265358979323846);
      out.cos_theta_o = float(std::cos(theta));
      const double lit = cos_lit_ <= 1.0f ? std::acos(std::clamp(double(cos_lit_), -1.0, 1.0)) - 1e-4 : -1.0;
      out.cos_theta_lit = lit > 0.0 ? float(std::cos(lit)) : kNoLitCone;
    }
    return out;
  }

 private:
  LightBounds b_;
  Vec3 axis_sum_{};
  float cos_o_ = 1.0f;
  float cos_lit_ = -1.0f;  // cos of the smallest θl_m − α so far (−1: none yet, i.e. π); kNoLitCone: none possible
  bool empty_ = true, same_axis_ = true, second_ = false;
};

double surface_area(const LightBounds& b, double floor_m) {
  const double x = double(b.upper_m.x - b.lower_m.x) + floor_m;
  const double y = double(b.upper_m.y - b.lower_m.y) + floor_m;
  const double z = double(b.upper_m.z - b.lower_m.z) + floor_m;
  return 2.0 * (x * y + y * z + z * x);
}

// Conty & Kulla's cost of a cluster: its intensity × orientation measure × surface area. The floor (a thousandth
// of the node's diagonal added to each extent) keeps collinear or coplanar point lights from all costing 0.
double cluster_cost(const LightBounds& b, double floor_m) {
  if (!(b.intensity_w_sr > 0.0f)) return 0.0;
  return double(b.intensity_w_sr) * orientation_measure(b) * surface_area(b, floor_m);
}

// True if every leaf below a cluster with bounds `b` scores > 0 at (p, n), decided from the cluster's own bounds
// (no leaf is read): p lies outside the cluster's bounding sphere, the whole box lies strictly above p's tangent
// plane (so every member's box does), and every direction from a member's point to p lies within the lit cone θl
// (light_bounds.h: inside that member's emission cone and falloff). With w the direction from the box centre to p and
// θu the angle the bounding sphere subtends at p, a direction from any point of the box to p is within ∠(axis, w) +
// θu of the axis; that must not exceed θl less twice the bounds' angular margin. For one-sided flat emitters (θl =
// π/2) this puts p in front of every member's plane; for a ceiling of downlights (θl = their γ reach), below it and
// inside every member's beam. Two-sided clusters are never certified here.
bool every_leaf_scores(const ImportanceBounds& b, Vec3 p, Vec3 normal) {
  // cos(θl − 2·margin) below, margin 1e-3 rad (light_bounds.cpp); θl ≤ 2·margin certifies nothing.
  if (b.two_sided || !(b.cos_theta_lit < kLitConeCosMargin)) return false;
  const Vec3 to_p = p - b.centre_m;
  if (!(normal == Vec3{}) && !(-dot(normal, to_p) - dot(abs(normal), b.half_m) > 0.0f)) return false;
  const float distance2 = length_squared(to_p);
  const float radius2 = b.radius2_m2;
  if (!(distance2 > radius2)) return false;
  // cos and sin of ∠(axis, w) + θu by the angle-sum formula; a sum past π fails (its sine turns negative).
  const float sin2_u = radius2 / distance2;
  const float c = dot(b.axis, to_p / std::sqrt(distance2));
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  const float cos_u = std::sqrt(1.0f - sin2_u), sin_u = std::sqrt(sin2_u);
  const float c_sum = c * cos_u - s * sin_u;
  const float s_sum = s * cos_u + c * sin_u;
  if (!(s_sum >= 0.0f)) return false;
  const float sin_l = std::sqrt(std::max(0.0f, 1.0f - b.cos_theta_lit * b.cos_theta_lit));
  return c_sum >= b.cos_theta_lit * kLitConeCosMargin + sin_l * kLitConeSinMargin;
}

// Whether leaf a is the better representative of a subtree than leaf b: the one more likely to score > 0 at an
// arbitrary point, i.e. the one whose emission reaches the widest cone (θo + θe: a point light everywhere, a spot
// its cone, a triangle its hemisphere), then the brighter.
bool more_likely_to_score(const ImportanceBounds& a, const ImportanceBounds& b) {
  const auto reach = [](const ImportanceBounds& x) {
    return std::min(std::acos(std::clamp(double(x.cos_theta_o), -1.0, 1.0)) +
                        std::acos(std::clamp(double(x.cos_theta_e), -1.0, 1.0)),
                    3.14159265358979323846) + (x.two_sided ? 3.14159265358979323846 : 0.0);
  };
  const double reach_a = reach(a), reach_b = reach(b);
  if (std::fabs(reach_a - reach_b) > 1e-6) return reach_a > reach_b;
  return a.intensity_w_sr > b.intensity_w_sr;
}

}  // namespace

namespace {

constexpr double kBandLowerNm = 360.0, kBandUpperNm = 830.0;

// A light's emission spectrum in BvhLightSampler::kBands bands: each band's mean over its mean over 360-830 nm
// (1 nm midpoint sums), so the bands average to 1. Flat for lights without one spectrum or with a black one.
std::array<float, BvhLightSampler::kBands> band_shape(const Light& light) {
  std::array<float, BvhLightSampler::kBands> shape;
  shape.fill(1.0f);
  const LightSpectrum* spectrum = light.emitted_spectrum();
  if (!spectrum) return shape;
  // 30 midpoints per band, 0.98 nm apart: fine enough for 1 nm tables and line spectra a few nm wide.
  constexpr int kNmPerBand = int(kBandUpperNm - kBandLowerNm) / BvhLightSampler::kBands;
  const double band_nm = (kBandUpperNm - kBandLowerNm) / BvhLightSampler::kBands;
  std::array<double, BvhLightSampler::kBands> mean{};
  double total = 0.0;
  for (int b = 0; b < BvhLightSampler::kBands; ++b) {
    const double step = band_nm / (kNmPerBand + 1);
    for (int i = 0; i <= kNmPerBand; ++i)
      mean[size_t(b)] += std::max(0.0, spectrum->shape()->value(kBandLowerNm + b * band_nm + (i + 0.5) * step));
    mean[size_t(b)] /= kNmPerBand + 1;
    total += mean[size_t(b)] / BvhLightSampler::kBands;
  }
  if (!(total > 0.0) || !std::isfinite(total)) return shape;
  for (int b = 0; b < BvhLightSampler::kBands; ++b) shape[size_t(b)] = float(mean[size_t(b)] / total);
  return shape;
}

int band_of(float lambda_nm) {
  const int b = int((double(lambda_nm) - kBandLowerNm) * (BvhLightSampler::kBands / (kBandUpperNm - kBandLowerNm)));
  return std::clamp(b, 0, BvhLightSampler::kBands - 1);
}

}  // namespace

BvhLightSampler::BvhLightSampler(std::span<const Light* const> lights, Importance importance, int search_budget)
    : search_budget_(search_budget) {
  const bool spectral = importance == Importance::spectral;
  std::vector<std::array<float, kBands>> light_bands;  // spectral: per light, band_shape
  if (spectral)
    for (const Light* light : lights) light_bands.push_back(light->is_infinite() ? std::array<float, kBands>{} : band_shape(*light));
  first_part_.resize(lights.size());
  is_infinite_.resize(lights.size());
  size_t total_parts = 0;
  for (size_t i = 0; i < lights.size(); ++i) {
    first_part_[i] = uint32_t(total_parts);
    total_parts += size_t(std::max(lights[i]->part_count(), 1));
  }
  trails_.assign(total_parts, 0);
  std::vector<BuildItem> items;
  for (size_t i = 0; i < lights.size(); ++i) {
    const Light& light = *lights[i];
    // An environment with portals has bounds (its portals) and is a leaf like any area light.
    if (light.is_infinite() && !light.part_bounds(0)) {
      is_infinite_[i] = true;
      if (light.total_power_w(1.0) > 0.0 && light.sampled_by_nee()) {
        infinite_lights_.push_back(int(i));
        // A directional light with E⊥ ≤ 0 (or NaN) but power counts as a wide one: it keeps the rule's share.
        const float e = light.directional_irradiance_w_m2().value_or(0.0f);
        directional_irradiance_.push_back(e > 0.0f && std::isfinite(e) ? e : 0.0f);
        if (directional_irradiance_.back() > 0.0f) {
          ++directional_count_;
          directional_sum_ += directional_irradiance_.back();
        }
      }
      continue;
    }
    bool any_bounds = false;
    for (int k = 0; k < light.part_count(); ++k) {
      const std::optional<LightBounds> b = light.part_bounds(k);
      if (!b || !(b->intensity_w_sr > 0.0f) || !std::isfinite(b->intensity_w_sr) || !is_finite(b->lower_m) ||
          !is_finite(b->upper_m))
        continue;
      any_bounds = true;
      items.push_back({*b, b->centre_m(), uint32_t(leaves_.size()), uint32_t(i)});
      leaves_.push_back({int(i), k});
    }
    // A finite light with power must say where it emits, or the tree could never pick it.
    assert(any_bounds || !(light.total_power_w(0.0) > 0.0));
    (void)any_bounds;
  }
  leaf_count_ = int(leaves_.size());
  if (spectral) {
    light_bands_ = std::move(light_bands);
    node_bands_.resize(items.empty() ? 0 : 2 * items.size() - 1);
  }
  if (!items.empty()) {
    nodes_.reserve(2 * items.size());
    build(items, 0, items.size(), 0, 0);
    if (!nodes_[0].is_leaf) {
      // Depth-first order: a node's subtree ends where its second child's does (a leaf's right after it).
      std::vector<uint32_t> subtree_end(nodes_.size());
      for (size_t i = nodes_.size(); i-- > 0;)
        subtree_end[i] = nodes_[i].is_leaf ? uint32_t(i + 1) : subtree_end[nodes_[i].index];
      build_wide(0, subtree_end);
      wide_nodes_.shrink_to_fit();  // about one wide node per three leaves
      representatives_.shrink_to_fit();
    }
    tree_representative4_.set(0, nodes_[nodes_[0].representative].bounds);
  }
  light_bands_.clear();
  light_bands_.shrink_to_fit();
}

uint32_t BvhLightSampler::build(std::vector<BuildItem>& items, size_t begin, size_t end, int depth, uint64_t trail) {
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.emplace_back();
  if (end - begin == 1) {
    const Leaf& leaf = leaves_[items[begin].leaf];
    nodes_[index].bounds = ImportanceBounds::of(items[begin].bounds);
    nodes_[index].index = items[begin].leaf;
    nodes_[index].is_leaf = true;
    nodes_[index].representative = index;
    trails_[first_part_[size_t(leaf.light)] + uint32_t(leaf.part)] = trail | (uint64_t(1) << depth);
    max_depth_ = std::max(max_depth_, depth);
    if (!node_bands_.empty())
      for (int b = 0; b < kBands; ++b)
        node_bands_[index][size_t(b)] = items[begin].bounds.intensity_w_sr * light_bands_[items[begin].spectrum][size_t(b)];
    return index;
  }

  BoundsAccumulator node_bounds;
  for (size_t i = begin; i < end; ++i) node_bounds.add_first_pass(items[i].bounds);
  if (node_bounds.needs_second_pass())
    for (size_t i = begin; i < end; ++i) node_bounds.add_second_pass(items[i].bounds);
  const LightBounds bounds = node_bounds.result();
  Vec3 centroid_lower = items[begin].centroid, centroid_upper = items[begin].centroid;
  for (size_t i = begin; i < end; ++i) {
    const Vec3 c = items[i].centroid;
    centroid_lower = {std::fmin(centroid_lower.x, c.x), std::fmin(centroid_lower.y, c.y), std::fmin(centroid_lower.z, c.z)};
    centroid_upper = {std::fmax(centroid_upper.x, c.x), std::fmax(centroid_upper.y, c.y), std::fmax(centroid_upper.z, c.z)};
  }
  const Vec3 extent = centroid_upper - centroid_lower;
  const float max_extent = max_component(extent);
  const double floor_m = 1e-3 * double(length(bounds.upper_m - bounds.lower_m));

  size_t middle = begin;
  if (depth < kCostDepth && max_extent > 0.0f) {
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_split = 0;
    // As many bins as items, up to kBins: most nodes are small, and each bin boundary costs two cluster costs.
    const int bins_here = int(std::min<size_t>(kBins, end - begin));
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0.0f)) continue;
      std::array<LightBounds, kBins> bins{};
      std::array<size_t, kBins> counts{};
      const float scale = float(bins_here) / extent[axis];
      const auto bin_of = [&](const BuildItem& item) {
        return std::clamp(int((item.centroid[axis] - centroid_lower[axis]) * scale), 0, bins_here - 1);
      };
      std::array<BoundsAccumulator, kBins> accumulators;
      for (size_t i = begin; i < end; ++i) {
        const int bin = bin_of(items[i]);
        accumulators[size_t(bin)].add_first_pass(items[i].bounds);
        ++counts[size_t(bin)];
      }
      std::array<bool, kBins> second{};
      bool any_second = false;
      for (int b = 0; b < bins_here; ++b) any_second |= second[size_t(b)] = accumulators[size_t(b)].needs_second_pass();
      if (any_second)
        for (size_t i = begin; i < end; ++i) {
          const int bin = bin_of(items[i]);
          if (second[size_t(bin)]) accumulators[size_t(bin)].add_second_pass(items[i].bounds);
        }
      for (int b = 0; b < bins_here; ++b)
        if (counts[size_t(b)] > 0) bins[size_t(b)] = accumulators[size_t(b)].result();
      std::array<double, kBins> cost_above{};  // cost of bins [s, bins_here)
      LightBounds above;
      for (int s = bins_here - 1; s >= 1; --s) {
        above = unite(above, bins[size_t(s)]);
        cost_above[size_t(s)] = cluster_cost(above, floor_m);
      }
      LightBounds below;
      size_t count_below = 0;
      // Thin axes are penalised (Conty & Kulla's K_r): a split across a short extent separates little.
      const double regulariser = double(max_extent) / double(extent[axis]);
      for (int s = 1; s < bins_here; ++s) {
        below = unite(below, bins[size_t(s - 1)]);
        count_below += counts[size_t(s - 1)];
        if (count_below == 0 || count_below == end - begin) continue;
        const double cost = regulariser * (cluster_cost(below, floor_m) + cost_above[size_t(s)]);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_split = s;
        }
      }
    }
    if (best_axis >= 0) {
      const float scale = float(bins_here) / extent[best_axis];
      const float lower = centroid_lower[best_axis];
      middle = size_t(std::partition(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(end),
                                     [&](const BuildItem& item) {
                                       return std::clamp(int((item.centroid[best_axis] - lower) * scale), 0,
                                                         bins_here - 1) < best_split;
                                     }) -
                      items.begin());
    }
  }
  if (middle == begin || middle == end) {
    // No useful cost split: halve by count along the longest centroid extent.
    middle = begin + (end - begin) / 2;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[axis]) axis = a;
    std::nth_element(items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(middle),
                     items.begin() + std::ptrdiff_t(end),
                     [axis](const BuildItem& a, const BuildItem& b) { return a.centroid[axis] < b.centroid[axis]; });
  }

  const uint32_t first = build(items, begin, middle, depth + 1, trail);
  const uint32_t second = build(items, middle, end, depth + 1, trail | (uint64_t(1) << depth));
  nodes_[index].bounds = ImportanceBounds::of(bounds);
  nodes_[index].index = second;
  if (!node_bands_.empty())
    for (int b = 0; b < kBands; ++b)
      node_bands_[index][size_t(b)] = node_bands_[first][size_t(b)] + node_bands_[second][size_t(b)];
  const uint32_t first_representative = nodes_[first].representative;
  const uint32_t second_representative = nodes_[second].representative;
  nodes_[index].representative =
      more_likely_to_score(nodes_[second_representative].bounds, nodes_[first_representative].bounds)
          ? second_representative
          : first_representative;
  return index;
}

uint32_t BvhLightSampler::build_wide(uint32_t index, const std::vector<uint32_t>& subtree_end) {
  const uint32_t wide = uint32_t(wide_nodes_.size());
  wide_nodes_.emplace_back();
  std::array<uint32_t, 4> slots{};
  int count = 0, first_slots = 0;
  for (const uint32_t child : {index + 1, nodes_[index].index}) {
    if (nodes_[child].is_leaf) {
      slots[size_t(count++)] = child;
    } else {
      slots[size_t(count++)] = child + 1;
      slots[size_t(count++)] = nodes_[child].index;
    }
    if (first_slots == 0) first_slots = count;
  }
  std::array<uint32_t, 4> below{kNoLeaf, kNoLeaf, kNoLeaf, kNoLeaf};
  for (int j = 0; j < count; ++j) {
    const uint32_t child = slots[size_t(j)];
    if (!nodes_[child].is_leaf) below[size_t(j)] = build_wide(child, subtree_end);
  }
  WideNode& node = wide_nodes_[wide];  // (after the recursion, which grows the vector)
  for (int j = 0; j < count; ++j) {
    const uint32_t child = slots[size_t(j)];
    node.bounds.set(j, nodes_[child].bounds);
    node.child[size_t(j)] = child;
    node.child_end[size_t(j)] = subtree_end[child];
    node.wide[size_t(j)] = below[size_t(j)];
    if (!nodes_[child].is_leaf) node.interior_slots = uint8_t(node.interior_slots | (1 << j));
  }
  if (node.interior_slots != 0) {
    node.representatives = uint32_t(representatives_.size());
    Representatives& r = representatives_.emplace_back();
    for (int j = 0; j < count; ++j) {
      const uint32_t child = slots[size_t(j)];
      if (nodes_[child].is_leaf) continue;
      r.node[size_t(j)] = nodes_[child].representative;
      r.bounds.set(j, nodes_[nodes_[child].representative].bounds);
    }
  }
  node.count = uint8_t(count);
  node.first_slots = uint8_t(first_slots);
  return wide;
}

namespace {

// Sums four floats in ascending order: the same result for any order of the inputs (rotated lanes).
float order_independent_sum(std::array<float, 4> v) {
  const auto order = [](float& a, float& b) {
    if (b < a) std::swap(a, b);
  };
  order(v[0], v[1]);
  order(v[2], v[3]);
  order(v[0], v[2]);
  order(v[1], v[3]);
  order(v[1], v[2]);
  return ((v[0] + v[1]) + v[2]) + v[3];
}

}  // namespace

BvhLightSampler::Query BvhLightSampler::query(const LightSamplingPoint& at) const {
  Query q(at);
  if (node_bands_.empty() || !at.wavelengths) return q;
  static_assert(kLaneCount == 4);
  const SampledWavelengths& lambda = *at.wavelengths;
  const Float4 pdf = lambda.pdf();
  std::array<float, 4> w{};
  for (int k = 0; k < 4; ++k) {
    q.band[size_t(k)] = band_of(lambda.lambda_nm(k));
    // Lanes without a density (terminated) add nothing to the film.
    w[size_t(k)] = pdf[k] > 0.0f && std::isfinite(pdf[k]) ? 1.0f : 0.0f;
  }
  const float total = order_independent_sum(w);
  if (!(total > 0.0f) || !std::isfinite(total)) return q;
  for (int k = 0; k < 4; ++k) q.weight[size_t(k)] = w[size_t(k)] / total;
  q.spectral = true;
  return q;
}

float BvhLightSampler::importance(uint32_t index, const Query& at) const {
  const float broadband = light_importance(nodes_[index].bounds, at.position_m, at.normal);
  if (!at.spectral || !(broadband > 0.0f)) return broadband;
  return spectral_importance(index, broadband, at);
}

float BvhLightSampler::spectral_importance(uint32_t index, float broadband, const Query& at) const {
  const float intensity = nodes_[index].bounds.intensity_w_sr;
  const std::array<float, kBands>& bands = node_bands_[index];
  std::array<float, 4> terms;
  for (size_t k = 0; k < 4; ++k) terms[k] = at.weight[k] * bands[size_t(at.band[k])];
  const float spectral = order_independent_sum(terms) + kSpectralFloor * intensity;
  return broadband * (spectral / intensity);
}

// Inlined into the descents of sample() and pmf(): a call's register saves were ~20 instructions per level.
[[gnu::always_inline]] inline BvhLightSampler::WideSplit BvhLightSampler::wide_split(uint32_t index, uint32_t witness,
                                                                                     const Query& at) const {
  const WideNode& node = wide_nodes_[index];
  const Importance4 importance4 = light_importance4(node.bounds, at.point4);
  WideSplit out;
  out.weight = importance4.value;
  // Which scoring slots still need a witness, as bit masks: not a leaf (its own), not certified (by the node's own
  // bounds, or below a certified node), not holding the witness passed down (a leaf node index within the slot's
  // depth-first range [child, child_end); node indices are < 2³¹, so signed compares order them).
  const int scoring = _mm_movemask_ps(_mm_cmpgt_ps(_mm_loadu_ps(importance4.value.data()), _mm_setzero_ps()));
  out.certified = witness == kCertified ? 0xf : importance4.certified;
  if (witness < kUnknown) {
    const __m128i w = _mm_set1_epi32(int(witness));
    const __m128i first = _mm_loadu_si128(reinterpret_cast<const __m128i*>(node.child.data()));
    const __m128i end = _mm_loadu_si128(reinterpret_cast<const __m128i*>(node.child_end.data()));
    const __m128i holds = _mm_andnot_si128(_mm_cmpgt_epi32(first, w), _mm_cmpgt_epi32(end, w));
    out.holder = _mm_movemask_ps(_mm_castsi128_ps(holds));
    out.passed_down = witness;
  }
  const int unchecked = scoring & node.interior_slots & ~out.certified & ~out.holder;
  if (unchecked != 0) {
    // Their representatives first, all four in lanes (the scalar search would check each one first, one by one);
    // a search only below a slot whose representative scores 0.
    const Representatives& representatives = representatives_[node.representatives];
    const int representative_scores = light_scores4(representatives.bounds, at.point4);
    for (size_t j = 0; j < node.count; ++j) {
      if (!((unchecked >> j) & 1)) continue;
      if ((representative_scores >> j) & 1) {
        out.witness[j] = representatives.node[j];
        continue;
      }
      int budget = search_budget_ > 0 ? search_budget_ : -1;
      out.witness[j] = find_scoring_leaf(node.child[j], at, &budget, /*representative_checked=*/true);
      if (out.witness[j] == kNoLeaf) out.weight[j] = 0.0f;
    }
  }
  if (at.spectral)
    for (size_t j = 0; j < node.count; ++j)
      if (out.weight[j] > 0.0f) out.weight[j] = spectral_importance(node.child[j], out.weight[j], at);
  out.sum = (out.weight[0] + out.weight[1]) + (out.weight[2] + out.weight[3]);
  return out;
}

uint32_t BvhLightSampler::find_scoring_leaf(uint32_t index, const Query& at, int* budget,
                                            bool representative_checked) const {
  // One node visit = one importance evaluation; a budget of 0 left means give up (a negative one never does).
  const auto visit = [budget] {
    if (*budget == 0) return false;
    if (*budget > 0) --*budget;
    return true;
  };
  const Node& node = nodes_[index];
  if (!visit()) return kUnknown;
  if (!representative_checked && light_importance(nodes_[node.representative].bounds, at.position_m, at.normal) > 0.0f)
    return node.representative;
  // Depth first; a child that scores 0 is skipped whole (its leaves' bounds lie inside its own, so they score 0
  // too, up to rounding).
  for (const uint32_t child : {index + 1, node.index}) {
    const Node& c = nodes_[child];
    if (!visit()) return kUnknown;
    if (!(light_importance(c.bounds, at.position_m, at.normal) > 0.0f)) continue;
    if (c.is_leaf) return child;
    if (every_leaf_scores(c.bounds, at.position_m, at.normal)) return c.representative;
    if (const uint32_t leaf = find_scoring_leaf(child, at, budget); leaf != kNoLeaf) return leaf;
  }
  return kNoLeaf;
}

inline BvhLightSampler::Shares BvhLightSampler::shares(const Query& at) const {
  // Without lights at infinity the tree takes everything (a descent that finds no slot returns no light). Inline,
  // as that case is most scenes'.
  const int m = int(infinite_lights_.size());
  if (m == 0) [[likely]] {
    Shares s;
    s.tree = nodes_.empty() ? 0.0f : 1.0f;
    return s;
  }
  return infinite_shares(at);
}

BvhLightSampler::Shares BvhLightSampler::infinite_shares(const Query& at) const {
  const int m = int(infinite_lights_.size());
  // Whether some leaf scores, decided as for any child (the root's certificate, else its representative, else a
  // search), not by the root's split: choosing or weighing a light at infinity then costs one importance
  // evaluation where the representative scores, and the witness found spares the descent one slot's check.
  // The tree's representative first (it scores at most points: the widest-reaching leaf, e.g. a portal sky).
  uint32_t witness = kNoLeaf;
  if (!nodes_.empty()) {
    // (In lane 0 of light_scores4: exactly the scalar importance's > 0, without the importance.)
    const uint32_t representative = nodes_[0].representative;
    if (light_scores4(tree_representative4_, at.point4) & 1)
      witness = representative;
    else if (nodes_[0].is_leaf)
      witness = kNoLeaf;
    else if (light_importance(nodes_[0].bounds, at.position_m, at.normal) > 0.0f) {
      if (every_leaf_scores(nodes_[0].bounds, at.position_m, at.normal)) {
        witness = kCertified;
      } else {
        int budget = search_budget_ > 0 ? search_budget_ : -1;
        witness = find_scoring_leaf(0, at, &budget, /*representative_checked=*/true);
      }
    }
  }
  // The fixed rule over the m lights at infinity and the tree (if it can contribute): 1/(m + 1) each. The directional
  // ones (the sun: only light sampling finds it) and the tree then split their part between them by irradiance (a
  // sun's E⊥, the tree's root importance at the point) mixed with the rule, so each keeps at least
  // kInfiniteRuleWeight of its rule's share; the wide ones (environments, skies: BSDF sampling finds them) keep theirs.
  const bool tree_can = witness != kNoLeaf;
  Shares s;
  s.root_witness = witness;
  const int members = m + (tree_can ? 1 : 0);
  s.wide = 1.0f / float(members);
  if (directional_count_ == 0) {
    s.tree = tree_can ? s.wide : 0.0f;
    return s;
  }
  // The directional lights' and the tree's part of the rule, split by E mixed with the rule.
  const int splitting = directional_count_ + (tree_can ? 1 : 0);
  const float pool = float(splitting) / float(members);
  const float tree_estimate = tree_can ? light_importance(nodes_[0].bounds, at.position_m, at.normal) : 0.0f;
  const float rule = kInfiniteRuleWeight;
  const float total = tree_estimate + directional_sum_;
  s.directional_base = pool * rule / float(splitting);
  s.directional_scale = total > 0.0f && std::isfinite(total) ? pool * (1.0f - rule) / total : 0.0f;
  if (!(s.directional_scale > 0.0f)) s.directional_base = pool / float(splitting);
  if (tree_can) s.tree = s.directional_base + s.directional_scale * tree_estimate;
  return s;
}

std::optional<LightChoice> BvhLightSampler::sample(const LightSamplingPoint& point, float u_float) const {
  const Query at = query(point);
  const Shares shares_here = shares(at);
  const int m = int(infinite_lights_.size());
  double u = double(u_float);
  // The lights at infinity first, each an interval of [0, 1) as long as its probability; the tree the rest.
  double infinite_total = 0.0;
  for (int k = 0; k < m; ++k) {
    const float p = infinite_probability(size_t(k), shares_here);
    if (!(p > 0.0f)) continue;
    if (u < infinite_total + double(p)) return LightChoice{infinite_lights_[size_t(k)], 0, p};
    infinite_total += double(p);
  }
  if (!(shares_here.tree > 0.0f)) return std::nullopt;
  constexpr double kBelowOne = 1.0 - 0x1p-53;
  u = std::min((u - infinite_total) / double(shares_here.tree), kBelowOne);
  float probability = shares_here.tree;
  uint32_t node = 0;  // binary node reached
  if (nodes_[0].is_leaf) {
    if (!(importance(0, at) > 0.0f)) return std::nullopt;
  } else {
    uint32_t wide = 0, witness = shares_here.root_witness;
    for (;;) {
      const WideNode& w = wide_nodes_[wide];
      const WideSplit s = wide_split(wide, witness, at);
      if (!(s.sum > 0.0f)) return std::nullopt;  // no slot can contribute (only through rounding)
      // The slot whose interval of [0, Σ) holds u·Σ (the last slot with weight, against rounding).
      const double target = u * double(s.sum);
      int chosen = -1;
      double below = 0.0, chosen_below = 0.0;
      for (int j = 0; j < w.count; ++j) {
        const double weight = double(s.weight[size_t(j)]);
        if (!(weight > 0.0)) continue;
        chosen = j;
        chosen_below = below;
        if (target < below + weight) break;
        below += weight;
      }
      if (chosen < 0) return std::nullopt;
      const float weight = s.weight[size_t(chosen)];
      u = std::clamp((target - chosen_below) / double(weight), 0.0, kBelowOne);
      probability *= weight / s.sum;
      witness = s.witness_of(chosen);
      node = w.child[size_t(chosen)];
      if (w.wide[size_t(chosen)] == kNoLeaf) break;
      wide = w.wide[size_t(chosen)];
    }
  }
  if (!(probability > 0.0f)) return std::nullopt;  // underflow far down a deep tree
  const Leaf& leaf = leaves_[nodes_[node].index];
  return LightChoice{leaf.light, leaf.part, probability};
}

float BvhLightSampler::pmf(const LightSamplingPoint& point, int light, int part) const {
  const Query at = query(point);
  if (light < 0 || size_t(light) >= first_part_.size() || part < 0) return 0.0f;
  if (is_infinite_[size_t(light)]) {
    const auto k = std::find(infinite_lights_.begin(), infinite_lights_.end(), light);
    if (part != 0 || k == infinite_lights_.end()) return 0.0f;
    return infinite_probability(size_t(k - infinite_lights_.begin()), shares(at));
  }
  const size_t end = size_t(light) + 1 < first_part_.size() ? first_part_[size_t(light) + 1] : trails_.size();
  const size_t slot = first_part_[size_t(light)] + size_t(part);
  if (slot >= end) return 0.0f;
  uint64_t trail = trails_[slot];
  if (trail == 0) return 0.0f;
  const Shares shares_here = shares(at);
  if (!(shares_here.tree > 0.0f)) return 0.0f;
  float probability = shares_here.tree;
  if (nodes_[0].is_leaf) return importance(0, at) > 0.0f ? probability : 0.0f;
  uint32_t wide = 0, witness = shares_here.root_witness;
  for (;;) {
    const WideNode& w = wide_nodes_[wide];
    const WideSplit s = wide_split(wide, witness, at);
    // The trail's next bit picks the binary child; unless that child is a leaf, the bit after it the grandchild.
    const bool second = (trail & 1) != 0;
    trail >>= 1;
    size_t j = second ? w.first_slots : 0;
    if ((second ? w.count - w.first_slots : w.first_slots) == 2) {
      j += trail & 1;
      trail >>= 1;
    }
    if (!(s.weight[j] > 0.0f)) return 0.0f;
    probability *= s.weight[j] / s.sum;
    witness = s.witness_of(int(j));
    if (w.wide[j] == kNoLeaf) return probability;
    wide = w.wide[j];
  }
}

size_t BvhLightSampler::memory_bytes() const {
  return sizeof(*this) + nodes_.capacity() * sizeof(Node) + wide_nodes_.capacity() * sizeof(WideNode) +
         representatives_.capacity() * sizeof(Representatives) +
         leaves_.capacity() * sizeof(Leaf) +
         first_part_.capacity() * sizeof(uint32_t) + trails_.capacity() * sizeof(uint64_t) +
         infinite_lights_.capacity() * sizeof(int) + directional_irradiance_.capacity() * sizeof(float) +
         is_infinite_.capacity() / 8 +
         node_bands_.capacity() * sizeof(node_bands_[0]);
}

}  // namespace rimu
