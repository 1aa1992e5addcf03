#include "transport/lights/sky/cie_sky_light.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

namespace rimu {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// The sampling grid: φ × cos θ cells.
constexpr int kCellsPhi = 256, kCellsMu = 64;
// Share of the mean relative luminance added to every cell's weight (see the header).
constexpr double kLuminanceFloor = 1e-3;

std::array<double, 3> hemisphere_direction(double phi, double mu) {
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu};
}

}  // namespace

CieSkyIntegrals integrate_cie_sky(const CieSkyParameters& p, const std::array<double, 3>& sun_local, int n_phi,
                                  int n_mu) {
  // dω = dφ dμ: each midpoint stands for 2π/n_phi × 1/n_mu sr.
  const CieSkyLuminance luminance(p, sun_local);
  CieSkyIntegrals sums;
  for (int j = 0; j < n_mu; ++j) {
    const double mu = (j + 0.5) / n_mu;
    double row = 0.0;
    for (int i = 0; i < n_phi; ++i)
      row += luminance(hemisphere_direction(kTwoPi * (i + 0.5) / n_phi, mu));
    sums.solid_angle_sr += row;
    sums.cosine_weighted_sr += row * mu;
  }
  const double cell_sr = kTwoPi / (double(n_phi) * n_mu);
  sums.solid_angle_sr *= cell_sr;
  sums.cosine_weighted_sr *= cell_sr;
  return sums;
}

CieSkyLight::CieSkyLight(int type, Vec3 up, Vec3 sun_direction, LightSpectrum zenith_radiance,
                         std::optional<CieSkyIntegrals> integrals)
    : type_(type),
      parameters_(cie_sky_parameters(type)),
      frame_(Frame::from_normal(normalize(up))),
      zenith_radiance_(std::move(zenith_radiance)) {
  const Vec3 sun = frame_.to_local(normalize(sun_direction));
  const double norm = std::sqrt(double(sun.x) * sun.x + double(sun.y) * sun.y + double(sun.z) * sun.z);
  sun_local_ = {sun.x / norm, sun.y / norm, sun.z / norm};
  luminance_.emplace(parameters_, sun_local_);
  // The integrals depend on the sun's zenith angle only (the hemisphere is symmetric under rotation about up).
  integrals_ = integrals ? *integrals : integrate_cie_sky(parameters_, sun_local_);

  std::vector<double> weights(size_t(kCellsPhi) * kCellsMu);
  double mean = 0.0;
  for (int y = 0; y < kCellsMu; ++y)
    for (int x = 0; x < kCellsPhi; ++x) {
      double largest = 0.0;
      for (int j = 0; j <= 2; ++j)
        for (int i = 0; i <= 2; ++i) {
          // v = 1 − μ: row 0 is at the zenith. The horizon row's lower edge (μ = 0) is the limit from above.
          const double mu = std::max(1e-9, 1.0 - (y + 0.5 * j) / kCellsMu);
          const double phi = kTwoPi * (x + 0.5 * i) / kCellsPhi;
          largest = std::max(largest, (*luminance_)(hemisphere_direction(phi, mu)));
        }
      weights[size_t(y) * kCellsPhi + x] = largest;
      mean += largest;
    }
  mean /= double(weights.size());
  for (double& w : weights) w += kLuminanceFloor * mean;
  distribution_ = Distribution2D(weights, kCellsPhi, kCellsMu);
}

double CieSkyLight::relative_luminance(Vec3 direction) const {
  const Vec3 d = frame_.to_local(direction);
  return (*luminance_)({d.x, d.y, d.z});
}

Vec2 CieSkyLight::direction_to_uv(Vec3 direction) const {
  const Vec3 d = frame_.to_local(direction);
  const float below_one = std::nextafter(1.0f, 0.0f);
  float phi = std::atan2(d.y, d.x);
  if (phi < 0.0f) phi += float(kTwoPi);
  return {std::min(phi / float(kTwoPi), below_one), std::clamp(1.0f - d.z, 0.0f, below_one)};
}

Vec3 CieSkyLight::uv_to_direction(Vec2 uv) const {
  const auto d = hemisphere_direction(kTwoPi * uv.x, 1.0 - uv.y);
  return frame_.to_world({float(d[0]), float(d[1]), float(d[2])});
}

SampledSpectrum CieSkyLight::radiance_escaped(Vec3 direction, const SampledWavelengths& lambda) const {
  const double g = relative_luminance(direction);
  if (!(g > 0.0)) return SampledSpectrum(0.0f);
  return zenith_radiance_.sample(lambda) * Float4(float(g));
}

float CieSkyLight::pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit*) const {
  if (zenith_radiance_.is_black() || !(dot(wi, frame_.n) > 0.0f)) return 0.0f;
  if (!portals_.empty()) return portals_.pdf(ref.position, wi);
  const float pdf = distribution_.pdf(direction_to_uv(wi)) / float(kTwoPi);
  return std::isfinite(pdf) ? pdf : 0.0f;
}

std::optional<LightSample> CieSkyLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                  Vec2 u) const {
  if (zenith_radiance_.is_black()) return std::nullopt;
  LightSample s;
  if (!portals_.empty()) {
    const auto through = portals_.sample(ref.position, u);
    if (!through || !(dot(through->wi, frame_.n) > 0.0f)) return std::nullopt;  // below the horizon: no sky there
    s.wi = through->wi;
    s.pdf_solid_angle = through->pdf_sr;
    s.radiance = radiance_escaped(s.wi, lambda);
    return s;
  }
  // The density and radiance come from the returned direction, as pdf_li and radiance_escaped compute them, so a
  // BSDF-sampled ray along it gets the same numbers.
  s.wi = normalize(uv_to_direction(distribution_.sample(u).uv));
  s.pdf_solid_angle = pdf_li(ref, s.wi);
  if (!(s.pdf_solid_angle > 0.0f)) return std::nullopt;
  s.radiance = radiance_escaped(s.wi, lambda);
  return s;
}

double CieSkyLight::portal_radiance_w_m2_sr() const {
  return zenith_radiance_.integral_360_830() * integrals_.cosine_weighted_sr / std::numbers::pi;
}

std::optional<LightBounds> CieSkyLight::part_bounds(int part) const {
  if (part != 0) return std::nullopt;
  return portal_light_bounds(portals_, portal_radiance_w_m2_sr());
}

double CieSkyLight::total_power_w(double scene_radius_m) const {
  if (!portals_.empty()) return std::numbers::pi * portals_.total_area_m2() * portal_radiance_w_m2_sr();
  return std::numbers::pi * scene_radius_m * scene_radius_m * zenith_radiance_.integral_360_830() *
         integrals_.solid_angle_sr;
}

}  // namespace rimu
