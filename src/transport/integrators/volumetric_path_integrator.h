// The path tracer for scenes with participating media: surfaces as in PathIntegrator, plus free flights,
// scattering and next-event estimation inside homogeneous and voxel-grid media (docs/media.md).
#pragma once

#include "transport/geometry/ray_differentials.h"

#include <vector>

#include "transport/media/equiangular_sampling.h"
#include "transport/media/medium.h"
#include "transport/integrators/path_integrator.h"
#include "transport/media/spectral_distance_sampling.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

/// A TransportScene plus its media. Non-owning, like TransportScene.
struct VolumetricScene {
  TransportScene surfaces;
  const std::vector<Medium>* media = nullptr;
  /// Indexed by material: the medium a shape of that material encloses, and whether its surface is index-matched.
  /// Materials beyond the end have no medium and a real surface.
  const std::vector<MediumBoundary>* boundaries = nullptr;
  /// The medium around the camera (camera paths start inside it; no boundary need enclose it), −1: vacuum.
  int camera_medium = -1;
};

/// Which lights equiangular sampling aims at (the scene key integrator.equiangular).
enum class EquiangularLights {
  off,
  /// Lights at a point (point, spot, projector, IES luminaire), where the 1/d² it cancels is sharpest. The default:
  /// it costs one more light connection per segment, which pays for these (docs/benchmarks.md).
  points,
  /// Every light not at infinity: also emitting triangles and spheres, by their centres. Lower noise in the glow
  /// around a softbox or bulb in haze; in a scene filled with haze where lights are large against the distances
  /// (a hazy Cornell box) the extra connection can cost more than it gains (docs/benchmarks.md).
  all,
};

struct VolumetricIntegratorSettings {
  PathIntegratorSettings path;  ///< max_depth counts surface interactions (and see below); RR counts all vertices
  /// Whether scattering events in media count towards path.max_depth too, as pbrt-v4's volpath counts them
  /// (the pbrt importer sets it for scenes with media). Either way a vertex at depth max_depth gets no next-event
  /// estimation and no direction: with it, max_depth 0 keeps no medium-scattered light, 1 single scattering.
  bool max_depth_includes_media = false;
  DistanceSampling distance = DistanceSampling::spectral_mis;
  /// A safety bound on scattering events per path (stuck-path guard; Russian roulette ends paths long before in
  /// any medium with albedo < 1). Paths reaching it end, which truncates at most the 10⁶th-order scattering.
  int max_medium_events = 1000000;
  /// Equiangular sampling on every homogeneous segment, combined with free-flight sampling + NEE by the balance
  /// heuristic (Kulla & Fajardo 2012; docs/media.md), towards the lights EquiangularLights says. Not used with
  /// spectral_tracking, in grid media, inside subsurface walks, or with direct_lighting = bsdf_only.
  EquiangularLights equiangular = EquiangularLights::points;
};

/// The free-flight technique a wavelength mode runs when the scene asks for `requested` (docs/media.md,
/// "Wavelength modes in media"). Spectral MIS over the lanes needs the hero to be a uniformly random member of a
/// symmetric lane set, which independent and rgb modes do not provide:
///   independent: spectral_mis → hero_only (no spectral MIS, like its surfaces); the other techniques unchanged;
///   rgb:         spectral_mis, hero_only → spectral_tracking. Lane 0 is always red there, so a hero density would
///                sample every path by red's σ_t; spectral tracking (Kutz et al. 2017, made for RGB media) is
///                lane-independent and bounded. averaged is lane-independent too and stays.
DistanceSampling distance_sampling_for(DistanceSampling requested, WavelengthMode mode);

/// Radiance along camera rays in scenes with media, per lane, with the same output contract as
/// PathIntegrator::radiance (lane j: this path's spectral-MIS-weighted estimate for λ_j).
///
/// Estimator (docs/transport.md and docs/media.md): throughput β = f/p(x̄|hero), ratios R_k = p(x̄|λ_k)/p(x̄|hero);
/// each free flight multiplies β by FreeFlight::weight and R_k by FreeFlight::pdf_ratio; lights are found by NEE
/// (with transmittance along the shadow ray, through index-matched boundaries) and by direction sampling, combined
/// by the power heuristic with S_dir = q_dir · Σ_k R_k · pass_k. β and R are rescaled together so that ΣR = 4 at
/// every vertex (the lane estimate 4β/ΣR is invariant), which keeps thousands of bounces in float range.
///
/// Random numbers per vertex: light choice (1), light position (2), lobe (1; unused in media), direction (2),
/// Russian roulette (1); per homogeneous segment, the equiangular technique's four; free flights take a variable
/// number (spectral_distance_sampling.h).
class VolumetricPathIntegrator {
 public:
  VolumetricPathIntegrator(const VolumetricScene& scene, VolumetricIntegratorSettings settings);

  /// With each light group's share of the result added to `groups` (light_group_radiance.h).
  SampledSpectrum radiance(const Ray& ray, const SampledWavelengths& lambda, Sampler& sampler,
                           const LightGroupRadiance& groups = {}) const {
    return radiance(ray, nullptr, lambda, sampler, groups);
  }
  /// The same with the camera ray's differentials (nullptr: none), which give textured hits their footprint when
  /// the scene asks for it (transport/integrators/path_footprint.h: through specular bounces and straight passages,
  /// ended by any other bounce or a scattering in a medium).
  SampledSpectrum radiance(const Ray& ray, const RayDifferentials* differentials, const SampledWavelengths& lambda,
                           Sampler& sampler, const LightGroupRadiance& groups = {}) const {
    return radiance(ray, differentials, lambda, sampler, PathGuidingContext{}, groups);
  }
  /// The same, guided by (and teaching) the field in `guiding` when the path settings' guiding is on: at surface
  /// vertices only, as the surface integrator guides them (a medium vertex samples its phase function).
  SampledSpectrum radiance(const Ray& ray, const RayDifferentials* differentials, const SampledWavelengths& lambda,
                           Sampler& sampler, const PathGuidingContext& guiding,
                           const LightGroupRadiance& groups = {}) const;
  const VolumetricScene& scene() const { return scene_; }

 private:
  struct ShadowResult {
    SampledSpectrum transmittance;
    SampledSpectrum pass_probability;
  };
  /// Transmittance from `origin` along `direction` over `distance`, crossing index-matched boundaries (and the
  /// media behind them); std::nullopt if a real surface blocks the way.
  /// `throughput`: the direction-sampling technique's throughput along this direction (spectral tracking).
  /// `time`: the path's moment in the shutter (Ray::time), where moving objects block it.
  /// Draws no sampler dimension: tracked media take their numbers from a stream keyed by the shadow ray.
  std::optional<ShadowResult> shadow(Vec3 origin, Vec3 direction, float distance, float time, MediumStack stack,
                                     const SampledWavelengths& lambda, SampledSpectrum throughput) const;
  /// Whether the equiangular technique runs on segments through `medium` (see the setting).
  bool uses_equiangular(const Medium& medium) const;
  /// The equiangular technique on one homogeneous segment (volumetric_equiangular.cpp): picks a light (part) as NEE
  /// does; unless it is at infinity, samples t equiangularly towards the part's centre and connects to a point of
  /// the part as NEE would. `beta`, `ratios`: the path's β and R_k before the segment's free flight. Returns the
  /// MIS-weighted radiance per lane. Consumes four uniform numbers (light choice, t, point on the light) plus the
  /// shadow ray's. `light_group`: the chosen light's group.
  SampledSpectrum equiangular_direct(EquiangularSegment segment, const Medium& medium, const SampledSpectrum& beta,
                                     const SampledSpectrum& ratios, const MediumStack& stack,
                                     const SampledWavelengths& lambda, Sampler& sampler, int& light_group) const;
  /// w_d: the balance-heuristic weight of free-flight sampling (then NEE, or the phase function's direction) for a
  /// scattering event at `t` of `segment` lit by a light part centred at `centre_m`, against the equiangular
  /// technique: P_nee·S_dist / (P_nee·S_dist + P_equi·S_equi) (docs/media.md), with P_nee the probability NEE
  /// chooses the part at the scattering point and P_equi the one the equiangular technique chooses it with (at
  /// equiangular_choice_point).
  float distance_technique_weight(EquiangularSegment segment, const Medium& medium, float t, Vec3 centre_m,
                                  const SampledSpectrum& ratios, const SampledWavelengths& lambda,
                                  float nee_probability, float equiangular_probability) const;
  /// The point the equiangular technique aims at for `part` of `light` (Light::emission_centre_m), or std::nullopt
  /// where the setting leaves the light out (the technique then has density 0 for it, and w_d = 1).
  std::optional<Vec3> equiangular_centre_m(const Light& light, int part) const;
  /// Where the equiangular technique chooses its light: the segment's start, as a point in a medium (no normal).
  /// Any point fixed before the distance is drawn keeps the technique's density known to NEE's MIS weight.
  static LightSamplingPoint equiangular_choice_point(const EquiangularSegment& segment) {
    return {segment.origin + segment.direction * segment.t0, Vec3{}};
  }
  MediumBoundary boundary(int material) const {
    return material >= 0 && size_t(material) < scene_.boundaries->size() ? (*scene_.boundaries)[size_t(material)]
                                                                         : MediumBoundary{};
  }

  const VolumetricScene& scene_;
  VolumetricIntegratorSettings settings_;
  bool has_equiangular_lights_ = false;  ///< any light equiangular_centre_m aims at
  /// Some medium is tracked (uses_tracking): shadow() then reads the NEE throughput, which needs the BSDF's f and
  /// density first; else NEE may trace the shadow ray before evaluating a costly BSDF (Bsdf::evaluation_is_costly).
  bool shadow_reads_throughput_ = false;
};

}  // namespace rimu
