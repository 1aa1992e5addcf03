// What a denoiser needs to know about the surface a camera ray sees: its albedo, normal and distance, taken at the
// first non-specular hit (through mirrors and glass to what is seen in them).
#pragma once

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/geometry/ray.h"
#include "transport/geometry/vector.h"
#include "transport/sampling/sampler.h"

namespace rimu {

struct TransportScene;   // transport/integrators/path_integrator.h
struct VolumetricScene;  // transport/integrators/volumetric_path_integrator.h

/// One camera sample's features. Every value is finite.
struct PathFeatures {
  /// The directional albedo ρ(ωo) = ∫ f(ωo, ωi) |cos θi| dωi of the first non-specular BSDF, per lane, estimated with
  /// one BSDF sample (f·|cos|/pdf: exact for a Lambertian surface, unbiased for the others). 0 when the ray escapes,
  /// meets a light without a material or passes more than kMaxSpecularBounces delta bounces. Not multiplied by the
  /// throughput of the delta bounces before it: a mirror shows the albedo of what it reflects.
  SampledSpectrum albedo{0.0f};
  /// The world-space shading normal there (a normal or bump map's, if any), turned towards the arriving ray for
  /// opaque materials; 0 when the ray escapes.
  Vec3 normal{};
  /// The length of the path from the camera to that hit (through the delta bounces), in scene units; 0 when the
  /// ray escapes.
  float depth = 0.0f;
};

/// The delta bounces a feature ray follows before giving up (a hall of mirrors).
inline constexpr int kMaxSpecularBounces = 8;

/// Traces `ray` to its first non-specular hit: a BSDF with only delta lobes (a mirror, smooth glass) is passed by
/// sampling one of its lobes, as a path would. Media are ignored (features are surface properties). Uses `sampler`
/// for the delta lobe choices and the albedo's BSDF sample; the caller gives it a sampler of its own so that the
/// image's samples do not change. Cost: one closest-hit ray per surface passed, one BSDF sample.
/// With `media` (a scene with participating media): where the ray enters a medium that has a surface albedo
/// (Medium::surface_albedo: skin, wax, milk authored by albedo and mean free path) through a boundary that
/// transmits diffusely or roughly, the albedo is that surface albedo at the hit, clamped to [0, 1] — what the
/// object looks like — rather than the boundary BSDF's one-sample estimate (a smooth diffuse-entry boundary reads
/// 0 whenever its sample takes the mirror lobe).
PathFeatures first_diffuse_features(const TransportScene& scene, Ray ray, const SampledWavelengths& lambda,
                                    Sampler& sampler, const VolumetricScene* media = nullptr);

}  // namespace rimu
