#include "transport/bsdfs/dielectric_bsdf.h"

#include <cmath>
#include <numbers>

#include "transport/bsdfs/fresnel.h"
#include "transport/sampling/direction_warps.h"

namespace rimu {

std::optional<Vec3> refract(Vec3 w, Vec3 n, float eta_ratio) {
  // Snell: sin θt = sin θi / η. The transmitted direction is the tangential part of −w scaled by 1/η plus
  // −cos θt along the normal: wt = −w/η + (cos θi/η − cos θt) n.
  const float cos_i = dot(w, n);
  const float sin2_t = std::fmax(0.0f, 1.0f - cos_i * cos_i) / (eta_ratio * eta_ratio);
  if (sin2_t >= 1.0f) return std::nullopt;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  return -w / eta_ratio + (cos_i / eta_ratio - cos_t) * n;
}

void DielectricBsdf::eval_rough_lane(Vec3 wo, Vec3 wi, float eta, float& f, float& pdf, float* pdf_reverse) const {
  f = pdf = 0.0f;
  if (pdf_reverse) *pdf_reverse = 0.0f;
  const float cos_o = wo.z, cos_i = wi.z;
  if (cos_o == 0.0f || cos_i == 0.0f) return;
  const bool reflection = cos_o * cos_i > 0.0f;
  const float eta_ratio = reflection ? 1.0f : (cos_o > 0.0f ? eta : 1.0f / eta);  // η' = n_i / n_o
  // Generalised half vector (Walter et al. 2007, Eq. 16), oriented to the outside (+z).
  Vec3 m = wi * eta_ratio + wo;
  const float len2 = length_squared(m);
  if (!(len2 > 0.0f)) return;
  m = m / std::sqrt(len2);
  if (m.z < 0.0f) m = -m;
  const float wo_m = dot(wo, m), wi_m = dot(wi, m);
  // A microfacet seen from its back by either direction contributes nothing (Walter et al. 2007, Eq. 20's χ⁺).
  if (wo_m * cos_o <= 0.0f || wi_m * cos_i <= 0.0f) return;
  const float fresnel = fresnel_dielectric(wo_m, eta);
  // D, Λ(wo) and Λ(wi) once each: G2 = 1/(1 + Λo + Λi), and the visible-normal density of m seen from wo,
  // D_wo(m) = G1(wo) |wo·m| D(m) / |cos θo| with G1(wo) = 1/(1 + Λo) (TrowbridgeReitz::visible_d; m faces wo,
  // checked above).
  const float d = distribution_.d(m);
  const float lambda_o = distribution_.lambda(wo), lambda_i = distribution_.lambda(wi);
  const float g = 1.0f / (1.0f + lambda_o + lambda_i);
  const float visible = TrowbridgeReitz::visible_d(d, lambda_o, wo_m, cos_o);
  // Seen from wi instead (pdf(wi, wo), only when asked): the same m, D and Fresnel factor (Snell's law holds at m,
  // so F is the same from both sides), wi's visible normals, and for refraction the Jacobian's denominator
  // (wo·m + wi·m η')², which is η'² times this one.
  const float visible_from_i = pdf_reverse ? TrowbridgeReitz::visible_d(d, lambda_i, wi_m, cos_i) : 0.0f;
  float reverse = 0.0f;
  if (reflection) {
    f = d * g * fresnel / (4.0f * std::fabs(cos_o * cos_i));
    pdf = visible / (4.0f * std::fabs(wo_m)) * fresnel;
    if (pdf_reverse) reverse = visible_from_i / (4.0f * std::fabs(wi_m)) * fresnel;
  } else {
    const float denom = (wi_m + wo_m / eta_ratio) * (wi_m + wo_m / eta_ratio);
    if (!(denom > 0.0f)) return;
    const float transmit = 1.0f - fresnel;
    f = transmit * d * g * std::fabs(wi_m * wo_m / (cos_i * cos_o * denom)) / (eta_ratio * eta_ratio);
    pdf = visible * std::fabs(wi_m) / denom * transmit;
    if (pdf_reverse) reverse = visible_from_i * std::fabs(wo_m) / (denom * eta_ratio * eta_ratio) * transmit;
  }
  if (!std::isfinite(f) || !std::isfinite(pdf) || !std::isfinite(reverse)) f = pdf = reverse = 0.0f;
  if (pdf_reverse) *pdf_reverse = reverse;
}

void DielectricBsdf::eval_rough(Vec3 wo, Vec3 wi, SampledSpectrum& f, SampledSpectrum& pdf,
                                SampledSpectrum* pdf_reverse) const {
  if ((eta_ == Float4(eta_[0])).all()) {
    float f0, pdf0, reverse0;
    eval_rough_lane(wo, wi, eta_[0], f0, pdf0, pdf_reverse ? &reverse0 : nullptr);
    f = Float4(f0);
    pdf = Float4(pdf0);
    if (pdf_reverse) *pdf_reverse = Float4(reverse0);
    return;
  }
  alignas(16) float fs[4], pdfs[4], reverses[4];
  for (int lane = 0; lane < kLaneCount; ++lane)
    eval_rough_lane(wo, wi, eta_[lane], fs[lane], pdfs[lane], pdf_reverse ? &reverses[lane] : nullptr);
  f = Float4::load(fs);
  pdf = Float4::load(pdfs);
  if (pdf_reverse) *pdf_reverse = Float4::load(reverses);
}

SampledSpectrum DielectricBsdf::eval_with_reverse_pdf(Vec3 wo, Vec3 wi, SampledSpectrum& pdf_reverse) const {
  if ((diffuse_entry_ && (wo.z < 0.0f || wi.z < 0.0f)) || is_smooth()) {
    pdf_reverse = pdf(wi, wo);
    return eval(wo, wi);
  }
  SampledSpectrum f, pdf_forward;
  eval_rough(wo, wi, f, pdf_forward, &pdf_reverse);
  return f;
}

double DielectricBsdf::diffuse_entry_normalisation(double eta) {
  // 1 − F̄_int = (1 − F̄_ext)/η² (reciprocity, fresnel.h).
  const double inside_transmittance = (1.0 - fresnel_diffuse_reflectance(eta)) / (eta * eta);
  return 1.0 / (std::numbers::pi * inside_transmittance);
}

namespace {

// The way out of a diffuse-entry boundary towards wi (wi.z > 0), given leave = 1 − F(wo) per lane: f and the
// density of sample() (leave × cosine/π), for eval() and sample(): sample() has F(wo) from its lobe choice.
struct InsideLobe {
  SampledSpectrum f, pdf;
};
InsideLobe inside_lobe(SampledSpectrum leave, Vec3 wi, SampledSpectrum eta, SampledSpectrum normalisation) {
  if (!(wi.z > 0.0f)) return {Float4(0.0f), Float4(0.0f)};  // the mirror is a delta; nothing else stays inside
  const SampledSpectrum enter = Float4(1.0f) - fresnel_dielectric(Float4(wi.z), eta);
  return {leave * enter * normalisation, leave * Float4(cosine_hemisphere_pdf(wi.z))};
}

}  // namespace

SampledSpectrum DielectricBsdf::eval_inside_diffuse_entry(Vec3 wo, Vec3 wi) const {
  return inside_lobe(Float4(1.0f) - fresnel_dielectric(Float4(wo.z), eta_), wi, eta_, entry_norm_).f;
}

SampledSpectrum DielectricBsdf::pdf_inside_diffuse_entry(Vec3 wo, Vec3 wi) const {
  if (!(wi.z > 0.0f)) return Float4(0.0f);
  return (Float4(1.0f) - fresnel_dielectric(Float4(wo.z), eta_)) * Float4(cosine_hemisphere_pdf(wi.z));
}

std::optional<BsdfSample> DielectricBsdf::sample_inside_diffuse_entry(Vec3 wo, float u_lobe, Vec2 u) const {
  const SampledSpectrum reflectance = fresnel_dielectric(Float4(wo.z), eta_);
  if (u_lobe < reflectance[0]) {
    const Vec3 wi{-wo.x, -wo.y, wo.z};
    return BsdfSample{wi, reflectance / Float4(std::fabs(wo.z)), reflectance, true};
  }
  const Vec3 wi = sample_cosine_hemisphere(u);
  if (!(wi.z > 0.0f)) return std::nullopt;  // the horizon has density 0
  const InsideLobe lobe = inside_lobe(Float4(1.0f) - reflectance, wi, eta_, entry_norm_);
  BsdfSample s{wi, lobe.f, lobe.pdf};
  if (!(s.pdf[0] > 0.0f)) return std::nullopt;
  s.eta = 1.0f / eta_[0];
  return s;
}

SampledSpectrum DielectricBsdf::eval(Vec3 wo, Vec3 wi) const {
  if (diffuse_entry_ && wo.z < 0.0f) return eval_inside_diffuse_entry(wo, wi);
  if (is_smooth()) return Float4(0.0f);
  SampledSpectrum f, pdf;
  eval_rough(wo, wi, f, pdf);
  return f;
}

SampledSpectrum DielectricBsdf::pdf(Vec3 wo, Vec3 wi) const {
  if (diffuse_entry_ && wo.z < 0.0f) return pdf_inside_diffuse_entry(wo, wi);
  if (is_smooth()) return Float4(0.0f);
  SampledSpectrum f, pdf;
  eval_rough(wo, wi, f, pdf);
  return pdf;
}

std::optional<BsdfSample> DielectricBsdf::sample_smooth(Vec3 wo, float u_lobe) const {
  const float cos_o = wo.z;
  const SampledSpectrum reflectance = fresnel_dielectric(Float4(cos_o), eta_);
  if (u_lobe < reflectance[0]) {
    // Mirror: f = R δ / cos θi, chosen with probability R, so the weight f·cos/pdf is 1 in the hero lane.
    const Vec3 wi{-wo.x, -wo.y, wo.z};
    return BsdfSample{wi, reflectance / Float4(std::fabs(cos_o)), reflectance, true};
  }
  const SampledSpectrum eta_ratio = select(Float4(cos_o) > Float4(0.0f), eta_, Float4(1.0f) / eta_);
  const Vec3 normal{0.0f, 0.0f, cos_o > 0.0f ? 1.0f : -1.0f};
  const auto wi = refract(wo, normal, eta_ratio[0]);
  // R(hero) < 1 here, so the hero is not totally reflected; a transmitted direction on the horizon would have
  // cos θi = 0 and an infinite f.
  if (!wi || wi->z == 0.0f) return std::nullopt;
  const SampledSpectrum transmittance = Float4(1.0f) - reflectance;
  SampledSpectrum f = transmittance / (Float4(std::fabs(wi->z)) * eta_ratio * eta_ratio);
  SampledSpectrum pdf = transmittance;
  // Lanes with another η refract elsewhere: for them this direction has density 0 and f has no delta here.
  const Mask4 other_direction = eta_ != Float4(eta_[0]);
  f = select(other_direction, Float4(0.0f), f);
  pdf = select(other_direction, Float4(0.0f), pdf);
  BsdfSample s{*wi, f, pdf, true};
  s.wavelength_dependent_direction = other_direction.any();
  s.eta = eta_ratio[0];
  return s;
}

std::optional<BsdfSample> DielectricBsdf::sample(Vec3 wo, float u_lobe, Vec2 u) const {
  if (wo.z == 0.0f) return std::nullopt;
  if (diffuse_entry_ && wo.z < 0.0f) return sample_inside_diffuse_entry(wo, u_lobe, u);
  if (is_smooth()) return sample_smooth(wo, u_lobe);

  const Vec3 m = distribution_.sample_visible(wo, u);  // on wo's side: wo·m > 0
  const float wo_m = dot(wo, m);
  if (!(wo_m > 0.0f)) return std::nullopt;
  // Fresnel at this microfacet for the hero, with the facet's normal seen from outside.
  const float hero_reflectance = fresnel_dielectric(m.z < 0.0f ? -wo_m : wo_m, eta_[0]);
  Vec3 wi;
  float eta = 1.0f;
  if (u_lobe < hero_reflectance) {
    wi = reflect(wo, m);
    if (!(wi.z * wo.z > 0.0f)) return std::nullopt;
  } else {
    const float eta_ratio = wo.z > 0.0f ? eta_[0] : 1.0f / eta_[0];
    const auto t = refract(wo, m, eta_ratio);
    if (!t || !(t->z * wo.z < 0.0f)) return std::nullopt;
    wi = *t;
    eta = eta_ratio;
  }
  // f and the four pdfs from the same code as eval()/pdf(), so sample() can never disagree with them.
  BsdfSample s{wi, Float4(0.0f), Float4(0.0f)};
  eval_rough(wo, wi, s.f, s.pdf);
  if (!(s.pdf[0] > 0.0f)) return std::nullopt;
  s.eta = eta;
  return s;
}

}  // namespace rimu
