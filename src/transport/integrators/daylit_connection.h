// Daylit points: a third technique for daylight after one reflection (docs/transport.md, "Daylit points").
//
// In a daylit room most of the light on the walls and ceiling comes from the sun's patch on the floor and the sky's
// light around the window, after one bounce. A path tracer finds it only by BSDF-sampling a direction into the patch
// from a wall (a few per cent of cosine-weighted directions) and then lighting the patch by next-event estimation:
// the walls stay grainy. Here each camera path also traces one ray of daylight into the scene through its windows
// (transport/lights/daylight_ray_sampler.h), which lands on a point y the sun or sky lights, and every diffuse or
// glossy vertex x of the path connects to y: the path x → y → light, with a shadow ray x → y and one y → light
// (which also gives the panes' transmittance at the path's own wavelengths).
//
// The same path x → y → ω is also made by BSDF sampling at x followed, at y, by next-event estimation (A) or by
// BSDF sampling that escapes into the light (C). The three are combined with the power heuristic over their densities
// in one measure (y per m², ω per sr), each summed over the four lanes as the integrator's spectral MIS does:
//   A: Σ_k R_k q_k(x→y) G_y · b P_y p_ω,   C: Σ_k R_k q_k(x→y) G_y q_k(y→ω),   B (this): Σ_k R_k · p(y, ω),
// with G_y = |n_y·(x→y)|/d², q the BSDF (or guided) densities, P_y b the light sampler's probability of the light at
// y (b: the resampling boost), p_ω next-event estimation's density of ω there and p(y, ω) DaylightRaySampler::density. The path
// integrator adds B's density to the A and C weights at y (daylit_density_factor), and this file computes B's.
#pragma once

#include <optional>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/geometry/frame.h"
#include "transport/geometry/surface_hit.h"
#include "transport/guiding/guided_bsdf.h"
#include "transport/integrators/shadow_passage.h"
#include "transport/lights/daylight_ray_sampler.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

struct TransportScene;
struct PathIntegratorSettings;
class GuidingField;

/// The point a daylight ray met, ready to be connected to.
struct DaylitPoint {
  SurfaceHit hit;
  std::optional<Bsdf> bsdf;
  Frame frame;             ///< shading frame; for an opaque material +z on the side the light arrives from
  Vec3 geometric_normal;   ///< on that side for an opaque material
  bool transmissive = false;
  int light = -1;
  Vec3 to_light;           ///< ω
  float density = 0.0f;    ///< p(y, ω) (DaylightRaySampler::density)
  float light_pdf = 0.0f;  ///< the density next-event estimation at y has for ω (technique A)
  bool delta_light = false;    ///< a sun of zero diameter (no technique C)
  SampledSpectrum radiance{0.0f};  ///< the light's radiance along ω (a delta sun's E) × the panes' transmittance to it
  SampledSpectrum pass_to_light{1.0f};  ///< the probability that BSDF sampling passes those panes (technique C)
  float light_choice = 0.0f;  ///< b · P_y: what next-event estimation at y counts for the light (technique A)
  std::optional<VertexGuide> guide;
};

/// Where a ray of daylight first meets a surface that is no pane (an opaque or refracting one, or an emitter), and
/// the panes it passed on its whole way from the light: those between the sky and its aperture as well as those
/// inside, each as a shadow ray passes it (their transmittance, and the probability that BSDF sampling would have
/// passed it: ShadowPassage). std::nullopt when the ray leaves the scene, something blocks the sky from the
/// aperture, or it passes more than kMaxShadowPassages panes in all (as one shadow ray may).
struct DaylightEntry {
  SurfaceHit hit;
  ShadowPassage passage;
};
std::optional<DaylightEntry> enter_through_aperture(const TransportScene& scene,
                                                    const DaylightRaySampler::DaylightRay& ray,
                                                    const SampledWavelengths& lambda, float time);

/// Traces `ray` into the scene through panes (as shadow rays pass them) to the first surface that scatters, then
/// from there towards the light. std::nullopt when the ray leaves the scene, meets an emitter without material, a
/// delta-only surface or a `mix` (which is chosen per direction seen from: no point of the technique), or the light
/// is blocked from the point.
std::optional<DaylitPoint> find_daylit_point(const TransportScene& scene, const DaylightRaySampler& daylight_rays,
                                             const PathIntegratorSettings& settings, const SampledWavelengths& lambda,
                                             const DaylightRaySampler::DaylightRay& ray, float time, const GuidingField* field);

/// The eye vertex x being connected (what the path integrator has at hand there).
struct ConnectingVertex {
  const SurfaceHit& hit;
  const Frame& frame;
  Vec3 geometric_normal;  ///< on the side of wo for an opaque material
  Vec3 wo;                ///< local
  const Bsdf& bsdf;
  const GuidedBsdf& sampling;  ///< the densities BSDF sampling has at x
  bool transmissive;
  SampledSpectrum pdf_ratio;   ///< R_k at x
  float time;
};

/// B's estimate at x, per lane, before the path's throughput: f_x G f_y L T × 4 × w_B / (Σ_k R_k p(y, ω)), zero when
/// x and y cannot see each other. `guiding_probability` is α of the guided densities.
SampledSpectrum connect_to_daylit_point(const TransportScene& scene, const LaneTechniques& lanes,
                                        const ConnectingVertex& x, const DaylitPoint& y,
                                        const SampledWavelengths& lambda, float guiding_probability);

}  // namespace rimu
