#include "transport/lights/area_light.h"
#include "transport/lights/lambertian_emission.h"

#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "transport/lights/light_warps.h"
#include "transport/sampling/spherical_triangle.h"

namespace rimu {

AreaLight::AreaLight(std::span<const Vec3> vertices_m, std::span<const uint32_t> indices, LightSpectrum radiance,
                     bool two_sided)
    : uniform_(std::move(radiance)), two_sided_(two_sided) {
  build_triangles(vertices_m, indices);
  set_weights();
}

AreaLight::AreaLight(std::span<const Vec3> vertices_m, std::span<const uint32_t> indices, TexturedEmission emission,
                     bool two_sided)
    : textured_(std::move(emission)), two_sided_(two_sided) {
  assert(textured_->triangle_count() == indices.size() / 3);
  build_triangles(vertices_m, indices);
  set_weights();
}

void AreaLight::build_triangles(std::span<const Vec3> vertices_m, std::span<const uint32_t> indices) {
  assert(indices.size() % 3 == 0);
  const size_t count = indices.size() / 3;
  triangles_.resize(count);
  for (size_t k = 0; k < count; ++k) {
    assert(indices[3 * k] < vertices_m.size() && indices[3 * k + 1] < vertices_m.size() &&
           indices[3 * k + 2] < vertices_m.size());
    Triangle& t = triangles_[k];
    t.v0 = vertices_m[indices[3 * k]];
    t.v1 = vertices_m[indices[3 * k + 1]];
    t.v2 = vertices_m[indices[3 * k + 2]];
    // The cross product in double: a 1e-4 m triangle has |e1 × e2| ~ 1e-8, a 1e5 m one ~ 1e10, both fine in
    // double, and collinear float vertices give exactly 0 rather than rounding noise.
    const double e1[3] = {double(t.v1.x) - t.v0.x, double(t.v1.y) - t.v0.y, double(t.v1.z) - t.v0.z};
    const double e2[3] = {double(t.v2.x) - t.v0.x, double(t.v2.y) - t.v0.y, double(t.v2.z) - t.v0.z};
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double twice_area = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (!(twice_area > 0.0) || !std::isfinite(twice_area)) {
      ++degenerate_count_;
      continue;
    }
    t.normal = Vec3(float(c[0] / twice_area), float(c[1] / twice_area), float(c[2] / twice_area));
    t.area_m2 = 0.5 * twice_area;
    area_m2_ += t.area_m2;
  }
}

void AreaLight::set_weights() {
  std::vector<double> weights(triangles_.size(), 0.0);
  if (uniform_) {
    // Uniform emission: by area alone (w_k = A_k), whatever L is.
    for (size_t k = 0; k < triangles_.size(); ++k) {
      triangles_[k].radiance_integral = uniform_->integral_360_830();
      weights[k] = triangles_[k].area_m2;
    }
    emits_ = !uniform_->is_black() && area_m2_ > 0.0;
  } else {
    double emitted = 0.0;  // Σ A_k · mean_k
    for (size_t k = 0; k < triangles_.size(); ++k) {
      if (triangles_[k].area_m2 == 0.0) continue;
      triangles_[k].radiance_integral = textured_->triangle_mean_radiance_integral(k);
      emitted += triangles_[k].area_m2 * triangles_[k].radiance_integral;
    }
    emits_ = emitted > 0.0 && std::isfinite(emitted);
    // The floor (textured_emission.h): a share of the whole light's mean, so no triangle with area is unchoosable.
    const double floor = emits_ ? TexturedEmission::kWeightFloor * emitted / area_m2_ : 0.0;
    for (size_t k = 0; k < triangles_.size(); ++k)
      if (triangles_[k].area_m2 > 0.0)
        weights[k] = triangles_[k].area_m2 * std::max(triangles_[k].radiance_integral, floor);
  }
  double centroid[3] = {};
  for (size_t k = 0; k < triangles_.size(); ++k) {
    const Triangle& t = triangles_[k];
    triangles_[k].weight = weights[k];
    total_weight_ += weights[k];
    centroid[0] += weights[k] * (double(t.v0.x) + t.v1.x + t.v2.x) / 3.0;
    centroid[1] += weights[k] * (double(t.v0.y) + t.v1.y + t.v2.y) / 3.0;
    centroid[2] += weights[k] * (double(t.v0.z) + t.v1.z + t.v2.z) / 3.0;
  }
  if (total_weight_ > 0.0)
    weighted_centroid_m_ = Vec3(float(centroid[0] / total_weight_), float(centroid[1] / total_weight_),
                                float(centroid[2] / total_weight_));
  by_weight_ = Distribution1D(weights);
}

std::optional<Vec3> AreaLight::emission_centre_m(int part) const {
  if (!emits_ || !(total_weight_ > 0.0)) return std::nullopt;
  if (part < 0) return weighted_centroid_m_;
  if (part >= triangle_count() || triangles_[size_t(part)].area_m2 == 0.0) return std::nullopt;
  const Triangle& t = triangles_[size_t(part)];
  return (t.v0 + t.v1 + t.v2) * (1.0f / 3.0f);
}

SampledSpectrum AreaLight::emitted(size_t k, Vec3 barycentric, const SampledWavelengths& lambda) const {
  if (uniform_) return uniform_->sample(lambda);
  return textured_->radiance(textured_->uv_at(k, barycentric), lambda);
}

namespace {
/// Barycentrics (b0, b1, b2) of a point in (or, up to rounding, near) triangle (v0, v1, v2): the least-squares solution
/// of p − v0 = b1 e1 + b2 e2 in double, clamped to the triangle.
Vec3 barycentric_in(Vec3 v0, Vec3 v1, Vec3 v2, Vec3 p) {
  const double e1[3] = {double(v1.x) - v0.x, double(v1.y) - v0.y, double(v1.z) - v0.z};
  const double e2[3] = {double(v2.x) - v0.x, double(v2.y) - v0.y, double(v2.z) - v0.z};
  const double d[3] = {double(p.x) - v0.x, double(p.y) - v0.y, double(p.z) - v0.z};
  const auto dot3 = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const double d11 = dot3(e1, e1), d12 = dot3(e1, e2), d22 = dot3(e2, e2), p1 = dot3(d, e1), p2 = dot3(d, e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0) || !std::isfinite(det)) return {1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f};
  double b1 = std::max(0.0, (d22 * p1 - d12 * p2) / det), b2 = std::max(0.0, (d11 * p2 - d12 * p1) / det);
  if (b1 + b2 > 1.0) {
    const double s = b1 + b2;
    b1 /= s;
    b2 /= s;
  }
  return {float(1.0 - b1 - b2), float(b1), float(b2)};
}
}  // namespace

Vec3 AreaLight::barycentric_of(const Triangle& t, Vec3 point) { return barycentric_in(t.v0, t.v1, t.v2, point); }

bool AreaLight::samples_solid_angle(const Triangle& t, Vec3 reference) {
  // A_k / d² against the centroid: a function of (triangle, reference) alone, so sampling and pdf agree on it.
  const Vec3 centroid = (t.v0 + t.v1 + t.v2) / 3.0f;
  return t.area_m2 > kSolidAngleSamplingRatio * double(length_squared(centroid - reference));
}

float AreaLight::triangle_pdf(const Triangle& t, Vec3 reference, Vec3 wi, float distance_squared) const {
  const float cos_light = -dot(t.normal, wi);  // between the normal and y → x
  if (!two_sided_ && !(cos_light > 0.0f)) return 0.0f;
  double pdf = 0.0;
  if (samples_solid_angle(t, reference)) {
    const double omega = spherical_triangle_solid_angle(reference, t.v0, t.v1, t.v2);
    if (!(omega > 0.0)) return 0.0f;
    pdf = 1.0 / omega;
  } else {
    pdf = double(distance_squared) / (t.area_m2 * std::fabs(double(cos_light)));
  }
  if (!(pdf > 0.0) || !std::isfinite(pdf) || pdf > double(std::numeric_limits<float>::max())) return 0.0f;
  return float(pdf);
}

std::optional<LightSample> AreaLight::sample_triangle(size_t k, const LightReference& ref,
                                                      const SampledWavelengths& lambda, Vec2 u, double choice) const {
  const Triangle& t = triangles_[k];
  LightSample s;
  Vec3 barycentric{1.0f / 3.0f, 1.0f / 3.0f, 1.0f / 3.0f};  // where on t the sample lies (an image needs it)
  if (samples_solid_angle(t, ref.position)) {
    // Behind a one-sided triangle nothing arrives; say so before sampling (triangle_pdf would say 0 anyway).
    if (!two_sided_ && !(dot(t.normal, ref.position - t.v0) > 0.0f)) return std::nullopt;
    double omega = 0.0;
    const std::optional<Vec3> wi = sample_spherical_triangle(ref.position, t.v0, t.v1, t.v2, u, &omega);
    if (!wi) return std::nullopt;
    // The point where wi meets the triangle's plane (inside the triangle up to rounding).
    const float along = dot(t.normal, *wi);
    const float distance = dot(t.normal, t.v0 - ref.position) / along;
    if (!(distance > 0.0f) || !std::isfinite(distance)) return std::nullopt;
    s.wi = *wi;
    s.distance = distance;
    // triangle_pdf's value without computing Ω again (the same function of the same corners gave omega): 1/Ω, 0
    // behind a one-sided triangle.
    if (!two_sided_ && !(-dot(t.normal, s.wi) > 0.0f)) return std::nullopt;
    const double pdf = 1.0 / omega;
    if (!(pdf > 0.0) || !std::isfinite(pdf) || pdf > double(std::numeric_limits<float>::max())) return std::nullopt;
    s.pdf_solid_angle = float(choice * double(float(pdf)));
    if (textured_) barycentric = barycentric_of(t, ref.position + s.wi * s.distance);
  } else {
    const Vec3 b = sample_uniform_triangle(u);
    barycentric = b;
    const Vec3 point = t.v0 * b.x + t.v1 * b.y + t.v2 * b.z;
    const Vec3 to_light = point - ref.position;
    const float distance_squared = length_squared(to_light);
    if (!(distance_squared > 0.0f) || !std::isfinite(distance_squared)) return std::nullopt;
    s.distance = std::sqrt(distance_squared);
    s.wi = to_light / s.distance;
    s.pdf_solid_angle = float(choice * double(triangle_pdf(t, ref.position, s.wi, distance_squared)));
  }
  if (!(s.pdf_solid_angle > 0.0f) || !std::isfinite(s.pdf_solid_angle)) return std::nullopt;
  s.radiance = emitted(k, barycentric, lambda);
  s.normal = t.normal;
  return s;
}

std::optional<LightSample> AreaLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                Vec2 u) const {
  if (by_weight_.is_zero() || !emits_) return std::nullopt;
  const auto pick = by_weight_.sample_discrete(u.x);
  const Triangle& t = triangles_[pick.index];
  return sample_triangle(size_t(pick.index), ref, lambda, {pick.u_remapped, u.y}, t.weight / total_weight_);
}

std::optional<LightSample> AreaLight::sample_part_li(int part, const LightReference& ref,
                                                     const SampledWavelengths& lambda, Vec2 u) const {
  if (part == -1) return sample_li(ref, lambda, u);
  if (part < 0 || part >= triangle_count() || !emits_) return std::nullopt;
  if (triangles_[size_t(part)].area_m2 == 0.0) return std::nullopt;
  return sample_triangle(size_t(part), ref, lambda, u, 1.0);
}

float AreaLight::hit_pdf(size_t k, const LightReference& ref, Vec3 wi, const SurfaceHit* hit, bool whole_mesh) const {
  if (!hit || k >= triangles_.size() || by_weight_.is_zero() || !emits_) return 0.0f;
  const Triangle& t = triangles_[k];
  if (t.area_m2 == 0.0) return 0.0f;
  const float distance_squared = length_squared(hit->position - ref.position);
  if (!(distance_squared > 0.0f) || !std::isfinite(distance_squared)) return 0.0f;
  const float pdf = triangle_pdf(t, ref.position, wi, distance_squared);
  return whole_mesh ? float(double(pdf) * (t.weight / total_weight_)) : pdf;
}

float AreaLight::pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit) const {
  return hit ? hit_pdf(hit->primitive, ref, wi, hit, true) : 0.0f;
}

float AreaLight::pdf_part_li(int part, const LightReference& ref, Vec3 wi, const SurfaceHit* hit) const {
  if (part == -1) return pdf_li(ref, wi, hit);
  if (!hit || part < 0 || size_t(part) != size_t(hit->primitive)) return 0.0f;
  return hit_pdf(size_t(part), ref, wi, hit, false);
}

std::optional<LightBounds> AreaLight::part_bounds(int part) const {
  if (part < 0 || part >= triangle_count() || !emits_) return std::nullopt;
  const Triangle& t = triangles_[size_t(part)];
  if (t.area_m2 == 0.0) return std::nullopt;
  // An image's floored mean (w_k / A_k), so that a triangle the mean's grid saw as black is still found.
  const double radiance_integral = uniform_ ? t.radiance_integral : t.weight / t.area_m2;
  return triangle_light_bounds(t.v0, t.v1, t.v2, t.normal, t.area_m2, radiance_integral, two_sided_);
}

SampledSpectrum AreaLight::radiance(const SurfaceHit& hit, Vec3 w_out, const SampledWavelengths& lambda) const {
  if (hit.primitive >= triangles_.size()) return Float4(0.0f);
  const Triangle& t = triangles_[hit.primitive];
  if (t.area_m2 == 0.0 || (!two_sided_ && !(dot(t.normal, w_out) > 0.0f))) return Float4(0.0f);
  if (uniform_) return uniform_->sample(lambda);
  return textured_->radiance(hit.uv, lambda);
}

double AreaLight::total_power_w(double) const {
  const double sides = two_sided_ ? 2.0 : 1.0;
  if (uniform_) return sides * std::numbers::pi * area_m2_ * uniform_->integral_360_830();
  double power = 0.0;
  for (const Triangle& t : triangles_) power += t.area_m2 * t.radiance_integral;
  return sides * std::numbers::pi * power;
}

}  // namespace rimu

namespace rimu {

bool AreaLight::samples_emission() const { return uniform_.has_value() && emits_ && total_weight_ > 0.0; }

std::optional<EmissionSample> AreaLight::sample_emission(float u_part, Vec2 u_position, Vec2 u_direction,
                                                         const SampledWavelengths& lambda) const {
  if (!samples_emission()) return std::nullopt;
  // A triangle by area (the weights of uniform emission), a point uniform on it: p_A = 1/A over the whole light; a
  // two-sided light picks its side by the remapped choice number's half.
  const auto pick = by_weight_.sample_discrete(u_part);
  const Triangle& t = triangles_[size_t(pick.index)];
  if (t.area_m2 == 0.0) return std::nullopt;
  const Vec3 b = sample_uniform_triangle(u_position);
  EmissionSample sample = lambertian_emission(t.v0 * b.x + t.v1 * b.y + t.v2 * b.z, t.normal, two_sided_,
                                              pick.u_remapped < 0.5f, u_direction, uniform_->sample(lambda), area_m2_);
  sample.primitive = uint32_t(pick.index);
  return sample;
}

EmissionDensity AreaLight::emission_density(Vec3 normal, Vec3 direction) const {
  if (!samples_emission()) return {};
  return lambertian_emission_density(normal, direction, two_sided_, area_m2_);
}

}  // namespace rimu
