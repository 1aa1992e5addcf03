// Which light next-event estimation samples at a glossy vertex: chosen among a few candidates by what the BSDF
// passes from each (resampled importance sampling; Talbot, Cline & Egbert 2005).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

#include "transport/lights/light.h"
#include "transport/lights/light_sampler.h"
#include "transport/sampling/bit_mixing.h"

namespace rimu {

/// The light a vertex's next-event estimation samples, and the factor its contribution is multiplied by.
struct ChosenLight {
  LightChoice pick;
  /// Its radiance may be pending where the light was not resampled (Light::sample_part_li_deferred): call the
  /// light's resolve_radiance once the shadow ray has passed.
  LightSample sample;
  /// The BSDF towards the light times |cos θi|, per lane (never all zero).
  SampledSpectrum f_cos;
  /// What multiplies the usual estimate f·L/q (q = pick.probability · sample.pdf_solid_angle, the light sampler's
  /// density of this sample): exactly 1 for one candidate; for M candidates q × RIS's unbiased contribution weight
  /// (Σ_j w_j / M) / p̂(chosen).
  float density_scale = 1.0f;
  /// Whether the light was chosen among candidates (false: the light sampler's own choice, for one candidate or
  /// where the point has a single light to give).
  bool resampled = false;
};

/// Why: the light sampler (a light tree or by power) weighs lights by the irradiance each could bring, which
/// ignores the BSDF. At a rough-metal vertex (α = 0.01) lit by fifty downlights, the one light inside the narrow lobe
/// is chosen with the same few percent as any other, and when it is its glint arrives with f ≈ 10³ divided by that
/// probability: a firefly (docs/transport.md, "Glossy vertices and many lights"). Drawing M candidates from the
/// light sampler and keeping one in proportion to p̂ = m · Σ_lanes f·|cos θi|·L (unshadowed; m the MIS weight, below)
/// puts the lobe's light in the shadow ray up to M times as often. RIS is unbiased for any p̂ that is non-zero
/// wherever the integrand is (p̂ is the MIS-weighted integrand before visibility, with m at most the final weight,
/// which panes only raise), and its estimate f·L·W with W = (Σ w_j / M)/p̂(chosen), w_j = p̂(x_j)/p(x_j), replaces
/// f·L/p(x). The candidates live on the union of the lights' domains (a delta
/// light's point, an area light's directions), each density taken in its own light's measure, as p(x) is.
///
/// Random numbers: candidate 0 uses the sampler's (u_choice, u_light); candidate j shifts u_choice by j/M (so the M
/// choices are stratified along the light sampler's CDF) and u_light by j steps of the R2 sequence, modulo 1; the
/// reservoir's choice uses a hash of the sampler's numbers. The result is deterministic for the sampler's numbers.
///
/// `f_cos_towards(wi_world)` returns f·|cos θi| per lane, zero where the light cannot be reached (below an opaque
/// surface). `light_weight(sample, choice_probability)` returns the MIS weight the estimate will carry (1 for a
/// delta light; the power heuristic against BSDF sampling otherwise), and p̂ includes it: RIS then targets what
/// next-event estimation actually adds. Without it, at a glossy vertex under an environment the candidates
/// crowd into the lobe, where BSDF sampling takes nearly all the weight, and the rest of the sphere is reached
/// rarely and with large W: a rough conductor in a white furnace had 3× the standard error it has without.
/// With `candidates` ≤ 1 this is the light sampler's own choice, unchanged (light_weight is not called).
template <typename FCosTowards, typename LightWeight>
std::optional<ChosenLight> choose_light(const LightSampler& light_sampler, const std::vector<std::unique_ptr<Light>>& lights,
                                        const LightSamplingPoint& at, const LightReference& reference,
                                        const SampledWavelengths& lambda, int candidates, float u_choice, Vec2 u_light,
                                        const FCosTowards& f_cos_towards, const LightWeight& light_weight) {
  // Resampling reads each candidate's radiance; the light sampler's own choice leaves it to after the shadow ray.
  auto candidate_of = [&](const std::optional<LightChoice>& pick, Vec2 u_l,
                          bool defer_radiance = false) -> std::optional<ChosenLight> {
    if (!pick) return std::nullopt;
    const Light& light = *lights[size_t(pick->light)];
    const auto ls = defer_radiance ? light.sample_part_li_deferred(pick->part, reference, lambda, u_l)
                                   : light.sample_part_li(pick->part, reference, lambda, u_l);
    if (!ls) return std::nullopt;
    const float density = pick->probability * ls->pdf_solid_angle;
    if (!(density > 0.0f)) return std::nullopt;
    const SampledSpectrum f_cos = f_cos_towards(ls->wi);
    if (!(max_lane(f_cos) > 0.0f)) return std::nullopt;
    return ChosenLight{*pick, *ls, f_cos, 1.0f};
  };
  const std::optional<LightChoice> first = light_sampler.sample(at, u_choice);
  if (candidates <= 1) return candidate_of(first, u_light, true);
  // Where the sampler has one light to give (a scene lit by an environment alone, or a point where every other
  // light is culled), every candidate would be that light: resampling would only choose among its directions, which
  // an environment's own importance sampling and MIS already serve (docs/benchmarks.md, "Glossy vertices").
  // A probability of 1 is a property of the point, not of the draw, so skipping here keeps the estimate unbiased.
  if (first && first->probability >= 1.0f) return candidate_of(first, u_light, true);

  auto bits_of = [](float v) {
    uint32_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  const uint64_t key = (uint64_t(bits_of(u_choice)) << 32) ^ (uint64_t(bits_of(u_light.x)) << 16) ^ bits_of(u_light.y);
  auto unit = [](uint64_t h) { return float(h >> 40) * 0x1p-24f; };  // [0, 1)

  std::optional<ChosenLight> kept;
  float kept_target = 0.0f;
  float weight_sum = 0.0f;
  for (int j = 0; j < candidates; ++j) {
    float u_c = u_choice, ux = u_light.x, uy = u_light.y;
    if (j > 0) {
      u_c += float(j) / float(candidates);
      if (u_c >= 1.0f) u_c -= 1.0f;
      // A toroidal shift of the sampler's 2D point by j steps of the R2 sequence (Roberts 2018: 1/φ₂, 1/φ₂²), so
      // that whichever candidate is kept, a pixel's light points are its stratified ones shifted, not random ones.
      ux += float(j) * 0.7548776662f;
      uy += float(j) * 0.5698402910f;
      ux -= std::floor(ux);
      uy -= std::floor(uy);
      ux = std::fmin(ux, 0x1.fffffep-1f);
      uy = std::fmin(uy, 0x1.fffffep-1f);
    }
    // Candidate 0 is the sampler's own pick, already drawn above.
    auto c = candidate_of(j == 0 ? first : light_sampler.sample(at, u_c), Vec2{ux, uy});
    if (!c) continue;
    const float target = sum(c->f_cos * c->sample.radiance) * light_weight(c->sample, c->pick.probability);
    if (!(target > 0.0f) || !std::isfinite(target)) continue;
    const float w = target / (c->pick.probability * c->sample.pdf_solid_angle);
    weight_sum += w;
    const float u_keep = unit(mix_bits(key ^ (0xd1b54a32d192ed03ULL * uint64_t(j + 1))));
    if (u_keep * weight_sum < w) {  // keep candidate j with probability w / Σ_{i ≤ j} w_i (a weighted reservoir)
      kept = c;
      kept_target = target;
    }
  }
  if (!kept || !(weight_sum > 0.0f) || !std::isfinite(weight_sum)) return std::nullopt;
  kept->density_scale =
      kept->pick.probability * kept->sample.pdf_solid_angle * weight_sum / (float(candidates) * kept_target);
  kept->resampled = true;
  return kept;
}

}  // namespace rimu
