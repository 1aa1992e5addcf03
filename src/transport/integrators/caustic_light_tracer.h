// Caustics by light tracing: the paths a path tracer cannot find, or finds only by chance.
//
// A caustic is light that reaches a diffuse or glossy surface by way of one or more specular (delta) bounces: a spot
// light focused by a glass, the bright pattern under a water surface. In Heckbert's notation its paths to the camera
// are E D S⁺ L: the camera sees a surface point y with a non-delta component (D), whose light came through specular
// vertices (S) from a light (L). A path tracer finds them only when a BSDF-sampled ray from y happens to pass all the
// S vertices and hit the light: never for a light at a point, rarely for a small lamp. A light tracer finds them
// easily: a ray of the light's emission, bounced at S vertices by their delta lobes, lands on y, which is connected
// to the camera (pbrt-v4's light tracing and bidirectional methods do the same).
//
// The split (no MIS needed): with `PathIntegratorSettings::caustic_light_tracing` the path tracer drops exactly the
// paths E D S⁺ L whose light is traced here (Light::samples_emission: lights at a point, uniform emitting triangles
// and spheres), where D is the camera ray's first vertex sampled by a non-delta lobe and every later vertex by a delta
// lobe; this tracer adds exactly those, by one light path per camera sample. Every path is counted once. Panes
// passed straight through (Material::passes_shadow_rays) are no vertices here either, as in the path tracer. Lights
// not traced (at infinity, projectors, image emission, luminaires with an opening) keep the path tracer's caustics.
//
// Estimator. A light ℓ is chosen by power (P_ℓ), a ray of its emission drawn with weight W = L_e cos/(p_A p_ω)
// (EmissionSample); at each S vertex the throughput takes f·|cos|/p of the sampled delta lobe, with the radiance
// scaling of refraction undone (flux, not radiance, is carried: × η'²) and the shading-normal correction of adjoint
// transport, |ωo·n_s||ωi·n_g| / (|ωo·n_g||ωi·n_s|) (Veach 1997, §5.3). At a vertex y with a non-delta component the
// contribution to the camera is β f(y; ωo, ω_c) |ωo·n_s||ω_c·n_g|/|ωo·n_g| · T · importance (light_tracing_camera.h),
// T the panes' transmittance on the way; the render loop spreads it over the pixels by the pixel filter's density
// and divides it by the number of light paths per camera sample per pixel. Wavelengths are the camera sample's four,
// with the same spectral-MIS ratios R as the path tracer (lane j's estimate 4β_j/ΣR).
#pragma once

#include <optional>
#include <vector>

#include "transport/integrators/light_tracing_camera.h"
#include "transport/integrators/path_integrator.h"
#include "transport/sampling/distribution_1d.h"

namespace rimu {

/// What one light path adds to the film: a film position and lane estimates, in PathIntegrator::radiance's units
/// times the camera's importance (per light path; the render loop normalises).
struct CausticSplat {
  Vec2 film_px;
  SampledSpectrum radiance;
  SampledWavelengths lambda;  ///< the wavelengths of `radiance`'s lanes
  int light_group = 0;
};

class CausticLightTracer {
 public:
  /// The lights it traces: every one with Light::samples_emission(), chosen by total power; none in a scene without a
  /// material that can scatter specularly (nothing to trace there).
  CausticLightTracer(const TransportScene& scene, const PathIntegratorSettings& settings);

  /// No light to trace (the render then runs without it).
  bool empty() const { return traced_.empty(); }
  /// Whether light `index` is traced (the path tracer drops its E D S⁺ L paths).
  static bool traces(const Light& light) { return light.samples_emission(); }

  /// One light path at the camera sample's wavelengths and time, its splats appended to `splats` (one per vertex
  /// with a non-delta component after at least one specular bounce: usually none, at most max_depth − 1).
  void trace(const SampledWavelengths& lambda, Sampler& sampler, float time, const LightTracingCamera& camera,
             std::vector<CausticSplat>& splats) const;

 private:
  const TransportScene& scene_;
  PathIntegratorSettings settings_;
  std::vector<int> traced_;  ///< indices of the traced lights
  std::optional<Distribution1D> by_power_;
};

}  // namespace rimu
