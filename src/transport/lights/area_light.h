// An emissive triangle mesh: spectral radiance L(λ) over its surface, from its front side or both sides; uniform, or
// read from an image at the surface's texture coordinates (textured_emission.h).
//
// Sampling (from a reference point x): a triangle (with probability w_k / W when the whole mesh is sampled, w_k its
// area A_k times, for an image, its mean emission (floored; textured_emission.h), or the light sampler's choice of
// part), then a direction to it by one of two techniques, fixed per (triangle, x):
//   - far triangles (A_k ≤ kSolidAngleSamplingRatio · d_c², d_c the distance to its centroid): a point y uniform
//     on its area, so p_ω = d²/(A_k |cos θ_l|) with θ_l between the light's normal at y and y → x (dω = |cos θ_l|
//     dA/d²). Grazing directions (cos θ_l → 0) make p_ω infinite; sample_li then returns std::nullopt and pdf_li 0,
//     a set of zero measure, so no energy is lost;
//   - near triangles: a direction uniform in the solid angle Ω_k the triangle subtends (spherical_triangle.h),
//     p_ω = 1/Ω_k. Area sampling there is unbiased but its estimate L cos θ_i cos θ_l A_k/d² is unbounded: its
//     variance grows as A_k/d² and has no bound at all for receivers that touch the emitter (a socket around a bulb,
//     a plane a tessellated bulb rests on), where the pixel means of any affordable sample count come out low
//     (issue 29's bulbs; docs/transport.md, "Emitters seen from close by").
// The whole-mesh density is (w_k / W)·p_ω; pdf_li and pdf_part_li recompute the same technique's density for a
// BSDF-sampled hit, so MIS sees exactly the density the light sample had.
//
// Front side: the normal n_k = (v1 − v0) × (v2 − v0) / |…|, i.e. counter-clockwise winding seen from the front,
// as in SurfaceHit::geometric_normal. A one-sided light emits towards w_out only when n·w_out > 0.
// Degenerate (zero-area or non-finite) triangles are kept in the index space (so triangle k of the mesh is still
// SurfaceHit::primitive == k) but get probability 0; they are counted, and never divide anything.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "transport/sampling/distribution_1d.h"
#include "transport/lights/light.h"
#include "transport/lights/light_spectrum.h"
#include "transport/lights/textured_emission.h"

namespace rimu {

class AreaLight final : public Light {
 public:
  /// `vertices_m`: world-space positions (after the instance transform); `indices`: three per triangle, triangle
  /// k is (indices[3k], indices[3k+1], indices[3k+2]), indices < vertices_m.size() (asserted). `radiance` in
  /// W/(m²·sr·nm). Cost O(triangles).
  AreaLight(std::span<const Vec3> vertices_m, std::span<const uint32_t> indices, LightSpectrum radiance,
            bool two_sided);
  /// The same with the radiance of an image (`emission` has one entry of corner uvs per triangle, asserted). Cost
  /// O(triangles × points of their means) on top.
  AreaLight(std::span<const Vec3> vertices_m, std::span<const uint32_t> indices, TexturedEmission emission,
            bool two_sided);

  /// A triangle by weight, then a direction to it (see above): p_ω = (w_k/W)·p_k(ω). std::nullopt for a reference on
  /// the light (d = 0), behind a one-sided light, at grazing angles (p_ω not finite), or without area or power.
  std::optional<LightSample> sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                       Vec2 u) const override;
  /// p_ω for a ray from `ref` along wi that hit triangle hit->primitive at hit->position; 0 without a hit, for a
  /// degenerate triangle, the back of a one-sided light, or a grazing hit.
  float pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit* hit) const override;
  /// L on the emitting side(s) (an image's at hit.uv), 0 behind a one-sided light; w_out points away from the
  /// surface.
  SampledSpectrum radiance(const SurfaceHit& hit, Vec3 w_out, const SampledWavelengths& lambda) const override;
  /// Lambertian emitter: Φ = π A ∫L(λ) dλ per emitting side (an image's: Σ_k A_k times triangle k's mean).
  double total_power_w(double scene_radius_m) const override;
  bool samples_emission() const override;
  std::optional<EmissionSample> sample_emission(float u_part, Vec2 u_position, Vec2 u_direction,
                                                const SampledWavelengths& lambda) const override;
  EmissionDensity emission_density(Vec3 normal, Vec3 direction) const override;

  /// Parts are the triangles (light samplers may choose them one by one, e.g. the light BVH).
  int part_count() const override { return triangle_count(); }
  /// A direction to triangle `part` by its technique at ref (p_k(ω): d²/(A_k|cos θ_l|) or 1/Ω_k); otherwise as
  /// sample_li.
  std::optional<LightSample> sample_part_li(int part, const LightReference& ref, const SampledWavelengths& lambda,
                                            Vec2 u) const override;
  /// p_k(ω) for a ray that hit triangle `part` (= hit->primitive); 0 as pdf_li.
  float pdf_part_li(int part, const LightReference& ref, Vec3 wi, const SurfaceHit* hit) const override;
  /// The triangle's box, normal (θo = 0, θe = π/2) and intensity L·A_k (an image's: the triangle's floored mean L);
  /// none for degenerate triangles.
  std::optional<LightBounds> part_bounds(int part) const override;
  /// Triangle `part`'s centroid (none if it is degenerate); part −1: the mean of the centroids weighted by w_k.
  std::optional<Vec3> emission_centre_m(int part) const override;

  int triangle_count() const { return int(triangles_.size()); }
  /// Triangles skipped for zero (or non-finite) area.
  int degenerate_triangle_count() const { return degenerate_count_; }
  double area_m2() const { return area_m2_; }
  bool two_sided() const { return two_sided_; }

  /// The uniform emission's spectrum; nullptr for an image's, which varies over the light.
  const LightSpectrum* emitted_spectrum() const override { return uniform_ ? &*uniform_ : nullptr; }
  bool is_textured() const { return textured_.has_value(); }

 private:
  struct Triangle {
    Vec3 v0, v1, v2;
    Vec3 normal;  // unit front normal; zero for degenerate triangles
    double area_m2 = 0.0;
    double weight = 0.0;            // w_k: the area, times an image's floored mean ∫L dλ
    double radiance_integral = 0.0;  // ∫L dλ, W/(m²·sr): uniform, or an image's mean over the triangle (unfloored)
  };
  /// Builds triangles_ and area_m2_ (weights still 0).
  void build_triangles(std::span<const Vec3> vertices_m, std::span<const uint32_t> indices);
  /// Sets each triangle's radiance integral and weight, and the distribution over them.
  void set_weights();
  /// The barycentrics (b0, b1, b2) of a point on t (clamped to it).
  static Vec3 barycentric_of(const Triangle& t, Vec3 point);
  /// Radiance leaving triangle k at barycentrics b (the uniform L, or the image's at the point's uv).
  SampledSpectrum emitted(size_t k, Vec3 barycentric, const SampledWavelengths& lambda) const;
  /// Triangles at least this large against the squared distance to their centroid are sampled by solid angle.
  /// At A/d² = 0.01 (a triangle ~1/10 of the distance across) area sampling's relative variance is already below
  /// ~1e-3 per sample, and the spherical triangle's trigonometry is not needed further away.
  static constexpr double kSolidAngleSamplingRatio = 0.01;
  /// Whether triangle t is sampled by solid angle from `reference` (else by area).
  static bool samples_solid_angle(const Triangle& t, Vec3 reference);
  /// p_k(ω) of triangle t's technique for a direction wi from `reference` that meets it at squared distance
  /// `distance_squared`, if seen from the emitting side, finite and > 0; else 0.
  float triangle_pdf(const Triangle& t, Vec3 reference, Vec3 wi, float distance_squared) const;
  /// A direction to triangle k by its technique; the density is `choice` (the probability of having chosen it)
  /// times p_k(ω).
  std::optional<LightSample> sample_triangle(size_t k, const LightReference& ref,
                                             const SampledWavelengths& lambda, Vec2 u, double choice) const;
  /// The density for a hit on triangle `k`: p_k(ω), times w_k/W for whole-mesh sampling (0 for bad hits).
  float hit_pdf(size_t k, const LightReference& ref, Vec3 wi, const SurfaceHit* hit, bool whole_mesh) const;

  std::vector<Triangle> triangles_;
  Distribution1D by_weight_;
  std::optional<LightSpectrum> uniform_;       // exactly one of these two is set
  std::optional<TexturedEmission> textured_;
  double area_m2_ = 0.0;
  double total_weight_ = 0.0;  // W = Σ w_k
  bool emits_ = false;         // some triangle has area and emission
  Vec3 weighted_centroid_m_{};  // Σ_k w_k c_k / Σ_k w_k (valid when emits_)
  int degenerate_count_ = 0;
  bool two_sided_;
};

}  // namespace rimu
