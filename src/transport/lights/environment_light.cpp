#include "transport/lights/environment_light.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

#include "transport/sampling/distribution_coarsening.h"
#include "transport/sampling/equal_area_square.h"
#include "transport/lights/light_warps.h"

namespace rimu {

namespace {
constexpr float kPiF = std::numbers::pi_v<float>;
constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPiF);
/// Share of the mean luminance added to every pixel's sampling weight (see the header).
constexpr double kLuminanceFloor = 1e-3;
/// The relative variance a coarser sampling table may add to a light sample (see the header): 1 %.
constexpr double kMaxAddedSamplingVariance = 0.01;
}  // namespace

EnvironmentLight::EnvironmentLight(LightSpectrum radiance)
    : constant_(std::move(radiance)), frame_{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}} {
  mean_radiance_integral_ = constant_->integral_360_830();
}

EnvironmentLight::EnvironmentLight(std::shared_ptr<const RadianceImage> image, double scale, Frame frame,
                                   EnvironmentMapping mapping)
    : image_(std::move(image)), image_scale_(scale), frame_(frame), mapping_(mapping) {
  assert(image_ && image_->width() > 0 && image_->height() > 0 && std::isfinite(scale) && scale >= 0.0);
  const int w = image_->width(), h = image_->height();
  // The sampling weights in float (a 2048² sky's 4 M weights: 16 MiB, not 32), sums in double.
  std::vector<float> luminance(size_t(w) * h);
  double mean = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float lum = image_->luminance(x, y);
      assert(std::isfinite(lum) && lum >= 0.0f);
      luminance[size_t(y) * w + x] = std::max(0.0f, lum);
      mean += luminance[size_t(y) * w + x];
    }
  mean /= double(w) * h;
  // Ω_y = (2π/w)(cos θ_top − cos θ_bottom) of a pixel in row y (equirectangular) or 4π/(w·h) (equal-area), for
  // the power estimate.
  const bool equal_area = mapping_ == EnvironmentMapping::equal_area_octahedral;
  double radiance_times_solid_angle = 0.0;
  std::vector<double> row_integrals(w);
  for (int y = 0; y < h; ++y) {
    image_->radiance_integrals(y, row_integrals);
    const double theta_center = std::numbers::pi * (y + 0.5) / h;
    const double sin_theta = equal_area ? 1.0 : std::sin(theta_center);
    const double pixel_sr = equal_area ? 4.0 * std::numbers::pi / (double(w) * h)
                                       : 2.0 * std::numbers::pi / w *
                                             (std::cos(std::numbers::pi * y / h) - std::cos(std::numbers::pi * (y + 1) / h));
    for (int x = 0; x < w; ++x) {
      float& weight = luminance[size_t(y) * w + x];
      weight = float((double(weight) + kLuminanceFloor * mean) * sin_theta);
      radiance_times_solid_angle += row_integrals[x] * pixel_sr;
    }
  }
  mean_radiance_integral_ = image_scale_ * radiance_times_solid_angle / (4.0 * std::numbers::pi);
  distribution_ = sampling_table(luminance, w, h, distribution_block_);
}

Distribution2D EnvironmentLight::sampling_table(std::span<const float> weights, int width, int height,
                                                SamplingBlock& block) {
  block = choose_sampling_block(weights, width, height, kMaxAddedSamplingVariance);
  if (block.factor == 1) return Distribution2D(weights, width, height);
  return Distribution2D(block_sums(weights, width, height, block.factor), width / block.factor,
                        height / block.factor);
}

Vec2 EnvironmentLight::direction_to_uv(Vec3 direction) const {
  const Vec3 d = frame_.to_local(direction);
  const float below_one = std::nextafter(1.0f, 0.0f);
  if (mapping_ == EnvironmentMapping::equal_area_octahedral) {
    const Vec2 uv = equal_area_sphere_to_square(d);
    return {std::min(uv.x, below_one), std::min(uv.y, below_one)};
  }
  const float theta = std::acos(std::clamp(d.z, -1.0f, 1.0f));
  float phi = std::atan2(-d.y, d.x);
  if (phi < 0.0f) phi += 2.0f * kPiF;
  return {std::min(phi / (2.0f * kPiF), below_one), std::min(theta / kPiF, below_one)};
}

Vec3 EnvironmentLight::uv_to_direction(Vec2 uv) const {
  if (mapping_ == EnvironmentMapping::equal_area_octahedral) return frame_.to_world(equal_area_square_to_sphere(uv));
  const float theta = kPiF * uv.y, phi = 2.0f * kPiF * uv.x;
  const float sin_theta = std::sin(theta);
  return frame_.to_world({sin_theta * std::cos(phi), -sin_theta * std::sin(phi), std::cos(theta)});
}

SampledSpectrum EnvironmentLight::lookup(Vec2 uv, const SampledWavelengths& lambda) const {
  const int x = std::min(int(uv.x * float(image_->width())), image_->width() - 1);
  const int y = std::min(int(uv.y * float(image_->height())), image_->height() - 1);
  return image_->radiance(x, y, lambda) * Float4(float(image_scale_));
}

SampledSpectrum EnvironmentLight::radiance_escaped(Vec3 direction, const SampledWavelengths& lambda) const {
  if (constant_) return constant_->sample(lambda);
  return lookup(direction_to_uv(direction), lambda);
}

float EnvironmentLight::pdf_li(const LightReference& ref, Vec3 wi, const SurfaceHit*) const {
  if (!(mean_radiance_integral_ > 0.0) || !sampled_by_nee()) return 0.0f;
  if (!portals_.empty()) return portals_.pdf(ref.position, wi);
  if (distribution_.is_zero()) return kUniformSpherePdf;
  if (mapping_ == EnvironmentMapping::equal_area_octahedral) {
    // dω = 4π du dv everywhere (the map preserves area).
    const float pdf = sampling_distribution(ref).pdf(direction_to_uv(wi)) / (4.0f * kPiF);
    return std::isfinite(pdf) ? pdf : 0.0f;
  }
  const Vec3 d = frame_.to_local(wi);
  const float sin_theta = std::sqrt(std::fmax(0.0f, d.x * d.x + d.y * d.y));
  if (!(sin_theta > 0.0f)) return 0.0f;
  const float pdf = sampling_distribution(ref).pdf(direction_to_uv(wi)) / (2.0f * kPiF * kPiF * sin_theta);
  return std::isfinite(pdf) ? pdf : 0.0f;
}

std::optional<LightSample> EnvironmentLight::sample_li(const LightReference& ref, const SampledWavelengths& lambda,
                                                       Vec2 u) const {
  std::optional<LightSample> s = sample_direction(ref, u);
  if (s) s->radiance = radiance_escaped(s->wi, lambda);
  return s;
}

std::optional<LightSample> EnvironmentLight::sample_part_li_deferred(int, const LightReference& ref,
                                                                     const SampledWavelengths&, Vec2 u) const {
  std::optional<LightSample> s = sample_direction(ref, u);
  if (s) s->radiance_pending = true;
  return s;
}

void EnvironmentLight::resolve_radiance(LightSample& sample, const SampledWavelengths& lambda) const {
  if (!sample.radiance_pending) return;
  sample.radiance = radiance_escaped(sample.wi, lambda);
  sample.radiance_pending = false;
}

std::optional<LightSample> EnvironmentLight::sample_direction(const LightReference& ref, Vec2 u) const {
  if (!(mean_radiance_integral_ > 0.0) || !sampled_by_nee()) return std::nullopt;
  LightSample s;
  if (!portals_.empty()) {
    const auto through = portals_.sample(ref.position, u);
    if (!through) return std::nullopt;
    s.wi = through->wi;
    s.pdf_solid_angle = through->pdf_sr;
  } else if (distribution_.is_zero()) {
    s.wi = sample_uniform_sphere(u);
    s.pdf_solid_angle = kUniformSpherePdf;
  } else {
    // The density and radiance are evaluated from the returned direction, exactly as pdf_li and
    // radiance_escaped do, so a BSDF-sampled ray along the same direction gets the same numbers even where the
    // uv → direction → uv round trip crosses a pixel edge by an ulp.
    s.wi = normalize(uv_to_direction(sampling_distribution(ref).sample(u).uv));
    s.pdf_solid_angle = pdf_li(ref, s.wi);
    if (s.pdf_solid_angle == 0.0f) return std::nullopt;
  }
  return s;
}

void EnvironmentLight::set_combined_with_bsdf_sampling(bool combined) {
  combined_with_bsdf_ = combined;
  compensated_ = Distribution2D();
  if (!combined || !image_ || distribution_.is_zero()) return;
  const int w = image_->width(), h = image_->height();
  const bool equal_area = mapping_ == EnvironmentMapping::equal_area_octahedral;
  // Ȳ over solid angle: rows of an equirectangular map weighted by sin θ (their pixels' solid angle).
  double weighted = 0.0, total_weight = 0.0;
  std::vector<double> sin_theta(h, 1.0);
  for (int y = 0; y < h; ++y) {
    if (!equal_area) sin_theta[y] = std::sin(std::numbers::pi * (y + 0.5) / h);
    for (int x = 0; x < w; ++x) weighted += sin_theta[y] * std::max(0.0, double(image_->luminance(x, y)));
    total_weight += sin_theta[y] * w;
  }
  const double mean = weighted / total_weight;
  std::vector<float> weights(size_t(w) * h);  // float, as the main table's
  bool any = false;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float above = float(std::max(0.0, double(image_->luminance(x, y)) - mean) * sin_theta[y]);
      weights[size_t(y) * w + x] = above;
      any = any || above > 0.0;
    }
  if (any) compensated_ = sampling_table(weights, w, h, compensated_block_);
}

std::optional<LightBounds> EnvironmentLight::part_bounds(int part) const {
  if (part != 0) return std::nullopt;
  return portal_light_bounds(portals_, mean_radiance_integral_);
}

double EnvironmentLight::total_power_w(double scene_radius_m) const {
  // A portal of area A under radiance L from its whole outer hemisphere passes ∫ L cos θ dω dA = π L A.
  if (!portals_.empty()) return std::numbers::pi * portals_.total_area_m2() * mean_radiance_integral_;
  return 4.0 * std::numbers::pi * std::numbers::pi * scene_radius_m * scene_radius_m * mean_radiance_integral_;
}

}  // namespace rimu
