// Light from infinitely far away in every direction: a constant radiance, or an image in one of two mappings:
// equirectangular (latitude-longitude, below) or equal-area octahedral (pbrt-v4's, further below).
//
// Equirectangular directions. The light has its own orthonormal frame (s, t, n), given at construction (default: world x, y, z):
// n is "up", the image's top row. A direction d with local coordinates (d_s, d_t, d_n) maps to
//   θ = acos(d_n) ∈ [0, π]  (0 at the top),   φ = atan2(−d_t, d_s) wrapped to [0, 2π),
//   u = φ / 2π (image x = ⌊u·width⌋),         v = θ / π (image y = ⌊v·height⌋),
// so u = 0 (the left edge) looks along +s, and u grows to the RIGHT of a viewer at the centre who looks along +s
// with n up (the image is not mirrored when seen from inside). The frame must be right-handed (s × t = n);
// a y-up scene passes Frame{{1,0,0},{0,0,-1},{0,1,0}}: +y up, u = 0 along +x.
//
// Equal-area octahedral directions (EnvironmentMapping::equal_area_octahedral; transport/sampling/equal_area_square.h): a
// direction with local coordinates d maps to (u, v) = equal_area_sphere_to_square(d) — the image centre looks along
// +n, the middle of the right edge along +s, the middle of the bottom edge (v = 1) along +t, the corners along −n.
// This is pbrt-v4's ImageInfiniteLight with (s, t, n) its light-space x, y, z, pixel row 0 at v = 0. Every pixel
// of a w × h image subtends exactly 4π/(w·h) sr; the frame may have either handedness (pbrt's light-to-world
// transform may mirror).
//
// Lookup: nearest pixel (piecewise constant), NOT bilinear, so the radiance is constant on exactly the cells the
// sampling density is constant on: importance sampling by luminance then matches the integrand pixel for pixel.
//
// Sampling (Pharr, Jakob & Humphreys, PBR 3rd ed., §14.2.4): a Distribution2D over the pixels with weights
//   f(x, y) = (Y(x, y) + 10⁻³·Ȳ) · sin θ_y        (θ_y at the row's centre),
// the sin θ accounting for the smaller solid angle of rows near the poles. The small floor 10⁻³·Ȳ (Ȳ the mean
// pixel luminance) keeps a nonzero density wherever the image could be nonzero even if its luminance is 0 (a deep
// violet pixel), at the cost of ≤ 0.1 % of the samples. With dω = sin θ dθ dφ = 2π² sin θ du dv,
//   p_ω(d) = p(u, v) / (2π² sin θ).
// Directions at the poles (sin θ = 0) have p_ω undefined: std::nullopt / pdf 0 (a set of zero measure).
// Equal-area images use the weights f(x, y) = Y(x, y) + 10⁻³·Ȳ (no sin θ: every pixel has the same solid angle),
// and since the map preserves area, p_ω(d) = p(u, v) / 4π exactly, at every direction.
// The tables may be coarser than the image (transport/sampling/distribution_coarsening.h): blocks of f × f pixels,
// f the largest power of two whose block sums add at most 1 % relative variance to a light sample by the measure
// there. A 2048² sky resampled from a small latitude-longitude original takes 4 × 4 blocks (0.4 % added), 1 MiB
// tables instead of 16, and its samples stop missing the cache; a map with a sharp sun keeps its pixels. The
// density is then constant over each block (uniform within it): still exactly what sample_li draws and pdf_li
// reports, so the estimate stays unbiased; only how well it follows the pixels changes.
// A black image (every weight 0) falls back to uniform sphere sampling, p_ω = 1/4π; so does a constant light.
//
// Portals (set_portals; transport/lights/environment_portal.h): rectangles through which the environment is known to reach
// the scene (a room's windows). sample_li then draws directions uniformly in the solid angle the portals subtend at
// the reference point, p_ω = N/ΣΩ (N portals crossed, ΣΩ their total solid angle), and pdf_li is 0 for every
// direction that crosses no portal. Those directions are NOT assumed dark (pbrt-v4's PortalImageInfiniteLight
// assumes they are): radiance_escaped still returns the environment there, so a BSDF-sampled ray that escapes
// elsewhere counts with MIS weight 1 and the estimate stays unbiased whatever the portals cover. An image is then
// sampled by solid angle within the portals, not by luminance (Bitterli et al. 2015's portal-masked image sampling
// would do both; not built). The power becomes what crosses the portals (total_power_w).
#pragma once

#include <memory>
#include <optional>

#include "transport/sampling/distribution_2d.h"
#include "transport/sampling/distribution_coarsening.h"
#include "transport/lights/radiance_image.h"
#include "transport/lights/environment_portal.h"
#include "transport/geometry/frame.h"
#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"

namespace rimu {

enum class EnvironmentMapping { equirectangular, equal_area_octahedral };

class EnvironmentLight final : public Light {
 public:
  /// Constant radiance `radiance` W/(m²·sr·nm) from every direction.
  explicit EnvironmentLight(LightSpectrum radiance);
  /// An image, its radiance multiplied by `scale` (set at load time, e.g. from nits in issue 5), oriented by
  /// `frame` (see above) and read in `mapping`. Cost O(width·height): the sampling distribution and 16 wavelengths
  /// of every pixel for the power estimate.
  EnvironmentLight(std::shared_ptr<const RadianceImage> image, double scale,
                   Frame frame = Frame{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
                   EnvironmentMapping mapping = EnvironmentMapping::equirectangular);

  /// Restrict light sampling to directions through `portals` (see above); an empty set restores the default.
  /// Call before the light is shared (lights are read-only while rendering).
  void set_portals(PortalSet portals) { portals_ = std::move(portals); }
  const PortalSet& portals() const { return portals_; }
  const PortalSet* portal_set() const override { return portals_.empty() ? nullptr : &portals_; }

  /// Tell the light that next-event estimation is combined with BSDF and phase sampling by MIS (the scene loader
  /// does unless the integrator runs next-event estimation alone, DirectLighting::nee_only, which needs the full
  /// density). Then, without portals, light sampling takes only what BSDF sampling does badly (Karlík et al. 2019,
  /// "MIS compensation"; pbrt-v4 does both, with "allowIncompletePDF"):
  ///  - a constant environment is not sampled at all. Light sampling could only draw it uniformly over the sphere,
  ///    which every non-delta BSDF and phase function samples at least as well; combined, its samples only add
  ///    variance, and in a dense medium far more (each needs a ratio-tracked transmittance). pbrt-v4's clouds.pbrt
  ///    under a uniform sky (160 × 90, 16 spp): relMSE 0.032 with both, 0.011 with phase sampling alone (pbrt 0.010).
  ///  - from surface points, an image is sampled by max(0, Y − Ȳ) (its luminance above the solid-angle mean Ȳ,
  ///    × sin θ for equirectangular maps) instead of by Y: the directions below the mean are left to BSDF sampling,
  ///    which then carries them with MIS weight 1. A map with nothing above its mean keeps the full density. In
  ///    media (a reference point without a normal) the full density stays: a phase-sampled ray reaches the sky only
  ///    if it survives its free flight, so light samples with their ratio-tracked transmittance do better there.
  ///    Measured, 16 spp against 256–1024-spp references, two seeds: a floor and three spheres (diffuse, rough
  ///    metal, coated) under the 2048² sky of the corpus scene cloud, relMSE 0.0182 → 0.0155 for about 5 % more CPU;
  ///    the cloud itself, compensated in the medium too, 0.070 → 0.091 (so not there).
  void set_combined_with_bsdf_sampling(bool combined);
  bool sampled_by_nee() const override { return !(combined_with_bsdf_ && constant_ && portals_.empty()); }

  /// A direction through the portals (if any), else by luminance (image) or uniform on the sphere; distance ∞.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  /// sample_li's sample with its radiance pending (the environment is one part).
  std::optional<LightSample> sample_part_li_deferred(int part, const LightReference& ref,
                                                     const SampledWavelengths& lambda, Vec2 u) const override;
  void resolve_radiance(LightSample& sample, const SampledWavelengths& lambda) const override;
  /// p_ω(wi); `hit` is ignored.
  float pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit = nullptr) const override;
  /// The radiance arriving from direction `direction` (nearest pixel, × scale).
  SampledSpectrum radiance_escaped(Vec3 direction, const SampledWavelengths& lambda) const override;
  /// Power entering a sphere of radius r: each point of it receives π·L̄ per unit area, so Φ = 4π² r² ∫L̄(λ) dλ, with
  /// L̄ the radiance averaged over directions (solid-angle weighted; for an image, a 16-wavelength midpoint rule).
  /// With portals, the power through them, Φ = π·A·∫L̄(λ)dλ (A their total area; an image's L̄ is its mean over the
  /// sphere, not over the directions each portal lets in), whatever the radius.
  double total_power_w(double scene_radius_m) const override;
  bool is_infinite() const override { return true; }

  /// (u, v) ∈ [0, 1)² of a world direction (the mapping's convention above), and back.
  Vec2 direction_to_uv(Vec3 direction) const;
  Vec3 uv_to_direction(Vec2 uv) const;

  /// With portals: where the light enters, for the light BVH, which then holds the environment as one leaf like an
  /// area light (bvh_light_sampler.h): the portals' rectangles, two-sided, intensity ∫L̄(λ)dλ·A (a Lambertian
  /// emitter of the mean radiance over the portals' area A). Without portals std::nullopt: a light at infinity.
  std::optional<LightBounds> part_bounds(int part) const override;

  /// The constant environment's spectrum; nullptr for an image (its spectrum varies with direction).
  const LightSpectrum* emitted_spectrum() const override { return constant_ ? &*constant_ : nullptr; }

  /// Pixels per side of a sampling-table cell (1: one cell per pixel), of the full and the compensated table.
  int sampling_block() const { return distribution_block_.factor; }
  int compensated_sampling_block() const { return compensated_block_.factor; }

 private:
  float solid_angle_pdf(Vec3 local_direction) const;
  /// sample_li's direction, density and distance, without the radiance.
  std::optional<LightSample> sample_direction(const LightReference& ref, Vec2 u) const;
  SampledSpectrum lookup(Vec2 uv, const SampledWavelengths& lambda) const;

  std::shared_ptr<const RadianceImage> image_;  // null for a constant environment
  std::optional<LightSpectrum> constant_;          // set for a constant environment
  double image_scale_ = 1.0;
  Frame frame_;
  EnvironmentMapping mapping_ = EnvironmentMapping::equirectangular;
  Distribution2D distribution_;  // empty: uniform sphere sampling
  PortalSet portals_;            // empty: the whole sphere
  bool combined_with_bsdf_ = false;  // see set_combined_with_bsdf_sampling
  Distribution2D compensated_;       // by max(0, Y − Ȳ); empty: sample by distribution_
  /// The distribution light samples from `ref` are drawn from (and pdf_li reports): compensated at surface points,
  /// the full one in media (ref.normal zero).
  const Distribution2D& sampling_distribution(const LightReference& ref) const {
    const bool in_medium = ref.normal.x == 0.0f && ref.normal.y == 0.0f && ref.normal.z == 0.0f;
    return compensated_.is_zero() || in_medium ? distribution_ : compensated_;
  }
  double mean_radiance_integral_ = 0.0;  // ∫L̄(λ)dλ over 360-830 nm, W/(m²·sr)
  SamplingBlock distribution_block_, compensated_block_;  // pixels per table cell side, and the variance added

  /// A table over `weights` (one per pixel), as coarse as choose_sampling_block allows; `block` receives the choice.
  static Distribution2D sampling_table(std::span<const float> weights, int width, int height, SamplingBlock& block);
};

}  // namespace rimu
