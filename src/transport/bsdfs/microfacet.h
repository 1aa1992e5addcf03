// The Trowbridge-Reitz (GGX) microfacet distribution: normal distribution, Smith masking, visible normals.
//
// All directions are in the local shading frame (macro normal +z). The distribution is symmetric under
// z → −z, so D, Λ and G depend only on |cos θ|; a direction below the surface is treated as its mirror image.
#pragma once

#include <cmath>

#include "transport/geometry/vector.h"

namespace rimu {

/// GGX / Trowbridge-Reitz microfacets with anisotropic width α_x, α_y (Walter et al. 2007, "Microfacet Models
/// for Refraction through Rough Surfaces", Eq. 33; anisotropic form: Heitz 2014, "Understanding the
/// Masking-Shadowing Function in Microfacet-Based BRDFs", Eq. 85).
///
/// Roughness → α: Rimu's materials take a perceptual roughness r ∈ [0, 1] and use α = r² (Burley 2012,
/// "Physically-Based Shading at Disney", §5.4), so r = 0.5 looks half-way between mirror and matte.
/// Below kSmoothAlpha the lobe is narrower than float directions resolve; BSDFs then use a delta lobe instead.
class TrowbridgeReitz {
 public:
  static constexpr float kSmoothAlpha = 1e-3f;
  /// The α of a perceptual roughness r: α = r² (Burley 2012).
  static float roughness_to_alpha(float roughness) { return roughness * roughness; }

  TrowbridgeReitz(float alpha_x, float alpha_y);

  float alpha_x() const { return alpha_x_; }
  float alpha_y() const { return alpha_y_; }
  /// True when both widths are below kSmoothAlpha: treat the surface as a perfect mirror / refractor.
  bool effectively_smooth() const { return alpha_x_ < kSmoothAlpha && alpha_y_ < kSmoothAlpha; }
  /// Below kGlossyAlpha (in both directions) and not smooth, the lobe's solid angle is a small fraction of the
  /// hemisphere (≈ π α² sr about the mirror direction: 0.28 sr at α = 0.3): a glossy lobe (BsdfFlags::has_glossy).
  static constexpr float kGlossyAlpha = 0.3f;
  bool is_glossy() const { return !effectively_smooth() && alpha_x_ < kGlossyAlpha && alpha_y_ < kGlossyAlpha; }

  /// The microfacet normal density D(m), per steradian of m, normalised so that the projected microfacet area
  /// covers the macro surface, ∫ D(m) cos θm dm = 1:  D(m) = 1 / (π αx αy (m_x²/αx² + m_y²/αy² + m_z²)²).
  float d(Vec3 m) const;
  /// Smith's auxiliary function Λ(w) = (√(1 + α(φ)² tan²θ) − 1)/2, α(φ)² = cos²φ αx² + sin²φ αy² (Heitz 2014,
  /// Eq. 86). +∞ at the horizon.
  float lambda(Vec3 w) const;
  /// Smith masking G1(w) = 1/(1 + Λ(w)).
  float g1(Vec3 w) const { return 1.0f / (1.0f + lambda(w)); }
  /// Height-correlated masking-shadowing G2(wo, wi) = 1/(1 + Λ(wo) + Λ(wi)) (Heitz 2014, Eq. 99).
  float g2(Vec3 wo, Vec3 wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

  /// Density of visible normals seen from w, per steradian of m (Heitz 2018, Eq. 1):
  ///     D_w(m) = G1(w) |w·m| D(m) / |cos θw|,   zero when m faces away from w.
  float visible_d(Vec3 w, Vec3 m) const;
  /// The same from D(m) and Λ(w) already at hand (m facing w): |w·m| D(m) / ((1 + Λ(w)) |cos θw|). For BSDFs that
  /// need D and Λ for G2 as well.
  static float visible_d(float d_m, float lambda_w, float w_dot_m, float cos_w) {
    return std::fabs(w_dot_m) * d_m / ((1.0f + lambda_w) * std::fabs(cos_w));
  }
  /// A microfacet normal distributed as D_w: stretch w to the α = 1 configuration (Heitz 2018, "Sampling the GGX
  /// Distribution of Visible Normals", JCGT 7(4)), where the visible normals are w plus a uniform point of a
  /// spherical cap (Dupuy & Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps", implemented from the
  /// paper's description; the same density as Heitz's projected-disk mapping, with no basis around w and two
  /// square roots fewer), unstretch. The result lies in w's hemisphere (m.z has the sign of w.z, or +z when
  /// w.z = 0). `u` in [0,1)².
  Vec3 sample_visible(Vec3 w, Vec2 u) const;

 private:
  float alpha_x_, alpha_y_;
};

}  // namespace rimu
