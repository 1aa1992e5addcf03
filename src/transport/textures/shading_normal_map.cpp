#include "transport/textures/shading_normal_map.h"

#include <cmath>

#include "spectral/error.h"

namespace rimu {
namespace {

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The component of `v` orthogonal to unit `n`.
Vec3 tangential(Vec3 v, Vec3 n) { return v - n * dot(v, n); }

// sin² of 1e-3 rad: tangents closer than this to the normal give no usable direction.
constexpr float kMinTangentSin2 = 1e-6f;

}  // namespace

Vec3 keep_above_surface(Vec3 n, Vec3 ng) {
  const float c = dot(n, ng);
  if (c >= kMinPerturbedCosine) return n;
  // The same tangential direction at exactly the minimum cosine; straight down has none left: ng itself.
  const Vec3 along = n - ng * c;
  const float along_length = length(along);
  if (!(along_length > 1e-6f)) return ng;
  const float sin_min = std::sqrt(1.0f - kMinPerturbedCosine * kMinPerturbedCosine);
  return along * (sin_min / along_length) + ng * kMinPerturbedCosine;
}

Vec3 map_tangent_normal(Vec3 ns, Vec3 ng, Vec3 dpdu, Vec3 tangent_normal) {
  const Vec3 s_raw = tangential(dpdu, ns);
  const float s2 = dot(s_raw, s_raw);
  if (!(s2 > kMinTangentSin2 * dot(dpdu, dpdu)) || !finite(s_raw)) return ns;
  const float len2 = dot(tangent_normal, tangent_normal);
  if (!(len2 > 0.0f) || !std::isfinite(len2)) return ns;
  const Vec3 s = s_raw / std::sqrt(s2);
  const Vec3 t = cross(ns, s);
  const Vec3 n = normalize(s * tangent_normal.x + t * tangent_normal.y + ns * tangent_normal.z);
  if (!finite(n)) return ns;
  return keep_above_surface(n, ng);
}

Vec2 bump_steps_uv(const MaterialContext& context) {
  float du = 0.5f * (std::fabs(context.duvdx.x) + std::fabs(context.duvdy.x));
  float dv = 0.5f * (std::fabs(context.duvdx.y) + std::fabs(context.duvdy.y));
  if (!(du > 0.0f) || !std::isfinite(du)) du = kBumpStepUv;
  if (!(dv > 0.0f) || !std::isfinite(dv)) dv = kBumpStepUv;
  return {du, dv};
}

Vec3 bump_normal(const MaterialContext& context, const FloatTexture& displacement) {
  const Vec3 ns = context.shading_normal;
  const Vec3 dpdu = tangential(context.dpdu, ns), dpdv = tangential(context.dpdv, ns);
  const Vec3 unbumped = cross(dpdu, dpdv);
  const float area2 = dot(unbumped, unbumped);
  // Parallel or zero tangents (within 1e-3 rad): no surface parametrisation to difference along.
  if (!(area2 > kMinTangentSin2 * dot(dpdu, dpdu) * dot(dpdv, dpdv)) || !finite(unbumped)) return ns;

  const Vec2 step = bump_steps_uv(context);
  const float d = displacement.evaluate(context);
  MaterialContext shifted = context;
  shifted.position = context.position + context.dpdu * step.x;
  shifted.uv = {context.uv.x + step.x, context.uv.y};
  const float d_u = displacement.evaluate(shifted);
  shifted.position = context.position + context.dpdv * step.y;
  shifted.uv = {context.uv.x, context.uv.y + step.y};
  const float d_v = displacement.evaluate(shifted);

  const Vec3 bumped_dpdu = dpdu + ns * ((d_u - d) / step.x);
  const Vec3 bumped_dpdv = dpdv + ns * ((d_v - d) / step.y);
  Vec3 n = normalize(cross(bumped_dpdu, bumped_dpdv));
  if (!finite(n)) return ns;
  if (dot(unbumped, ns) < 0.0f) n = -n;  // uv axes of the other handedness: keep the normal's side
  return keep_above_surface(n, context.geometric_normal);
}

std::shared_ptr<const ShadingNormalModifier> ShadingNormalModifier::normal_map(
    std::shared_ptr<const TangentNormalTexture> map) {
  if (!map) throw InputError({}, "a normal map needs an image");
  auto modifier = std::make_shared<ShadingNormalModifier>();
  modifier->normal_map_ = std::move(map);
  return modifier;
}

std::shared_ptr<const ShadingNormalModifier> ShadingNormalModifier::bump(FloatTexturePtr displacement) {
  if (!displacement) throw InputError({}, "a bump map needs a displacement texture");
  auto modifier = std::make_shared<ShadingNormalModifier>();
  modifier->displacement_ = std::move(displacement);
  return modifier;
}

Vec3 ShadingNormalModifier::shading_normal(const MaterialContext& context) const {
  if (normal_map_)
    return map_tangent_normal(context.shading_normal, context.geometric_normal, context.dpdu,
                              normal_map_->evaluate(context.uv));
  return bump_normal(context, *displacement_);
}

}  // namespace rimu
