#include "transport/guiding/vmf_mixture.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "transport/geometry/frame.h"
#include "transport/sampling/equal_area_square.h"

namespace rimu {
namespace {

constexpr float kInvFourPi = float(0.25 / std::numbers::pi);
constexpr float kTwoPi = float(2.0 * std::numbers::pi);

// A fitted sample: its direction and inverse distance as seen from the pivot.
struct PivotSample {
  Vec3 direction;
  float inverse_distance = 0.0f;
  float weight = 0.0f;
};

float kappa_from_mean_resultant(float r) {
  // Banerjee et al. 2005's approximation of the inverse of A₃(κ) = coth κ − 1/κ.
  r = std::clamp(r, 0.0f, 0.9999f);
  return r * (3.0f - r * r) / (1.0f - r * r);
}

}  // namespace

float vmf_normalisation(float kappa) {
  if (kappa < 1e-4f) return kInvFourPi;
  return kappa / (kTwoPi * float(-std::expm1(-2.0 * double(kappa))));
}

float sample_vmf_cosine(float kappa, float u) {
  if (kappa < 1e-4f) return 2.0f * u - 1.0f;
  // 1 + log(u + (1 − u) e^{−2κ}) / κ, the inverse of the cosine's distribution function.
  const float w = 1.0f + std::log(u + (1.0f - u) * std::exp(-2.0f * kappa)) / kappa;
  return std::clamp(w, -1.0f, 1.0f);
}

Vec3 VertexMixture::sample(float u_lobe, Vec2 u) const {
  int k = 0;
  float cumulative = weight[0];
  while (k + 1 < count && u_lobe >= cumulative) cumulative += weight[size_t(++k)];
  const float cos_theta = sample_vmf_cosine(kappa[size_t(k)], u.x);
  const float sin_theta = std::sqrt(std::fmax(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = kTwoPi * u.y;
  return Frame::from_normal(mean[size_t(k)]).to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta});
}

float VertexMixture::pdf(Vec3 direction) const {
  float density = 0.0f;
  for (int k = 0; k < count; ++k)
    density += weight[size_t(k)] * normalisation[size_t(k)] *
               std::exp(kappa[size_t(k)] * (dot(mean[size_t(k)], direction) - 1.0f));
  return density;
}

VmfMixture VmfMixture::fit(std::span<const GuidingSample> samples, const VmfMixtureSettings& settings) {
  VmfMixture mixture;
  double total = 0.0, total_squared = 0.0;
  size_t weighted = 0;
  Vec3 pivot_sum{0, 0, 0};
  for (const GuidingSample& s : samples) {
    const float w = s.direction.weight;
    if (!(w > 0.0f)) continue;
    total += w;
    total_squared += double(w) * w;
    pivot_sum = pivot_sum + s.position * w;
    ++weighted;
  }
  if (!(total > 0.0)) return mixture;
  mixture.effective_samples_ = float(total * total / total_squared);
  mixture.pivot_ = pivot_sum / float(total);

  // The samples as seen from the pivot: the point each one's light came from, re-aimed (parallax), at a fixed
  // stride when there are more than the fit reads.
  const size_t stride = std::max<size_t>(1, (weighted + size_t(settings.max_fit_samples) - 1) / size_t(settings.max_fit_samples));
  std::vector<PivotSample> fit_samples;
  fit_samples.reserve(weighted / stride + 1);
  size_t index = 0;
  for (const GuidingSample& s : samples) {
    if (!(s.direction.weight > 0.0f)) continue;
    if (index++ % stride != 0) continue;
    const Vec3 direction = equal_area_square_to_sphere(s.direction.square);
    PivotSample p{direction, 0.0f, s.direction.weight};
    if (std::isfinite(s.distance)) {
      const Vec3 to_light = s.position + direction * s.distance - mixture.pivot_;
      const float d = length(to_light);
      if (d > 0.0f) {
        p.direction = to_light / d;
        p.inverse_distance = 1.0f / d;
      }
    }
    fit_samples.push_back(p);
  }

  // Initial lobes spread over where the light is, as k-means++ does but deterministic: the first at the weight's
  // median, each next one at a fixed quantile of weight × (distance to the nearest lobe so far)², so that a sun and
  // the sky around it start in different lobes (lobes started together stay together under EM).
  const int lobe_count = std::clamp(settings.lobes, 1, VertexMixture::kMaxLobes);
  const size_t lobe_slots = size_t(lobe_count);
  std::vector<VmfLobe> lobes(lobe_slots);
  {
    std::vector<float> nearest(fit_samples.size(), 4.0f);
    auto pick = [&](double fraction, auto&& score) {
      double total_score = 0.0;
      for (size_t i = 0; i < fit_samples.size(); ++i) total_score += score(i);
      const double target = fraction * total_score;
      double cumulative = 0.0;
      for (size_t i = 0; i < fit_samples.size(); ++i)
        if ((cumulative += score(i)) >= target && score(i) > 0.0) return i;
      return fit_samples.size() - 1;
    };
    for (int k = 0; k < lobe_count; ++k) {
      // Golden-ratio fractions: well spread, deterministic.
      const double fraction = k == 0 ? 0.5 : std::fmod(0.5 + 0.6180339887498949 * k, 1.0);
      const size_t chosen = pick(fraction, [&](size_t i) {
        return double(fit_samples[i].weight) * (k == 0 ? 1.0 : double(nearest[i]) * nearest[i]);
      });
      lobes[size_t(k)] = {fit_samples[chosen].direction, 20.0f, 1.0f / float(lobe_count), 0.0f};
      for (size_t i = 0; i < fit_samples.size(); ++i)
        nearest[i] = std::min(nearest[i], 1.0f - dot(fit_samples[i].direction, fit_samples[chosen].direction));
    }
  }

  std::vector<double> w_sum(lobe_slots), w2_sum(lobe_slots), inverse_distance_sum(lobe_slots);
  std::vector<Vec3> direction_sum(lobe_slots);
  std::vector<float> log_term(lobe_slots), responsibility(lobe_slots);
  // A uniform background component explains the light that no lobe should (a sky around a sun, the diffuse rest of
  // a room), so that lobes are free to tighten on what is concentrated; it is dropped after the fit: the BSDF's share
  // of the guided mixture samples that light.
  float background = settings.background_component ? 0.5f : 0.0f;
  for (int iteration = 0; iteration < settings.iterations; ++iteration) {
    std::fill(w_sum.begin(), w_sum.end(), 0.0);
    std::fill(w2_sum.begin(), w2_sum.end(), 0.0);
    std::fill(inverse_distance_sum.begin(), inverse_distance_sum.end(), 0.0);
    std::fill(direction_sum.begin(), direction_sum.end(), Vec3{0, 0, 0});
    for (int k = 0; k < lobe_count; ++k) {
      const VmfLobe& l = lobes[size_t(k)];
      log_term[size_t(k)] = l.weight > 0.0f ? std::log(l.weight * vmf_normalisation(l.kappa)) : -INFINITY;
    }
    const float log_background = background > 0.0f ? std::log(background * kInvFourPi) : -INFINITY;
    double background_sum = 0.0;
    for (const PivotSample& p : fit_samples) {
      // E-step: each lobe's responsibility for the sample, in logs for large κ.
      float largest = log_background;
      for (int k = 0; k < lobe_count; ++k) {
        const VmfLobe& l = lobes[size_t(k)];
        const float v = log_term[size_t(k)] + l.kappa * (dot(l.mean, p.direction) - 1.0f);
        responsibility[size_t(k)] = v;
        largest = std::max(largest, v);
      }
      if (!std::isfinite(largest)) continue;
      const float background_share = std::exp(log_background - largest);
      float sum = background_share;
      for (int k = 0; k < lobe_count; ++k) sum += responsibility[size_t(k)] = std::exp(responsibility[size_t(k)] - largest);
      background_sum += p.weight * background_share / sum;
      for (int k = 0; k < lobe_count; ++k) {
        const float wr = p.weight * responsibility[size_t(k)] / sum;
        w_sum[size_t(k)] += wr;
        w2_sum[size_t(k)] += double(wr) * wr;
        direction_sum[size_t(k)] = direction_sum[size_t(k)] + p.direction * wr;
        inverse_distance_sum[size_t(k)] += double(wr) * p.inverse_distance;
      }
    }
    // M-step, with the concentration shrunk towards 0 for lobes resting on few effective samples.
    double all = background_sum;
    for (double w : w_sum) all += w;
    if (!(all > 0.0)) break;
    if (background > 0.0f) background = float(background_sum / all);
    for (int k = 0; k < lobe_count; ++k) {
      VmfLobe& l = lobes[size_t(k)];
      if (!(w_sum[size_t(k)] > 0.0)) {
        l.weight = 0.0f;
        continue;
      }
      const float resultant = length(direction_sum[size_t(k)]);
      l.weight = float(w_sum[size_t(k)] / all);
      if (resultant > 0.0f) l.mean = direction_sum[size_t(k)] / resultant;
      const double n = w_sum[size_t(k)] * w_sum[size_t(k)] / w2_sum[size_t(k)];
      const float r = float(resultant / w_sum[size_t(k)]);
      l.kappa = std::min(kappa_from_mean_resultant(r) * float(n / (n + settings.concentration_prior)), settings.max_kappa);
      l.inverse_distance = float(inverse_distance_sum[size_t(k)] / w_sum[size_t(k)]);
    }
  }
  for (const VmfLobe& l : lobes)
    if (l.weight > 0.0f) mixture.lobes_.push_back(l);
  // Renormalise after dropping empty lobes and the background.
  float sum = 0.0f;
  for (const VmfLobe& l : mixture.lobes_) sum += l.weight;
  for (VmfLobe& l : mixture.lobes_) {
    l.weight /= sum;
    l.normalisation = vmf_normalisation(l.kappa);
  }
  return mixture;
}

VertexMixture VmfMixture::at(Vec3 position) const {
  VertexMixture v;
  v.count = int(lobes_.size());
  for (size_t k = 0; k < lobes_.size(); ++k) {
    const VmfLobe& l = lobes_[k];
    Vec3 mean = l.mean;
    if (l.inverse_distance > 0.0f) {
      const Vec3 to_light = pivot_ + l.mean / l.inverse_distance - position;
      const float d = length(to_light);
      if (d * l.inverse_distance > 1e-4f) mean = to_light / d;
    }
    v.mean[k] = mean;
    v.kappa[k] = l.kappa;
    v.weight[k] = l.weight;
    v.normalisation[k] = l.normalisation;
  }
  return v;
}

}  // namespace rimu
