#include "transport/lights/sphere_light.h"
#include "transport/lights/lambertian_emission.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "transport/geometry/frame.h"
#include "transport/lights/light_warps.h"
#include "spectral/math_constants.h"

namespace rimu {
namespace {


struct Vec3D {
  double x, y, z;
};
Vec3D to_double(Vec3 v) { return {v.x, v.y, v.z}; }
double dot3(Vec3D a, Vec3D b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// 1 − cos θmax of the cone a sphere of squared radius r² subtends at squared distance d² > r² from its centre, as
// sin²θmax/(1 + cos θmax): exact where 1 − √(1 − sin²θmax) would cancel (a far, small sphere).
double one_minus_cos_max(double r2, double d2) {
  const double sin2_max = r2 / d2;
  return sin2_max / (1.0 + std::sqrt(std::max(0.0, 1.0 - sin2_max)));
}

// A density as a float, or 0 if it is not a positive finite float.
float finite_density(double pdf) {
  if (!(pdf > 0.0) || !(pdf <= double(std::numeric_limits<float>::max()))) return 0.0f;
  return float(pdf);
}

}  // namespace

SphereLight::SphereLight(Vec3 centre_m, float radius_m, LightSpectrum radiance, bool two_sided)
    : centre_m_(centre_m), radius_m_(radius_m), radiance_(std::move(radiance)), two_sided_(two_sided) {
  assert(radius_m > 0.0f && std::isfinite(radius_m));
}

double SphereLight::area_m2() const { return 4.0 * kPi * double(radius_m_) * double(radius_m_); }

std::optional<LightSample> SphereLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                  Vec2 u) const {
  if (radiance_.is_black()) return std::nullopt;
  const Vec3D c = to_double(centre_m_), p = to_double(ref.position);
  const Vec3D from_centre{p.x - c.x, p.y - c.y, p.z - c.z};
  const double d2 = dot3(from_centre, from_centre), r = radius_m_, r2 = r * r;
  LightSample s;
  Vec3D y{}, n{};  // the sampled point and its outward normal
  if (d2 > r2) {
    // θ from the axis x → c, uniform in the cone: 1 − cos θ uniform on [0, 1 − cos θmax]. The point y is where the
    // direction first meets the sphere; α, the angle at c between c → x and c → y, follows from the triangle x c y:
    // sin(∠y) = (d/r) sin θ with ∠y obtuse (the near side), α = π − θ − ∠y, so
    // cos α = sin²θ/sin θmax + cos θ √(1 − sin²θ/sin²θmax).
    const double omc_max = one_minus_cos_max(r2, d2);
    const double omc = double(u.x) * omc_max;
    const double cos_theta = 1.0 - omc, sin2_theta = omc * (2.0 - omc);
    const double d = std::sqrt(d2), sin_max = r / d, sin2_max = r2 / d2;
    const double cos_alpha = std::clamp(
        sin2_theta / sin_max + cos_theta * std::sqrt(std::max(0.0, 1.0 - sin2_theta / sin2_max)), -1.0, 1.0);
    const double sin_alpha = std::sqrt(std::max(0.0, 1.0 - cos_alpha * cos_alpha));
    const double phi = 2.0 * kPi * double(u.y);
    const Vec3 axis = normalize(Vec3(float(from_centre.x / d), float(from_centre.y / d), float(from_centre.z / d)));
    const Frame frame = Frame::from_normal(axis);
    const double a = sin_alpha * std::cos(phi), b = sin_alpha * std::sin(phi);
    n = {a * frame.s.x + b * frame.t.x + cos_alpha * axis.x, a * frame.s.y + b * frame.t.y + cos_alpha * axis.y,
         a * frame.s.z + b * frame.t.z + cos_alpha * axis.z};
    s.pdf_solid_angle = finite_density(1.0 / (2.0 * kPi * omc_max));
  } else {
    // On or inside: only the inner side faces x, and it emits only if two-sided.
    if (!two_sided_) return std::nullopt;
    const Vec3 w = sample_uniform_sphere(u);
    n = to_double(w);
  }
  y = {c.x + r * n.x, c.y + r * n.y, c.z + r * n.z};
  const Vec3D to_light{y.x - p.x, y.y - p.y, y.z - p.z};
  const double distance2 = dot3(to_light, to_light);
  if (!(distance2 > 0.0) || !std::isfinite(distance2)) return std::nullopt;
  const double distance = std::sqrt(distance2);
  const Vec3D wi{to_light.x / distance, to_light.y / distance, to_light.z / distance};
  if (!(d2 > r2)) {
    // Area density 1/(4πr²) to solid angle: × d_y²/|cos θ_l|.
    const double cos_light = std::fabs(dot3(n, wi));
    s.pdf_solid_angle = finite_density(distance2 / (4.0 * kPi * r2 * cos_light));
  }
  if (s.pdf_solid_angle == 0.0f) return std::nullopt;
  s.wi = normalize(Vec3(float(wi.x), float(wi.y), float(wi.z)));
  s.distance = float(distance);
  s.normal = normalize(Vec3(float(n.x), float(n.y), float(n.z)));
  s.radiance = radiance_.sample(lambda);
  return s;
}

float SphereLight::pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit) const {
  if (radiance_.is_black()) return 0.0f;
  const Vec3D c = to_double(centre_m_), p = to_double(ref.position);
  // wi renormalised in double: a float unit vector's length is 1 only to ~1e-7, which would move b² − d² below by
  // ~1e-7·d², far more than r² for a far sphere.
  Vec3D w = to_double(wi);
  const double w_length = std::sqrt(dot3(w, w));
  if (!(w_length > 0.0)) return 0.0f;
  w = {w.x / w_length, w.y / w_length, w.z / w_length};
  const Vec3D from_centre{p.x - c.x, p.y - c.y, p.z - c.z};
  const double d2 = dot3(from_centre, from_centre), r = radius_m_, r2 = r * r;
  // The ray x + t·wi meets the sphere where t² + 2bt + (d² − r²) = 0, b = (x − c)·wi: discriminant b² − d² + r².
  const double b = dot3(from_centre, w);
  if (d2 > r2) {
    // In the cone iff the ray meets the sphere ahead (b < 0) with a non-negative discriminant; the density is the
    // cone's, whichever direction in it. A ray that hit the sphere is in it. Otherwise wi, a float unit vector, is
    // trusted to δ = 1e-6·d sideways at the centre (its direction is good to ~1e-7 rad), which moves the
    // discriminant r² − (distance of the line from c)² by up to 2rδ + δ²: a direction sample_li made at the
    // silhouette then still has its density.
    if (!(b < 0.0)) return 0.0f;
    if (!hit) {
      const double slack = 1e-6 * std::sqrt(d2);
      if (!(b * b - d2 + r2 >= -(2.0 * r * slack + slack * slack))) return 0.0f;
    }
    return finite_density(1.0 / (2.0 * kPi * one_minus_cos_max(r2, d2)));
  }
  if (!two_sided_) return 0.0f;
  // From inside, the ray leaves through the far root t = −b + √(b² − d² + r²); there |cos θ_l| = √(b² − d² + r²)/r
  // ((y − c)·wi = b + t).
  const double root = std::sqrt(std::max(0.0, b * b - d2 + r2));
  const double t = -b + root;
  return finite_density(t * t * r / (4.0 * kPi * r2 * root));
}

SampledSpectrum SphereLight::radiance(const SurfaceHit& hit, Vec3 w_out, const SampledWavelengths& lambda) const {
  if (!two_sided_ && !(dot(hit.geometric_normal, w_out) > 0.0f)) return Float4(0.0f);
  return radiance_.sample(lambda);
}

double SphereLight::total_power_w(double) const {
  return (two_sided_ ? 2.0 : 1.0) * kPi * area_m2() * radiance_.integral_360_830();
}

std::optional<LightBounds> SphereLight::part_bounds(int part) const {
  if (part != 0 || radiance_.is_black()) return std::nullopt;
  return sphere_light_bounds(centre_m_, radius_m_, radiance_.integral_360_830());
}

}  // namespace rimu

namespace rimu {

bool SphereLight::samples_emission() const { return !radiance_.is_black(); }

std::optional<EmissionSample> SphereLight::sample_emission(float u_part, Vec2 u_position, Vec2 u_direction,
                                                           const SampledWavelengths& lambda) const {
  if (radiance_.is_black()) return std::nullopt;
  // A point uniform on the area (p_A = 1/A); a two-sided sphere picks its side by u_part.
  const Vec3 outward = sample_uniform_sphere(u_position);
  return lambertian_emission(centre_m_ + outward * radius_m_, outward, two_sided_, u_part < 0.5f, u_direction,
                             radiance_.sample(lambda), area_m2());
}

EmissionDensity SphereLight::emission_density(Vec3 normal, Vec3 direction) const {
  if (radiance_.is_black()) return {};
  return lambertian_emission_density(normal, direction, two_sided_, area_m2());
}

}  // namespace rimu
