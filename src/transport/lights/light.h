// The interface every light implements (see light_sample.h for the sampling contract).
//
// Representation: a small class hierarchy with virtual calls, not a std::variant. A scene has few lights, a
// light call costs one indirect branch next to a shadow ray (hundreds of ns), and virtual calls let the render
// side add light types (IES goniometric lights, issue 5) without touching a central variant. Lights are
// immutable after construction and shared read-only between threads.
//
// Directions and sides:
// - sample_li / pdf_li take wi FROM the reference point TOWARDS the light.
// - radiance() is asked with w_out pointing FROM the light's surface TOWARDS the receiver (−ray direction).
// - radiance_escaped() is asked with the escaping ray's own direction (from the scene towards infinity).
#pragma once

#include <optional>

#include "transport/lights/light_bounds.h"
#include "transport/lights/light_spectrum.h"
#include "transport/lights/light_sample.h"
#include "transport/geometry/surface_hit.h"

namespace rimu {

class PortalSet;  // transport/lights/environment_portal.h

/// A ray of a light's emission, for light tracing (transport/integrators/caustic_light_tracer.h).
struct EmissionSample {
  Vec3 origin_m;           ///< on the light (on its surface for an emitter with area; not offset)
  Vec3 direction;          ///< unit, away from the light
  Vec3 normal{};           ///< the emitting surface's normal at the origin, on the emitting side; zero for a point
  /// L_e·|cos θ| / (p_A·p_ω) per lane (a light at a point: I(ω)/p_ω), in W/nm: its mean over the samples is the
  /// light's spectral power Φ(λ).
  SampledSpectrum weight;
  /// p_A: the density of origin_m over the light's surface (per m², the side's choice included for a two-sided
  /// emitter); 1 for a light at a point. The bidirectional integrator's MIS weights read it (and p_ω).
  float pdf_position = 1.0f;
  /// p_ω: the solid-angle density of `direction` given the origin.
  float pdf_direction = 0.0f;
  /// The emitting triangle (SurfaceHit::primitive) of a mesh light; 0 for other lights.
  uint32_t primitive = 0;
};

/// The densities Light::sample_emission has for a ray it could have drawn (Light::emission_density).
struct EmissionDensity {
  float position = 0.0f;   ///< p_A, as EmissionSample::pdf_position
  float direction = 0.0f;  ///< p_ω, as EmissionSample::pdf_direction
};

class Light {
 public:
  virtual ~Light() = default;

  /// A direction towards the light with its solid-angle density (wavelength-independent) and the radiance that
  /// arrives along it, per lane. std::nullopt when the light cannot contribute at `ref` (reference on the light,
  /// behind a one-sided emitter, grazing so the density would be infinite, black light). Never returns a sample
  /// with a zero, infinite or NaN density.
  virtual std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                               Vec2 u) const = 0;

  /// The solid-angle density with which sample_li(ref, ...) would produce wi. `hit` is where the ray along wi
  /// met this light (area lights need it; lights at infinity ignore it and accept nullptr). 0 for delta lights,
  /// and 0 wherever sample_li would return std::nullopt.
  virtual float pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit = nullptr) const = 0;

  /// Radiance leaving a point of an area light towards w_out (unit, away from the surface). 0 for other lights.
  virtual SampledSpectrum radiance(const SurfaceHit& hit, Vec3 w_out, const SampledWavelengths& lambda) const;

  /// Radiance arriving from infinity along −direction, for a ray that escaped the scene along `direction`
  /// (unit). Nonzero only for lights at infinity (environment, distant lights with an angular size).
  virtual SampledSpectrum radiance_escaped(Vec3 direction, const SampledWavelengths& lambda) const;

  /// Radiant power in W over 360-830 nm (∫Φ_λ dλ), for picking lights by power. Lights at infinity count the
  /// power that crosses a disc (distant) or enters a sphere (environment) of radius `scene_radius_m` around the
  /// scene; finite lights ignore the radius.
  virtual double total_power_w(double scene_radius_m) const = 0;

  /// The one spectrum everything the light emits has (its spectral power is this times a factor independent of λ),
  /// or nullptr when the spectrum varies over the light (an environment image). The scene's wavelength density
  /// (transport/lights/emission_wavelength_density.h) is built from it. The pointer lives as long as the light.
  virtual const LightSpectrum* emitted_spectrum() const { return nullptr; }

  /// True if sample_li returns delta samples (point, spot, distant of zero diameter): no MIS with BSDF sampling.
  virtual bool is_delta() const { return false; }
  /// The point the emission of `part` (−1: the whole light) gathers around, which equiangular sampling in media aims
  /// at (transport/integrators/volumetric_equiangular.cpp): a point, spot, projector's or luminaire's position, an
  /// emitting triangle's centroid (a mesh's, weighted by emission, for part −1), a sphere's centre. std::nullopt
  /// for lights at infinity and parts that emit nothing. Any point is unbiased there; a central one makes the
  /// technique's 1/d² match the light's.
  virtual std::optional<Vec3> emission_centre_m(int /*part*/) const { return std::nullopt; }
  /// True if the light is at infinity (radiance_escaped may be nonzero).
  virtual bool is_infinite() const { return false; }
  /// For a light at infinity with portals (the windows it enters by), those portals; nullptr otherwise. Sun rays use
  /// them as the scene's apertures (transport/lights/daylight_ray_sampler.h).
  virtual const PortalSet* portal_set() const { return nullptr; }
  /// For a light at infinity whose light arrives from a small cone of directions (a distant light: the sun), which
  /// only light sampling finds (a BSDF-sampled ray hardly ever hits it): its irradiance at normal incidence ∫E⊥ dλ
  /// over 360-830 nm (W/m², unoccluded). std::nullopt for every other light, environments and skies included (BSDF
  /// sampling finds those). The light tree splits the light samples between itself and such lights by it
  /// (bvh_light_sampler.h, "Lights at infinity").
  virtual std::optional<float> directional_irradiance_w_m2() const { return std::nullopt; }
  /// False for a light that next-event estimation leaves to BSDF and phase sampling (a constant environment, when
  /// the integrator combines both: EnvironmentLight::set_combined_with_bsdf_sampling): the light samplers never choose it,
  /// sample_li gives nothing and pdf_li is 0, so a sampled ray that escapes to it counts with MIS weight 1.
  virtual bool sampled_by_nee() const { return true; }

  /// Whether sample_emission draws rays of this light (lights at a point, uniform emitting triangles and spheres);
  /// the others (lights at infinity, projectors, image emission, luminaires with an opening) are not light-traced.
  virtual bool samples_emission() const { return false; }
  /// A ray of emission: a part by power (u_part), a point on it (u_position), a direction (u_direction), with the
  /// weight of EmissionSample. std::nullopt where nothing is emitted, or for lights that do not sample emission.
  virtual std::optional<EmissionSample> sample_emission(float /*u_part*/, Vec2 /*u_position*/, Vec2 /*u_direction*/,
                                                        const SampledWavelengths& /*lambda*/) const {
    return std::nullopt;
  }
  /// The densities sample_emission has for a ray leaving the light along `direction` from a point of it whose
  /// emitting side's normal is `normal` (zero for a light at a point); zero for lights that do not sample emission
  /// and directions they never draw. The caller asks only for points and directions that emit.
  virtual EmissionDensity emission_density(Vec3 /*normal*/, Vec3 /*direction*/) const { return {}; }

  // Parts. A light sampler may choose the parts of a light separately: the triangles of an emissive mesh (part k
  // is triangle k, SurfaceHit::primitive). Every other light is one part, and these default to the whole light.

  /// The number of parts (≥ 1).
  virtual int part_count() const { return 1; }
  /// sample_li restricted to `part`: its solid-angle density is that of the part alone (for a triangle k,
  /// d²/(A_k |cos θ_l|)), so the sampler's probability of the part times it is the density of the whole choice.
  /// Part −1 is the whole light (sample_li, pdf_li), for samplers that choose whole lights.
  virtual std::optional<LightSample> sample_part_li(int part, const LightReference& ref,
                                                    const SampledWavelengths& lambda, Vec2 u) const;
  /// sample_part_li with the same direction, density and distance from the same numbers, but a light whose
  /// radiance costs more than its direction may leave `radiance` unevaluated (radiance_pending set): for callers
  /// that trace the shadow ray first and call resolve_radiance only for samples that pass. Why: an environment
  /// image's radiance is a random texel upsampled from RGB to four wavelengths; in a dense cloud 60 % of the shadow
  /// rays from its scattering points end in the cloud (docs/benchmarks.md, "pbrt-v3 scenes", cloud's second
  /// round). Lights whose radiance comes with their sampling return sample_part_li's sample.
  virtual std::optional<LightSample> sample_part_li_deferred(int part, const LightReference& ref,
                                                             const SampledWavelengths& lambda, Vec2 u) const {
    return sample_part_li(part, ref, lambda, u);
  }
  /// Evaluates the radiance of a sample this light left pending (sample_part_li_deferred) for the same `lambda`;
  /// does nothing to a sample whose radiance is there.
  virtual void resolve_radiance(LightSample& /*sample*/, const SampledWavelengths& /*lambda*/) const {}
  /// The density sample_part_li(part, ref, ...) has for wi (0 where it would return std::nullopt).
  virtual float pdf_part_li(int part, const LightReference& ref, Vec3 wi, const SurfaceHit* hit = nullptr) const;
  /// Where the part can emit, for the light BVH (light_bounds.h); std::nullopt for lights at infinity (except an
  /// environment with portals: the portals) and for parts that emit nothing (black, degenerate triangles), which the
  /// BVH then never picks.
  virtual std::optional<LightBounds> part_bounds(int) const { return std::nullopt; }

  /// The light group this light's emission is credited to (an index into the scene's group names; see
  /// transport/integrators/light_group_radiance.h). 0 in a scene without groups. Set once at load time.
  int light_group() const { return light_group_; }
  void set_light_group(int group) { light_group_ = group; }

 private:
  int light_group_ = 0;
};

}  // namespace rimu
