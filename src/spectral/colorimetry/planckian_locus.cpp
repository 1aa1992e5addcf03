#include "spectral/colorimetry/planckian_locus.h"

#include <algorithm>
#include <cmath>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/colorimetry.h"

namespace rimu {
namespace {

// 324 geometric steps from 1000 K to 25000 K: a ratio of 25^(1/324) = 1.00998 per step, Ohno's "1 %" table.
constexpr int kTableSteps = 324;
// Each cascade level spreads this many intervals over the bracket [T_{m-1}, T_{m+1}] of the level before, so the
// step shrinks 5-fold per level: 1 % -> 0.2 % -> 0.04 % -> 0.008 %. The interpolation error falls with the
// square of the step (Ohno 2013 reports ~1 K at 1 % without his correction factor): measured, 0.05 K after two
// levels and ~2e-3 K after three, at the cost of 11 locus evaluations (~0.2 ms) per level.
constexpr int kCascadeIntervals = 10;
constexpr int kCascadeLevels = 3;

double distance(Uv1960 a, Uv1960 b) { return std::hypot(a.u - b.u, a.v - b.v); }

double sign_of(double value) { return value < 0.0 ? -1.0 : 1.0; }

}  // namespace

PlanckianLocus::PlanckianLocus(const Observer& observer, IntegrationGrid grid) {
  // The same wavelengths integrate_on_grid() visits, with the observer read once.
  integrate_on_grid(grid, [&](double lambda_nm) {
    wavelengths_nm_.push_back(lambda_nm);
    x_bar_.push_back(observer.x_bar.value(lambda_nm));
    y_bar_.push_back(observer.y_bar.value(lambda_nm));
    z_bar_.push_back(observer.z_bar.value(lambda_nm));
    return 0.0;
  });
  table_.reserve(kTableSteps + 1);
  for (int i = 0; i <= kTableSteps; ++i) {
    const double t = kMinCct_k * std::pow(kMaxCct_k / kMinCct_k, double(i) / kTableSteps);
    table_.push_back({t, uv_at(t), 0.0});
  }
}

Uv1960 PlanckianLocus::uv_at(double temperature_k) const {
  // The rectangle-rule sum of CIE 15:2004 §7.1 (the step and the absolute radiance scale cancel in (u, v)).
  const BlackbodySpectrum planck(temperature_k, BlackbodySpectrum::Scale::absolute_radiance);
  Xyz xyz;
  for (size_t i = 0; i < wavelengths_nm_.size(); ++i) {
    const double radiance = planck.value(wavelengths_nm_[i]);
    xyz.x += radiance * x_bar_[i];
    xyz.y += radiance * y_bar_[i];
    xyz.z += radiance * z_bar_[i];
  }
  return uv1960_of(xyz);
}

Chromaticity PlanckianLocus::chromaticity_at(double temperature_k, double duv) const {
  const Uv1960 on = uv_at(temperature_k), normal = normal_at(temperature_k);
  return chromaticity_of(Uv1960{on.u + duv * normal.u, on.v + duv * normal.v});
}

Uv1960 PlanckianLocus::normal_at(double temperature_k) const {
  // Central difference in T; a relative step of 1e-4 keeps the truncation error (∝ h²) and the rounding error
  // (∝ 1e-16/h) both below 1e-8 of the tangent.
  const double h = 1e-4 * temperature_k;
  const Uv1960 a = uv_at(temperature_k - h), b = uv_at(temperature_k + h);
  const double du = b.u - a.u, dv = b.v - a.v, length = std::hypot(du, dv);
  // u falls monotonically with T along the whole locus, so (dv, -du) has a positive v component: the +Duv side.
  return {dv / length, -du / length};
}

CctDuv PlanckianLocus::cct_duv(Uv1960 uv) const {
  if (!std::isfinite(uv.u) || !std::isfinite(uv.v)) return {0.0, 0.0, CctValidity::far_from_locus};

  // Level 0: the nearest node of the precomputed 1 % table, kept one node in from either end so that it has
  // two neighbours (the interpolation below may then land outside the table, which is how a point beyond
  // 1000 K or 25000 K is recognised).
  std::vector<Node> nodes = table_;
  for (Node& n : nodes) n.distance = distance(uv, n.uv);
  auto nearest = [](const std::vector<Node>& list) {
    const auto it = std::min_element(list.begin(), list.end(),
                                     [](const Node& a, const Node& b) { return a.distance < b.distance; });
    return std::clamp<size_t>(size_t(it - list.begin()), 1, list.size() - 2);
  };
  size_t m = nearest(nodes);

  // Ohno's cascade: spread exact locus points over [T_{m-1}, T_{m+1}] geometrically and find the nearest again.
  for (int level = 0; level < kCascadeLevels; ++level) {
    const double low_k = nodes[m - 1].temperature_k, high_k = nodes[m + 1].temperature_k;
    std::vector<Node> finer;
    finer.reserve(kCascadeIntervals + 1);
    for (int j = 0; j <= kCascadeIntervals; ++j) {
      const double t = low_k * std::pow(high_k / low_k, double(j) / kCascadeIntervals);
      const Uv1960 p = uv_at(t);
      finer.push_back({t, p, distance(uv, p)});
    }
    nodes = std::move(finer);
    m = nearest(nodes);
  }

  const Node& prev = nodes[m - 1];
  const Node& mid = nodes[m];
  const Node& next = nodes[m + 1];

  // Triangular solution (Ohno 2013, eqs. 5-8): the foot of the perpendicular from the point to the chord
  // P_{m-1}P_{m+1}, at distance x along it; T and v are interpolated linearly along the chord.
  const double chord = distance(prev.uv, next.uv);
  const double x = (prev.distance * prev.distance - next.distance * next.distance + chord * chord) / (2.0 * chord);
  double cct_k = prev.temperature_k + (next.temperature_k - prev.temperature_k) * x / chord;
  const double v_on_chord = prev.uv.v + (next.uv.v - prev.uv.v) * x / chord;
  double duv = std::sqrt(std::max(0.0, prev.distance * prev.distance - x * x)) * sign_of(uv.v - v_on_chord);

  // Parabolic solution (Ohno 2013, eqs. 9-13): fit d(T) = aT² + bT + c through the three nodes and take its
  // minimum. Ohno uses it beyond |Duv| = 0.002, where d(T) is smooth; near the locus d(T) has a kink (|T - T0|)
  // that a parabola fits badly, and the triangular solution is the better one.
  if (std::abs(duv) >= 0.002) {
    const double t0 = prev.temperature_k, t1 = mid.temperature_k, t2 = next.temperature_k;
    const double d0 = prev.distance, d1 = mid.distance, d2 = next.distance;
    const double denominator = (t2 - t1) * (t0 - t2) * (t1 - t0);
    const double a = (t0 * (d2 - d1) + t1 * (d0 - d2) + t2 * (d1 - d0)) / denominator;
    const double b = -(t0 * t0 * (d2 - d1) + t1 * t1 * (d0 - d2) + t2 * t2 * (d1 - d0)) / denominator;
    const double c = -(d0 * (t2 - t1) * t1 * t2 + d1 * (t0 - t2) * t0 * t2 + d2 * (t1 - t0) * t0 * t1) / denominator;
    // a > 0 whenever the middle node is the nearest; at a clamped table end it may not be, and the triangular
    // estimate (which then lies off the table and is flagged below) is kept.
    if (a > 0.0) {
      cct_k = -b / (2.0 * a);
      duv = (a * cct_k * cct_k + b * cct_k + c) * sign_of(uv.v - uv_at(cct_k).v);
    }
  }

  // Off the table: report the end point and the signed distance to it, flagged. A point on the 1000 K or 25000 K
  // isotemperature line may come out a hair outside through the interpolation error (~1e-4 K there), so the
  // ends get a slack of 0.01 K.
  constexpr double kEndSlack_k = 0.01;
  if (cct_k < kMinCct_k - kEndSlack_k || cct_k > kMaxCct_k + kEndSlack_k) {
    const bool below = cct_k < kMinCct_k;
    const double end_k = below ? kMinCct_k : kMaxCct_k;
    const Uv1960 end = uv_at(end_k);
    return {end_k, distance(uv, end) * sign_of(uv.v - end.v),
            below ? CctValidity::below_range : CctValidity::above_range};
  }
  return {cct_k, duv, std::abs(duv) > kMaxAbsDuv ? CctValidity::far_from_locus : CctValidity::ok};
}

CctDuv cct_duv_of(const Spectrum& source, const Observer& observer) {
  const Xyz xyz = illuminant_xyz(source, observer, IntegrationGrid::cie_1nm());
  return PlanckianLocus(observer).cct_duv(uv1960_of(xyz));
}

const char* cct_validity_name(CctValidity v) {
  switch (v) {
    case CctValidity::ok: return "ok";
    case CctValidity::below_range: return "below 1000 K";
    case CctValidity::above_range: return "above 25000 K";
    case CctValidity::far_from_locus: return "|Duv| > 0.05";
  }
  return "?";
}

}  // namespace rimu
