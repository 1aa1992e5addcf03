#include "render/scene/refracted_light_warning.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "transport/lights/light.h"
#include "transport/integrators/path_integrator.h"

namespace rimu {
namespace {

constexpr int kSamplesPerProbe = 4;  // a 2×2 grid of light samples
constexpr int kMaxSurfacesPerRay = 32;

enum class Reach { direct, through_refraction, blocked };

bool refracts(const Material& material) { return std::holds_alternative<DielectricMaterial>(material.variant()); }

// Follows a ray to the light: panes (shadow-ray passable) are passed, refracting surfaces noted and passed, anything
// else blocks.
Reach reach(const Scene& scene, Ray ray, std::string& refracting_material) {
  bool refracted = false;
  const Vec3 end = ray.origin + ray.direction * ray.t_max;
  for (int k = 0; k < kMaxSurfacesPerRay; ++k) {
    const std::optional<SurfaceHit> hit = scene.geometry.intersect(ray);
    if (!hit) return refracted ? Reach::through_refraction : Reach::direct;
    if (hit->material < 0) return Reach::blocked;
    const Material& material = scene.materials[size_t(hit->material)];
    if (refracts(material)) {
      refracted = true;
      if (refracting_material.empty() && size_t(hit->material) < scene.material_names.size())
        refracting_material = scene.material_names[size_t(hit->material)];
    } else if (!material.passes_shadow_rays()) {
      return Reach::blocked;
    }
    ray.origin = offset_ray_origin(*hit, ray.direction, scene.scene_scale);
    ray.t_min = 0.0f;
    if (!std::isinf(ray.t_max)) ray.t_max = dot(end - ray.origin, ray.direction);
    if (!(ray.t_max > 0.0f)) return refracted ? Reach::through_refraction : Reach::direct;
  }
  return Reach::blocked;
}

std::vector<LightReference> probe_points(const Scene& scene) {
  const Vec3 eye = scene.camera.camera_to_world.point({0, 0, 0});
  std::vector<LightReference> points{{eye, Vec3{}}};
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z) {
        if (x == 0 && y == 0 && z == 0) continue;
        Ray ray;
        ray.origin = eye;
        ray.direction = normalize(Vec3{float(x), float(y), float(z)});
        const std::optional<SurfaceHit> hit = scene.geometry.intersect(ray);
        if (!hit) continue;
        points.push_back({offset_ray_origin(*hit, -ray.direction, scene.scene_scale), Vec3{}});
      }
  return points;
}

}  // namespace

std::vector<std::string> refracted_light_warnings(const Scene& scene) {
  std::vector<std::string> out;
  if (scene.infinite_lights.empty() || !std::any_of(scene.materials.begin(), scene.materials.end(), refracts)) return out;
  const SampledWavelengths lambda(Float4(450.0f, 500.0f, 550.0f, 600.0f), Float4(1.0f));
  const std::vector<LightReference> points = probe_points(scene);
  for (int index : scene.infinite_lights) {
    const Light& light = *scene.lights[size_t(index)];
    int direct = 0, refracted = 0;
    std::string material;
    for (const LightReference& point : points)
      for (int s = 0; s < kSamplesPerProbe; ++s) {
        const Vec2 u{(float(s % 2) + 0.5f) / 2.0f, (float(s / 2) + 0.5f) / 2.0f};  // a 2×2 grid over the light
        const std::optional<LightSample> sample = light.sample_li(point, lambda, u);
        if (!sample || !(sample->pdf_solid_angle > 0.0f)) continue;
        Ray ray;
        ray.origin = point.position;
        ray.direction = sample->wi;
        ray.t_max = sample->distance;
        const Reach r = reach(scene, ray, material);
        direct += r == Reach::direct;
        refracted += r == Reach::through_refraction;
      }
    // Mostly through glass: a probe can sit where a grazing ray slips past a pane's edge (a point on the wall
    // beside a window, between the pane and the wall's plane), so a few unobstructed samples do not clear the light.
    if (refracted > 0 && 9 * direct <= refracted) {
      const std::string& name = size_t(index) < scene.light_names.size() ? scene.light_names[size_t(index)] : std::string("a light");
      out.push_back("light '" + name + "' is reached from the camera's surroundings only through refracting glass ('" +
                    material + "'): shadow rays stop at refracting surfaces, so its light arrives by BSDF sampling alone "
                    "(noisy; a small sun practically never). For a window pane use \"thin_dielectric\", which shadow "
                    "rays pass (docs/transport.md, \"Glazing\")");
    }
  }
  return out;
}

std::vector<std::string> unlit_medium_warnings(const nlohmann::json& document, const Scene& scene) {
  std::vector<std::string> warnings;
  const bool small_lights = std::any_of(scene.lights.begin(), scene.lights.end(), [](const auto& light) {
    return light->is_delta() || light->directional_irradiance_w_m2().has_value();
  });
  const auto media = document.find("media");
  const auto materials = document.find("materials");
  if (!small_lights || media == document.end() || !media->is_object() || materials == document.end()) return warnings;
  for (const auto& [name, medium] : media->items()) {
    if (!medium.is_object() || medium.value("index_matched", false)) continue;
    // Homogeneous media scatter when given an albedo or σ_s; grids always may.
    const bool scatters = medium.value("type", std::string()) != "homogeneous" || medium.contains("albedo") ||
                          medium.contains("sigma_s");
    const std::string boundary = medium.value("boundary_material", std::string());
    const auto material = materials->find(boundary);
    if (!scatters || material == materials->end() || !material->is_object()) continue;
    const bool smooth = !material->contains("roughness") ||
                        ((*material)["roughness"].is_number() && (*material)["roughness"].get<double>() == 0.0);
    const bool index_one = (*material).contains("ior") && (*material)["ior"].is_number() && (*material)["ior"] == 1.0;
    if (material->value("type", std::string()) == "dielectric" && smooth && !index_one &&
        !material->value("diffuse_entry", false))
      warnings.push_back("media/" + name + ": no light from the point, spot, ies, goniometric, projection, distant "
                         "or sun lights reaches inside it: its boundary material '" + boundary + "' is a smooth "
                         "refracting dielectric (shadow rays stop there, and no path can hit such a light); for skin, "
                         "wax or milk give '" + boundary + "' \"diffuse_entry\": true (docs/scene-format.md, "
                         "\"dielectric\")");
  }
  return warnings;
}

}  // namespace rimu
