#include "transport/media/equiangular_sampling.h"

#include <algorithm>
#include <cmath>

namespace rimu {

std::optional<EquiangularSegment::Frame> EquiangularSegment::frame() const {
  const Vec3 to_light = light_m - origin;
  const float delta = dot(to_light, direction);
  const float h = length(to_light - direction * delta);
  // h = 0: the light lies on the ray's line, where ∫ dt/r² diverges; no equiangular density exists.
  if (!(h > 0.0f) || !std::isfinite(h) || !(t1 > t0)) return std::nullopt;
  // atan2 keeps θ in (−π/2, π/2) for h > 0, and t1 = 1e30 simply gives θ1 → π/2.
  const float theta0 = std::atan2(t0 - delta, h), theta1 = std::atan2(t1 - delta, h);
  if (!(theta1 > theta0)) return std::nullopt;
  return Frame{delta, h, theta0, theta1};
}

std::optional<EquiangularSegment::Sample> EquiangularSegment::sample(float u) const {
  const auto f = frame();
  if (!f) return std::nullopt;
  // θ uniform in [θ0, θ1]; t = Δ + h tan θ; dt/dθ = h / cos²θ = (h² + (t − Δ)²)/h, so p(t) = 1/((θ1 − θ0) dt/dθ).
  const float theta = f->theta0 + u * (f->theta1 - f->theta0);
  const float t = std::clamp(f->delta + f->h * std::tan(theta), t0, t1);
  const float x = t - f->delta;
  const float pdf = f->h / ((f->theta1 - f->theta0) * (f->h * f->h + x * x));
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;
  return Sample{t, pdf};
}

float EquiangularSegment::pdf(float t) const {
  if (!(t >= t0 && t <= t1)) return 0.0f;
  const auto f = frame();
  if (!f) return 0.0f;
  const float x = t - f->delta;
  return f->h / ((f->theta1 - f->theta0) * (f->h * f->h + x * x));
}

float distance_technique_density(const MediumCoefficients& c, DistanceSampling mode, float s_m,
                                 const SampledSpectrum& ratios) {
  const Float4 sigma_t = c.sigma_t_per_m();
  switch (mode) {
    case DistanceSampling::spectral_mis:
      // Each lane's own technique: σ_t,k e^{−σ_t,k s}, weighted by R_k (a lane with σ_t = 0 never scatters).
      return sum(ratios * sigma_t * exp(-sigma_t * Float4(s_m)));
    case DistanceSampling::hero_only:
      return sum(ratios) * sigma_t[0] * std::exp(-sigma_t[0] * s_m);
    case DistanceSampling::averaged: {
      const float mean = 0.25f * sum(sigma_t);
      return sum(ratios) * mean * std::exp(-mean * s_m);
    }
    case DistanceSampling::spectral_tracking:
      break;
  }
  return 0.0f;  // not combined with equiangular sampling (the integrator does not call it for trackers)
}

}  // namespace rimu
