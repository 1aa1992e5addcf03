#include "transport/media/noise_cloud_medium.h"

#include <algorithm>
#include <cmath>

#include "spectral/error.h"
#include "transport/geometry/ray_box_clip.h"
#include "transport/textures/perlin_noise.h"

namespace rimu {

namespace {
// The noise's gradient by forward differences over `step` (what pbrt-v4's displacement uses, not the analytic one).
// The four noise values in one perlin_noise4 call, each bit for bit the scalar call's (p + (step, 0, 0) etc.: adding
// 0 leaves a coordinate as it is).
Vec3 noise_gradient(Vec3 p) {
  constexpr float kStep = 0.01f;
  const Float4 n = perlin_noise4(Float4(p.x, p.x + kStep, p.x, p.x), Float4(p.y, p.y, p.y + kStep, p.y),
                                 Float4(p.z, p.z, p.z, p.z + kStep));
  const auto v = n.to_array();
  return Vec3{v[1] - v[0], v[2] - v[0], v[3] - v[0]} / kStep;
}
}  // namespace

NoiseCloudMedium::NoiseCloudMedium(SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m, float g,
                                   NoiseCloudShape shape, Vec3 bounds_min, Vec3 bounds_max,
                                   const std::optional<Transform>& world_from_medium)
    : unit_(std::move(sigma_a_per_m), std::move(sigma_s_per_m), g), shape_(shape), min_(bounds_min), max_(bounds_max) {
  for (float v : {shape.density, shape.wispiness, shape.frequency})
    if (!(v >= 0.0f) || !std::isfinite(v))
      throw InputError({}, "a noise cloud's density, wispiness and frequency must be finite and >= 0");
  const Vec3 extent = max_ - min_;
  if (!(extent.x > 0.0f && extent.y > 0.0f && extent.z > 0.0f)) throw InputError({}, "the medium's box is empty");
  if (world_from_medium) medium_from_world_ = box_from_world(*world_from_medium);
}

float NoiseCloudMedium::density_in_medium(Vec3 p) const {
  Vec3 q = p * shape_.frequency;
  if (shape_.wispiness > 0.0f) {
    float step = 0.05f * shape_.wispiness, frequency = 10.0f;
    for (int i = 0; i < 2; ++i, step *= 0.5f, frequency *= 1.99f) q = q + noise_gradient(q * frequency) * step;
  }
  // Five octaves at frequencies 1.99ⁱ, weighted 2⁻⁽ⁱ⁺¹⁾ and summed in the octaves' order.
  float octaves[5];
  perlin_octaves(q, 5, octaves);
  float sum = 0.0f, weight = 0.5f;
  for (int i = 0; i < 5; ++i, weight *= 0.5f) sum += weight * octaves[i];
  const float thinning = std::clamp((1.0f - p.y) * 4.5f * shape_.density * sum, 0.0f, 1.0f);
  return std::clamp(thinning + 2.0f * std::max(0.0f, 0.5f - p.y), 0.0f, 1.0f);
}

float NoiseCloudMedium::density(Vec3 p_world) const {
  const Vec3 p = medium_from_world_ ? medium_from_world_->point(p_world) : p_world;
  if (!(p.x >= min_.x && p.y >= min_.y && p.z >= min_.z && p.x <= max_.x && p.y <= max_.y && p.z <= max_.z))
    return 0.0f;
  return density_in_medium(p);
}

bool NoiseCloudMedium::clip(const Ray& world_ray, float t_max, float& t0, float& t1, Ray& medium_ray) const {
  // An affine map keeps the ray's parameter.
  medium_ray = world_ray;
  if (medium_from_world_) {
    medium_ray.origin = medium_from_world_->point(world_ray.origin);
    medium_ray.direction = medium_from_world_->vector(world_ray.direction);
  }
  return clip_ray_to_box(medium_ray, t_max, min_, max_, t0, t1);
}

}  // namespace rimu
