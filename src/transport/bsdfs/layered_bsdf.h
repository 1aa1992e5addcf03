// A dielectric coat over an opaque base with a participating slab between them, evaluated by a random walk:
// rough plastics, lacquered and tinted metals (pbrt-v4's coateddiffuse and coatedconductor).
#pragma once

#include <optional>
#include <variant>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"
#include "transport/bsdfs/conductor_bsdf.h"
#include "transport/bsdfs/dielectric_bsdf.h"
#include "transport/bsdfs/diffuse_bsdf.h"

namespace rimu {

/// What lies under the coat: a Lambertian or a (smooth or rough) conductor. Both are opaque and two-sided.
using LayerBase = std::variant<DiffuseBsdf, ConductorBsdf>;

/// The slab between the coat and the base: `thickness` in mean free paths (extinction σt = 1 per unit length,
/// grey), single-scattering `albedo` per lane (0 = purely absorbing, the default of pbrt-v4's coated materials),
/// Henyey-Greenstein asymmetry `g`.
struct LayerMedium {
  float thickness = 0.01f;
  SampledSpectrum albedo{0.0f};
  float g = 0.0f;
};

/// How much work one eval()/pdf()/sample() may do: `max_depth` scattering events per walk, `samples` walks per
/// eval()/pdf() (pbrt-v4's maxdepth and nsamples; defaults 10 and 1).
struct LayerWalk {
  int max_depth = 10;
  int samples = 1;
};

/// A two-layer BSDF: a dielectric interface of one index η (smooth or rough GGX) on top, `base` below, the slab
/// between (Guo, Hašan & Zhao 2018, "Position-Free Monte Carlo Simulation for Arbitrary Layered BSDFs"; the
/// estimators of Pharr, Jakob & Humphreys, PBR 4th ed., §14.3).
///
/// No closed form exists, so every call runs a random walk between the layers and returns an unbiased
/// ESTIMATE (with its own variance):
/// - eval(wo, wi): the coat's own reflection f_top(wo, wi) plus `samples` walks. Each walk refracts wo into the
///   slab (sampled from the coat), and a companion direction is refracted in from wi (sampled from wi's side:
///   the adjoint, without the radiance factor 1/η²). At every scattering event (base or medium) the walk
///   connects to that companion (next-event estimation, weighted by the power heuristic against the walk's own
///   next direction reaching the coat and leaving through it towards wi, whose density from wi's side is
///   evaluated exactly; pbrt-v4 uses the reverse density there, a density over the other side's directions, so
///   its two weights sum to more than 1 and its f() is biased high: docs/pbrt-import.md). Distances in the slab
///   are sampled exponentially when the albedo is non-zero, else the slab only attenuates, by
///   exp(−thickness/|cos θ|) per crossing. Russian roulette after 3 events when the throughput falls below 0.25.
/// - sample(wo): the walk itself: the coat's sample (a reflection is returned as it is), then medium distances,
///   base and coat samples until the walk leaves through the coat. The returned weight f·|cos θi|/pdf is the
///   walk's (exact in expectation); the returned pdf is the pdf() estimate below, with f scaled to keep the
///   weight, so that MIS with light sampling uses the same density in both strategies. A walk through delta
///   lobes only (smooth coat over a smooth metal, no scattering) returns a delta sample.
/// - pdf(wo, wi): an APPROXIMATE density for MIS only (it ignores the medium and multiple bounces, like
///   pbrt-v4's): the coat's reflection density plus a one-bounce estimate, mixed 9:1 with the uniform sphere
///   density so that it is never 0. sample() does not draw exactly from it.
///
/// Random numbers: eval() and pdf() are deterministic functions of their arguments (a hash of wo and wi seeds
/// the walk, as pbrt-v4 does), so the same (wo, wi) always gives the same estimate; sample() seeds from wo and
/// its random numbers. Lanes: the hero wavelength's choices drive the walk (lobe choices, roulette on the
/// largest lane); every lane carries its own weight (base albedo or metal Fresnel, slab albedo). The coat has
/// one index for all lanes, so no event is dispersive and the pdf is equal in every lane.
/// Opaque and two-sided: wo below the surface is mirrored into the upper hemisphere (and wi with it); wi on the
/// other side of wo gives 0.
class LayeredBsdf {
 public:
  /// `coat_eta` = n_coat / n_outside (> 0), `coat` its microfacet distribution.
  LayeredBsdf(float coat_eta, TrowbridgeReitz coat, LayerBase base, LayerMedium medium, LayerWalk walk);

  /// An unbiased estimate of f(wo, wi) per lane (no |cos θi|); 0 across the surface.
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  /// The approximate density described above (equal in all lanes); 0 across the surface.
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// One random walk; std::nullopt when it is absorbed, terminated or exceeds max_depth. `with_density` false:
  /// a non-delta result skips pdf()'s walk and has BsdfSample::density_deferred set (its density is pdf(wo, wi)).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u, bool with_density = true) const;
  BsdfFlags flags() const;

 private:
  bool base_is_specular() const;
  SampledSpectrum base_eval(Vec3 wo, Vec3 wi) const;
  float base_pdf(Vec3 wo, Vec3 wi) const;
  std::optional<BsdfSample> base_sample(Vec3 wo, float u_lobe, Vec2 u) const;
  /// exp(−|dz / cos θ|): the slab's transmittance over height dz along w.
  static float transmittance(float dz, Vec3 w);

  float eta_;
  DielectricBsdf top_;
  LayerBase base_;
  LayerMedium medium_;
  LayerWalk walk_;
  bool top_smooth_, has_albedo_;
};

}  // namespace rimu
