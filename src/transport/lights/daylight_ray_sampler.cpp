#include "transport/lights/daylight_ray_sampler.h"

#include <cmath>
#include <numbers>

#include "transport/geometry/frame.h"
#include "transport/lights/distant_light.h"
#include "transport/sampling/direction_warps.h"

namespace rimu {

namespace {

// One of `count` items picked with probability weight(j) / total (total = Σ weight(j) > 0), and u's place within
// the item's share, in [0, 1): the same number then serves as a coordinate on the item (as pbrt's
// SampleDiscrete remaps it). Rounding that leaves u beyond the last share picks the last item.
struct WeightedPick {
  size_t index = 0;
  float u_within = 0.5f;
};
template <class Weight>
WeightedPick pick_by_weight(size_t count, const Weight& weight, float total, float u_fraction) {
  float u = u_fraction * total;
  for (size_t j = 0; j < count; ++j) {
    const float w = weight(j);
    if (u < w || j + 1 == count) return {j, w > 0.0f ? std::fmin(u / w, 0x1.fffffep-1f) : 0.5f};
    u -= w;
  }
  return {};
}

}  // namespace

DaylightRaySampler::DaylightRaySampler(const std::vector<std::unique_ptr<Light>>& lights, Vec3 scene_centre,
                                       float scene_radius_m, Vec3 inside)
    : source_of_light_(lights.size(), -1), centre_(scene_centre), radius_(scene_radius_m) {
  for (const auto& light : lights)
    if (const PortalSet* portals = light->portal_set())
      for (const PortalRectangle& portal : portals->portals()) apertures_.push_back(portal);
  double total = 0.0;
  std::vector<double> powers;
  for (size_t i = 0; i < lights.size(); ++i) {
    Source source;
    source.light = int(i);
    double power = 0.0;
    if (const auto* distant = dynamic_cast<const DistantLight*>(lights[i].get())) {
      const std::optional<float> irradiance = lights[i]->directional_irradiance_w_m2();
      if (!irradiance) continue;
      source.sun = distant;
      power = double(*irradiance) * double(projected_area(distant->axis()));
    } else if (const PortalSet* portals = lights[i]->portal_set(); portals && lights[i]->is_infinite()) {
      source.sky = lights[i].get();
      source.portals = portals;
      source.portal_area_m2 = float(portals->total_area_m2());
      for (const PortalRectangle& p : portals->portals()) {
        // The inside point's distance from the plane, against the rounding of the corner's coordinates.
        const float side = dot(inside - p.corner, p.normal());
        const float tolerance = 1e-6f * (max_component(abs(p.corner)) + max_component(abs(inside)) + 1e-3f);
        source.outward.push_back(std::fabs(side) <= tolerance ? Vec3{} : side > 0.0f ? -p.normal() : p.normal());
      }
      power = lights[i]->total_power_w(double(scene_radius_m));
    }
    if (!(power > 0.0) || !std::isfinite(power)) continue;
    sources_.push_back(source);
    powers.push_back(power);
    total += power;
  }
  total_power_w_ = total;
  for (size_t k = 0; k < sources_.size(); ++k) {
    sources_[k].probability = float(powers[k] / total);
    source_of_light_[size_t(sources_[k].light)] = int(k);
  }
}

float DaylightRaySampler::projected_area(Vec3 direction) const {
  if (apertures_.empty()) return std::numbers::pi_v<float> * radius_ * radius_;
  double area = 0.0;
  for (const PortalRectangle& p : apertures_) area += p.area_m2() * std::fabs(double(dot(p.normal(), direction)));
  return float(area);
}

int DaylightRaySampler::crossings(Vec3 y, Vec3 to_light) const {
  if (apertures_.empty()) {
    // The disc sits at centre + r·ω; every point within the bounding sphere projects inside it.
    const Vec3 offset = y - centre_;
    const float along = dot(offset, to_light);
    const Vec3 across = offset - to_light * along;
    return along < radius_ && dot(across, across) <= radius_ * radius_ ? 1 : 0;
  }
  int n = 0;
  for (const PortalRectangle& p : apertures_) n += passes_through(p, y, to_light) ? 1 : 0;
  return n;
}

std::optional<DaylightRaySampler::DaylightRay> DaylightRaySampler::sample(const SampledWavelengths& lambda,
                                                                          float u_light, Vec2 u_direction,
                                                                          Vec2 u_aperture) const {
  if (sources_.empty()) return std::nullopt;
  size_t k = 0;
  for (float cumulative = sources_[0].probability; k + 1 < sources_.size() && u_light >= cumulative;)
    cumulative += sources_[++k].probability;
  const Source& source = sources_[k];
  return source.sun ? sample_sun(source, lambda, u_direction, u_aperture)
                    : sample_sky(source, lambda, u_direction, u_aperture);
}

std::optional<DaylightRaySampler::DaylightRay> DaylightRaySampler::sample_sun(const Source& source,
                                                                              const SampledWavelengths& lambda,
                                                                              Vec2 u_direction,
                                                                              Vec2 u_aperture) const {
  // Distant lights ignore the reference point.
  const auto ls = source.sun->sample_li(LightReference{}, lambda, u_direction);
  if (!ls) return std::nullopt;
  DaylightRay ray;
  ray.light = source.light;
  ray.to_light = ls->wi;
  ray.direction_pdf = ls->pdf_solid_angle;
  ray.radiance = ls->radiance;
  ray.is_delta = ls->is_delta;
  if (apertures_.empty()) {
    const Frame frame = Frame::from_normal(ls->wi);
    const float r = radius_ * std::sqrt(u_aperture.x), phi = 2.0f * std::numbers::pi_v<float> * u_aperture.y;
    ray.origin = centre_ + ls->wi * radius_ + frame.s * (r * std::cos(phi)) + frame.t * (r * std::sin(phi));
    return ray;
  }
  // An aperture by its projected area along ω, then a point uniform on it (uniform in projected area too).
  const float total = projected_area(ls->wi);
  if (!(total > 0.0f)) return std::nullopt;
  const WeightedPick pick = pick_by_weight(
      apertures_.size(),
      [&](size_t j) { return float(apertures_[j].area_m2()) * std::fabs(dot(apertures_[j].normal(), ls->wi)); },
      total, u_aperture.x);
  const PortalRectangle& p = apertures_[pick.index];
  ray.origin = p.corner + p.edge_a * pick.u_within + p.edge_b * u_aperture.y;
  return ray;
}

std::optional<DaylightRaySampler::DaylightRay> DaylightRaySampler::sample_sky(const Source& source,
                                                                              const SampledWavelengths& lambda,
                                                                              Vec2 u_direction,
                                                                              Vec2 u_aperture) const {
  const std::vector<PortalRectangle>& portals = source.portals->portals();
  const WeightedPick pick = pick_by_weight(
      portals.size(), [&](size_t j) { return float(portals[j].area_m2()); }, source.portal_area_m2, u_aperture.x);
  const size_t chosen = pick.index;
  const float s = pick.u_within;
  const PortalRectangle* portal = &portals[chosen];
  // A cosine-distributed direction about the portal's outer normal (either side where it has none).
  Vec3 normal = source.outward[chosen];
  float u_x = u_direction.x;
  if (normal == Vec3{}) {
    const bool back = u_direction.x >= 0.5f;
    u_x = std::fmin(back ? 2.0f * u_direction.x - 1.0f : 2.0f * u_direction.x, 0x1.fffffep-1f);
    normal = back ? -portal->normal() : portal->normal();
  }
  DaylightRay ray;
  ray.light = source.light;
  ray.to_light = normalize(Frame::from_normal(normal).to_world(sample_cosine_hemisphere({u_x, u_direction.y})));
  if (!(std::fabs(dot(ray.to_light, normal)) > 0.0f)) return std::nullopt;
  ray.origin = portal->corner + portal->edge_a * s + portal->edge_b * u_aperture.y;
  ray.radiance = source.sky->radiance_escaped(ray.to_light, lambda);
  return ray;
}

float DaylightRaySampler::density(int light, Vec3 y, Vec3 normal, Vec3 to_light, float direction_pdf) const {
  if (light < 0 || size_t(light) >= source_of_light_.size() || source_of_light_[size_t(light)] < 0) return 0.0f;
  const Source& source = sources_[size_t(source_of_light_[size_t(light)])];
  const float cos_y = std::fabs(dot(normal, to_light));
  if (source.sky) {
    // Σ over the portals the ray leaves by of the direction density's 1/π (1/(2π) for a portal with no outer side).
    float sides = 0.0f;
    const std::vector<PortalRectangle>& portals = source.portals->portals();
    for (size_t j = 0; j < portals.size(); ++j) {
      const Vec3 out = source.outward[j];
      if (out == Vec3{} ? true : dot(to_light, out) > 0.0f)
        if (passes_through(portals[j], y, to_light)) sides += out == Vec3{} ? 0.5f : 1.0f;
    }
    return source.probability * cos_y * sides / (std::numbers::pi_v<float> * source.portal_area_m2);
  }
  const int n = crossings(y, to_light);
  if (n == 0) return 0.0f;
  const float area = projected_area(to_light);
  if (!(area > 0.0f)) return 0.0f;
  return source.probability * direction_pdf * cos_y * float(n) / area;
}

}  // namespace rimu
