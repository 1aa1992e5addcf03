// A hair or fur fibre: the scattering model of Chiang, Bitterli, Tappan & Burley, "A Practical and Controllable
// Hair and Fur Model for Production Path Tracing" (EGSR 2016), as pbrt-v3/v4's HairBxDF. The fibre is a smooth
// dielectric cylinder with tilted cuticle scales and an absorbing interior; light leaving it is split into the
// lobes p = 0 (R: reflected at the surface), 1 (TT: through), 2 (TRT: one internal reflection) and one lobe
// for every longer path, each the product of a longitudinal Mp (d'Eon et al. 2011), an attenuation Ap (Fresnel
// and absorption) and an azimuthal Np (a trimmed logistic).
#pragma once

#include <array>
#include <optional>

#include "transport/bsdfs/bsdf_flags.h"
#include "transport/bsdfs/bsdf_sample.h"
#include "transport/geometry/frame.h"

namespace rimu {

/// The fibre's material parameters, with pbrt-v4's names and defaults.
struct HairParameters {
  float eta = 1.55f;       ///< refractive index of the fibre (keratin), the same at every wavelength; ≥ 1
  float beta_m = 0.3f;     ///< longitudinal roughness in (0, 1]: the width of the lobes along the fibre
  float beta_n = 0.3f;     ///< azimuthal roughness in (0, 1]: the width of the lobes around the fibre
  float alpha_deg = 2.0f;  ///< tilt of the cuticle scales, degrees: shifts R by −2α, TT by α and TRT by 4α
};

/// The fibre's direction in the local shading frame `frame` (normal = +z) as a unit (x, y): the world tangent
/// `dpdu` projected into the plane perpendicular to the normal. Where that projection vanishes (dpdu zero, as on
/// a surface that is not a curve, or along the normal), the frame's first axis (1, 0) stands in: a fixed,
/// arbitrary choice that keeps the BSDF finite (it then treats the surface as fibres running along frame.s).
Vec2 hair_fibre_direction(const Frame& frame, Vec3 dpdu);

/// The hair BSDF in Rimu's local frame. Internally each direction is expressed in the fibre's frame (pbrt's
/// convention): x along the fibre (sin θ = x, θ the angle from the plane perpendicular to the fibre), z the
/// shading normal, y = z × x, and the azimuth φ = atan2(z, y). `h` ∈ [−1, 1] is where the ray met the fibre
/// across its width, the signed offset from the centreline over the radius, relative to the ray: positive along
/// x × wo⊥ (wo⊥ = wo's part across the fibre), i.e. along d × tangent for a ray of direction d — a curve hit's
/// h = 2v − 1 (pbrt-v4's v). Only azimuth differences enter the model, so the frame's orientation about the fibre
/// (which way the normal faces) does not matter.
///
/// f(wo, wi) = Σ_p Mp(θo, θi) Ap(wo) Np(φ) / |cos θi|, where cos θi is wi.z (the integrator's cosine, which the
/// division cancels, as in pbrt). Mp is normalised over cos θ dθ and Np over φ, so the white furnace
/// ∫ f |wi.z| dωi = Σ_p Ap, which is 1 exactly when σa = 0 (Fresnel's R, T and the geometric series sum to 1).
/// The model is not reciprocal: Ap and the azimuthal offsets are evaluated at wo alone, and the cuticle tilt
/// shifts the lobes one way. It is reciprocal only where wo and wi are interchangeable for those: α = 0, h = 0 and
/// |sin θi| = |sin θo|.
///
/// Sampling: lobe p with probability Ap/ΣAp of the hero lane (lane k's pdf() uses its own Ap), then θi from that
/// lobe's Mp exactly (d'Eon 2013) and φ from its Np exactly; pdf() is the exact mixture density Σ_p P_p Mp Np.
/// Four uniforms: `u_lobe` chooses p and is then rescaled to draw φ, `u` draws θi.
/// Spectral: σa(λ) makes Ap differ per lane; the geometry (η, the roughnesses, the tilt) is shared.
class HairBsdf {
 public:
  /// Lobes p = 0, 1, 2 evaluated individually; the sum of all longer paths is the last entry of the Ap array.
  static constexpr int kMaxP = 3;

  /// `fibre_direction` from hair_fibre_direction(); `h` clamped to [−1, 1]; `sigma_a` ≥ 0 per lane, in units of
  /// the inverse fibre RADIUS (the chord of a unit-radius cross-section at offset sin γt is 2 cos γt).
  /// Parameters are assumed valid (HairMaterial checks them).
  HairBsdf(Vec2 fibre_direction, float h, SampledSpectrum sigma_a, const HairParameters& parameters);

  /// f per lane, without the cosine; 0 when wi.z = 0.
  SampledSpectrum eval(Vec3 wo, Vec3 wi) const;
  /// Per-lane solid-angle density of sample(): Σ_p P_p(lane) Mp Np.
  SampledSpectrum pdf(Vec3 wo, Vec3 wi) const;
  /// A direction from lobe p (chosen by the hero's Ap), with f and the per-lane pdf of that direction. std::nullopt
  /// when wi lands exactly on wi.z = 0, when the density underflows to 0 far in a tail, or when the hero's Ap all
  /// vanish (η = 1 with total absorption).
  std::optional<BsdfSample> sample(Vec3 wo, float u_lobe, Vec2 u) const;
  /// Glossy, and light passes through the fibre (TT): the integrator keeps the frame of the shading normal
  /// unflipped, which the fibre direction computed at bsdf() time relies on.
  BsdfFlags flags() const { return {false, true, true}; }

  /// Ap per lane at wo (p = 0, 1, 2, and the sum of p ≥ 3), for tests: with σa = 0 they sum to 1.
  std::array<SampledSpectrum, kMaxP + 1> attenuation(Vec3 wo) const;

  /// σa per lane (per unit radius) that gives a fibre of azimuthal roughness `beta_n` the multiple-scattering
  /// colour `reflectance` (Chiang et al. 2016, Eq. 9); the reflectance is clamped to [1e-4, 1] (0 would need an
  /// infinite σa).
  static SampledSpectrum sigma_a_from_reflectance(SampledSpectrum reflectance, float beta_n);

 private:
  struct Incidence;  // what depends on wo alone (hair_bsdf.cpp)
  Incidence incidence(Vec3 wo_fibre) const;
  /// Mp·Np for each lane-independent lobe p at (wo, wi) in the fibre frame: f and pdf weight these by Ap and P_p.
  std::array<float, kMaxP + 1> lobe_densities(const Incidence& in, Vec3 wi_fibre) const;
  /// sin and |cos| of θo shifted by lobe p's cuticle tilt.
  void tilted(int p, float sin_o, float cos_o, float& sin_op, float& cos_op) const;
  Vec3 to_fibre(Vec3 w) const { return {x_.x * w.x + x_.y * w.y, -x_.y * w.x + x_.x * w.y, w.z}; }
  Vec3 from_fibre(Vec3 f) const { return {x_.x * f.x - x_.y * f.y, x_.y * f.x + x_.x * f.y, f.z}; }

  Vec2 x_;                                   // the fibre's direction in the local frame
  float h_, gamma_o_, eta_;
  SampledSpectrum sigma_a_;
  std::array<float, kMaxP + 1> variance_;    // Mp's v per lobe
  float logistic_scale_;                     // Np's s
  std::array<double, kMaxP + 1> log_longitudinal_norm_;  // log(2v sinh(1/v)) per lobe
  double logistic_inverse_mass_;             // 1/(CDF(π) − CDF(−π)) of Np's logistic
  std::array<float, 3> sin_2k_alpha_, cos_2k_alpha_;  // k = 0, 1, 2: α, 2α, 4α
};

}  // namespace rimu
