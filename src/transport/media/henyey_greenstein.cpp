#include "transport/media/henyey_greenstein.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/geometry/frame.h"

namespace rimu {
namespace {
// Below this |g| the inverse CDF below loses precision to cancellation (its 1/(2g) factor); the phase function
// then differs from isotropic by less than 3|g| relative, so the isotropic density is used for both sampling
// and evaluation (consistency between sample() and eval() is what MIS needs).
constexpr float kIsotropicG = 1e-3f;
}  // namespace

float henyey_greenstein(float cos_theta, float g) {
  constexpr float inv_4pi = float(0.25 * std::numbers::inv_pi);
  if (std::fabs(g) < kIsotropicG) return inv_4pi;
  const float denominator = 1.0f + g * g - 2.0f * g * cos_theta;
  return inv_4pi * (1.0f - g * g) / (denominator * std::sqrt(denominator));
}

HenyeyGreenstein::HenyeyGreenstein(float g) : g_(std::clamp(g, -0.99f, 0.99f)) {}

float HenyeyGreenstein::eval(Vec3 wo, Vec3 wi) const { return henyey_greenstein(-dot(wo, wi), g_); }

PhaseSample HenyeyGreenstein::sample(Vec3 wo, Vec2 u) const {
  // Inverse CDF in μ = cos θ: the CDF of HG in μ is P(μ) = (1 − g²)/(2g) · [(1 + g² − 2gμ)^{-1/2} − (1 + g)^{-1}],
  // whose inverse at ξ is μ = (1 + g² − ((1 − g²)/(1 − g + 2gξ))²) / (2g) (e.g. Pharr, Jakob, Humphreys,
  // "Physically Based Rendering", 4th ed., §11.3.1). ξ = u.x runs from μ = −1 (ξ = 0) to μ = 1 (ξ = 1).
  float mu;
  if (std::fabs(g_) < kIsotropicG) {
    mu = 2.0f * u.x - 1.0f;
  } else {
    const float s = (1.0f - g_ * g_) / (1.0f - g_ + 2.0f * g_ * u.x);
    mu = (1.0f + g_ * g_ - s * s) / (2.0f * g_);
  }
  mu = std::clamp(mu, -1.0f, 1.0f);
  const float sin_theta = std::sqrt(std::fmax(0.0f, 1.0f - mu * mu));
  const float phi = 2.0f * std::numbers::pi_v<float> * u.y;
  // θ is measured from the propagation direction −wo.
  const Frame frame = Frame::from_normal(-wo);
  const Vec3 wi = normalize(frame.to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), mu}));
  return {wi, henyey_greenstein(mu, g_)};
}

}  // namespace rimu
