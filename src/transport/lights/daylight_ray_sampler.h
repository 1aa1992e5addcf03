// Rays of daylight entering the scene through its apertures: the light side of daylit points
// (transport/integrators/daylit_connection.h, docs/transport.md "Daylit points").
//
// Sources: distant lights (the sun) and lights at infinity with portals (a sky seen through windows). One is chosen
// with probability P_i ∝ the power it brings through the apertures: a sun's irradiance times the apertures' area
// projected along its axis, a sky's total_power_w (the power through its portals).
//
// A sun's ray: ω towards the sun drawn as its sample_li draws one (density p_ω: 1/Ω in the cone, the delta
// convention 1 for a sun of zero diameter), then a point uniform over the apertures' area projected along ω (an
// aperture by A_j |n_j·ω|, a point uniform on it). The ray leaves that point along −ω; the first surface that
// scatters is the daylit point y. Per unit projected area the start is uniform, 1/A⊥(ω), so y has the density
//   p(y, ω) = P_i · p_ω(ω) · |n_y·ω| · N(y, ω) / A⊥(ω),   A⊥(ω) = Σ_j A_j |n_j·ω|,
// per m² at y (and per sr for a sun of finite size), N the number of apertures the ray from y along +ω passes
// through (1 where they do not overlap as seen along ω). A sun's apertures: every portal of the scene's lights (a
// room's windows), else one disc of the scene's bounding-sphere radius facing ω, just outside the scene.
//
// A sky's ray: one of its portals by area, a point uniform on it, and ω cosine-distributed about the portal's
// normal on its outer side: the side away from a point known to be inside (the camera). Per unit of portal area and
// solid angle that is |n_j·ω| / (π ΣA); carried along the ray to y,
//   p(y, ω) = P_i · |n_y·ω| · N_i(y, ω) / (π ΣA_i),
// N_i counting the sky's own portals the ray from y along +ω leaves by (crosses towards their outer side). A portal
// whose plane holds the inside point has no outer side: ω is then drawn on either side (1/(2π) instead of 1/π for
// it). A wrong guess of the inside (a camera outside, looking in) wastes rays, it biases nothing. Its radiance is the
// sky's radiance_escaped(ω).
//
// Light that enters elsewhere is not lost: this technique's density is 0 for it, and next-event estimation and BSDF
// sampling carry it with MIS weights that then sum to one without this technique.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/geometry/vector.h"
#include "transport/lights/environment_portal.h"
#include "transport/lights/light.h"

namespace rimu {

class DistantLight;

class DaylightRaySampler {
 public:
  /// Sources among `lights` as above; `scene_centre` and `scene_radius_m` place the disc of suns without portals,
  /// `inside` says which side of a sky's portals is in (the camera's position). Empty when no source brings light
  /// through its apertures.
  DaylightRaySampler(const std::vector<std::unique_ptr<Light>>& lights, Vec3 scene_centre, float scene_radius_m,
                     Vec3 inside);

  bool empty() const { return sources_.empty(); }
  bool uses_portals() const { return !apertures_.empty(); }
  /// The power the sources bring through the apertures, in W (Σ of the powers the sources are chosen by).
  double total_power_w() const { return total_power_w_; }

  struct DaylightRay {
    int light = -1;        ///< index into the scene's lights
    Vec3 to_light;         ///< ω, unit, from the scene towards the light
    Vec3 origin;           ///< on an aperture; the ray travels along −ω
    float direction_pdf = 0.0f;  ///< a sun's p_ω (1 for a delta light, as its sample_li reports it); 0 for a sky
    SampledSpectrum radiance{0.0f};  ///< what arrives along ω: a sun's sample_li radiance (E for a delta sun)
    bool is_delta = false;           ///< a sun of zero diameter: BSDF sampling cannot reach it
  };
  /// A ray from five uniform numbers; std::nullopt where the chosen light gives no sample or no aperture faces ω.
  std::optional<DaylightRay> sample(const SampledWavelengths& lambda, float u_light, Vec2 u_direction,
                                    Vec2 u_aperture) const;

  /// p(y, ω) above for `light` (0 if it is not a source): `normal` y's geometric normal (either side),
  /// `direction_pdf` a sun's p_ω(ω) as its sample_li reports it (unused for a sky).
  float density(int light, Vec3 y, Vec3 normal, Vec3 to_light, float direction_pdf) const;

 private:
  struct Source {
    int light = -1;
    const Light* sky = nullptr;         ///< a sky (its portals are `portals`), or
    const DistantLight* sun = nullptr;  ///< a sun (the apertures are apertures_)
    const PortalSet* portals = nullptr;
    std::vector<Vec3> outward;          ///< per portal of a sky: its unit normal towards the outside, or zero (either)
    float portal_area_m2 = 0.0f;        ///< a sky's ΣA
    float probability = 0.0f;
  };
  float projected_area(Vec3 direction) const;                          // A⊥(ω) of the suns' apertures
  int crossings(Vec3 y, Vec3 to_light) const;                           // N(y, ω) for suns
  std::optional<DaylightRay> sample_sun(const Source& source, const SampledWavelengths& lambda, Vec2 u_direction,
                                        Vec2 u_aperture) const;
  std::optional<DaylightRay> sample_sky(const Source& source, const SampledWavelengths& lambda, Vec2 u_direction,
                                        Vec2 u_aperture) const;

  std::vector<Source> sources_;
  std::vector<int> source_of_light_;  // light index → index into sources_, or −1
  std::vector<PortalRectangle> apertures_;
  Vec3 centre_;
  float radius_ = 0.0f;
  double total_power_w_ = 0.0;
};

}  // namespace rimu
