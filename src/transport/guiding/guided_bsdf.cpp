#include "transport/guiding/guided_bsdf.h"

#include <cmath>

#include "transport/sampling/equal_area_square.h"

namespace rimu {

Vec3 VertexGuide::sample(float u_select, Vec2 u, float& pdf) const {
  if (tree_) {
    // The guide's density from the square point it drew (no inverse map: an atan2 fewer per guided direction).
    const Vec2 square = tree_->sample_square(u);
    pdf = tree_->pdf_direction_at_square(square);
    return equal_area_square_to_sphere(square);
  }
  const Vec3 wi = mixture_.sample(u_select, u);
  pdf = mixture_.pdf(wi);
  return wi;
}

float VertexGuide::pdf(Vec3 direction) const { return tree_ ? tree_->pdf_direction(direction) : mixture_.pdf(direction); }

std::optional<BsdfSample> GuidedBsdf::sample(Vec3 wo, float u_lobe, Vec2 u) const {
  if (!guide_) return bsdf_.sample(wo, u_lobe, u);
  if (u_lobe < alpha_) {
    float guide_pdf = 0.0f;
    const Vec3 wi = frame_.to_local(guide_->sample(u_lobe / alpha_, u, guide_pdf));
    BsdfSample s;
    s.wi = wi;
    s.f = bsdf_.eval(wo, wi);
    s.pdf = Float4(alpha_ * guide_pdf) + Float4(1.0f - alpha_) * bsdf_.pdf(wo, wi);
    if (!(s.pdf[0] > 0.0f)) return std::nullopt;
    return s;
  }
  // The BSDF's own lobe choice gets u_lobe rescaled to [0, 1) (the same stratification, one decision further).
  const float u_bsdf = std::fmin((u_lobe - alpha_) / (1.0f - alpha_), 0x1.fffffep-1f);
  std::optional<BsdfSample> s = bsdf_.sample(wo, u_bsdf, u);
  if (!s || s->is_delta) return s;  // guided BSDFs have no delta lobes; kept exact if one ever does
  s->pdf = Float4(alpha_ * guide_->pdf(frame_.to_world(s->wi))) + Float4(1.0f - alpha_) * s->pdf;
  return s;
}

SampledSpectrum GuidedBsdf::pdf(Vec3 wo, Vec3 wi) const {
  const SampledSpectrum bsdf_pdf = bsdf_.pdf(wo, wi);
  if (!guide_) return bsdf_pdf;
  return Float4(alpha_ * guide_->pdf(frame_.to_world(wi))) + Float4(1.0f - alpha_) * bsdf_pdf;
}

}  // namespace rimu
