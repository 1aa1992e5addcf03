#include "transport/lights/candela_distribution.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace rimu {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// The interval [grid[i], grid[i+1]] holding x (clamped to the ends) and the fraction t of the way along it.
std::pair<size_t, double> locate(const std::vector<double>& grid, double x) {
  const auto upper = std::upper_bound(grid.begin(), grid.end(), x);
  size_t i = upper == grid.begin() ? 0 : size_t(upper - grid.begin()) - 1;
  i = std::min(i, grid.size() - 2);
  const double t = std::clamp((x - grid[i]) / (grid[i + 1] - grid[i]), 0.0, 1.0);
  return {i, t};
}

}  // namespace

CandelaDistribution::CandelaDistribution(std::vector<double> gamma_deg, std::vector<double> c_deg,
                                         std::vector<double> values)
    : gamma_deg_(std::move(gamma_deg)), c_deg_(std::move(c_deg)), values_(std::move(values)) {
  assert(gamma_deg_.size() >= 2 && c_deg_.size() >= 2 && values_.size() == gamma_deg_.size() * c_deg_.size());
  assert(c_deg_.front() == 0.0 && c_deg_.back() == 360.0);
  for (double g : gamma_deg_) cos_gamma_.push_back(std::cos(g * kDegToRad));
  for (double v : values_) peak_ = std::max(peak_, v);

  const size_t nc = c_deg_.size() - 1, ng = gamma_deg_.size() - 1;
  std::vector<double> weights(nc * ng);
  for (size_t j = 0; j < ng; ++j) {
    const double g0 = gamma_deg_[j] * kDegToRad, g1 = gamma_deg_[j + 1] * kDegToRad;
    const double a = cos_gamma_[j] - cos_gamma_[j + 1];
    const double b = (std::sin(g1) - std::sin(g0)) / (g1 - g0) - cos_gamma_[j + 1];
    for (size_t i = 0; i < nc; ++i) {
      const double dc = (c_deg_[i + 1] - c_deg_[i]) * kDegToRad;
      const double at_g0 = 0.5 * (value(i, j) + value(i + 1, j)), at_g1 = 0.5 * (value(i, j + 1) + value(i + 1, j + 1));
      integral_ += dc * (at_g0 * (a - b) + at_g1 * b);
      const double mean = 0.25 * (value(i, j) + value(i + 1, j) + value(i, j + 1) + value(i + 1, j + 1));
      weights[j * nc + i] = mean * dc * a;
    }
  }
  cells_ = Distribution2D(weights, int(nc), int(ng));
}

double CandelaDistribution::intensity_deg(double gamma, double c) const {
  if (!(gamma >= gamma_deg_.front() && gamma <= gamma_deg_.back())) return 0.0;
  c = std::fmod(c, 360.0);
  if (c < 0.0) c += 360.0;
  const auto [j, t] = locate(gamma_deg_, gamma);
  const auto [i, s] = locate(c_deg_, c);
  return (1.0 - s) * ((1.0 - t) * value(i, j) + t * value(i, j + 1)) +
         s * ((1.0 - t) * value(i + 1, j) + t * value(i + 1, j + 1));
}

double CandelaDistribution::intensity(Vec3 w) const {
  const double gamma = std::acos(std::clamp(double(w.z), -1.0, 1.0)) / kDegToRad;
  const double c = std::atan2(double(w.y), double(w.x)) / kDegToRad;
  return intensity_deg(gamma, c);
}

std::optional<CandelaDistribution::DirectionSample> CandelaDistribution::sample(Vec2 u) const {
  if (cells_.is_zero()) return std::nullopt;
  const Distribution2D::Sample cell = cells_.sample(u);
  const size_t i = size_t(cell.x), j = size_t(cell.y);
  const size_t nc = c_deg_.size() - 1, ng = gamma_deg_.size() - 1;
  // Position inside the cell from the sample's offset within its uniform-grid cell.
  const double fu = std::clamp(double(cell.uv.x) * double(nc) - double(i), 0.0, 1.0);
  const double fv = std::clamp(double(cell.uv.y) * double(ng) - double(j), 0.0, 1.0);
  const double c = (c_deg_[i] + fu * (c_deg_[i + 1] - c_deg_[i])) * kDegToRad;
  const double cos_g = cos_gamma_[j] - fv * (cos_gamma_[j] - cos_gamma_[j + 1]);
  const double sin_g = std::sqrt(std::max(0.0, 1.0 - cos_g * cos_g));
  const double solid_angle = (c_deg_[i + 1] - c_deg_[i]) * kDegToRad * (cos_gamma_[j] - cos_gamma_[j + 1]);
  // P(cell) = pdf_uv / (nc · ng); p(ω) = P(cell) / Ω_cell.
  const double pdf = double(cell.pdf) / double(nc * ng) / solid_angle;
  if (!(pdf > 0.0) || !std::isfinite(pdf)) return std::nullopt;
  return DirectionSample{{float(sin_g * std::cos(c)), float(sin_g * std::sin(c)), float(cos_g)}, float(pdf)};
}

float CandelaDistribution::pdf(Vec3 w) const {
  if (cells_.is_zero()) return 0.0f;
  const double gamma = std::acos(std::clamp(double(w.z), -1.0, 1.0)) / kDegToRad;
  if (!(gamma >= gamma_deg_.front() && gamma <= gamma_deg_.back())) return 0.0f;
  double c = std::atan2(double(w.y), double(w.x)) / kDegToRad;
  if (c < 0.0) c += 360.0;
  const size_t j = locate(gamma_deg_, gamma).first, i = locate(c_deg_, c).first;
  const size_t nc = c_deg_.size() - 1, ng = gamma_deg_.size() - 1;
  // The cell's centre in the unit square gives the Distribution2D's density of that cell.
  const Vec2 centre{float((double(i) + 0.5) / double(nc)), float((double(j) + 0.5) / double(ng))};
  const double solid_angle = (c_deg_[i + 1] - c_deg_[i]) * kDegToRad * (cos_gamma_[j] - cos_gamma_[j + 1]);
  return float(double(cells_.pdf(centre)) / double(nc * ng) / solid_angle);
}

std::optional<std::pair<double, double>> CandelaDistribution::nonzero_gamma_rad() const {
  int first = -1, last = -1;
  for (int j = 0; j < int(gamma_deg_.size()); ++j)
    for (size_t i = 0; i < c_deg_.size(); ++i)
      if (value(i, size_t(j)) > 0.0) {
        if (first < 0) first = j;
        last = j;
        break;
      }
  if (first < 0) return std::nullopt;
  // Between grid angles the interpolant is positive only next to a positive grid value.
  return std::pair{gamma_deg_[size_t(std::max(first - 1, 0))] * kDegToRad,
                   gamma_deg_[size_t(std::min(last + 1, int(gamma_deg_.size()) - 1))] * kDegToRad};
}

}  // namespace rimu
