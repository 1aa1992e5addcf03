#include "render/reports/light_meter.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "spectral/error.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "transport/integrators/shadow_passage.h"
#include "transport/sampling/sampler.h"

namespace rimu {
namespace {


// The mean of `batches` batch means of `values` (consecutive runs of sizes n/batches, the first n % batches one
// longer), with their spread over √batches as the standard error.
MeterReading batch_mean_and_standard_error(const std::vector<double>& values, int batches) {
  MeterReading r;
  r.samples = int(values.size());
  if (values.empty()) return r;
  if (batches <= 1) return mean_and_standard_error(values);
  const size_t n = values.size(), base = n / size_t(batches), extra = n % size_t(batches);
  std::vector<double> means;
  for (size_t b = 0, start = 0; b < size_t(batches); ++b) {
    const size_t size = base + (b < extra ? 1 : 0);
    double sum = 0.0;
    for (size_t k = start; k < start + size; ++k) sum += values[k];
    means.push_back(sum / double(size));
    start += size;
  }
  MeterReading m = mean_and_standard_error(means);
  m.samples = r.samples;
  return m;
}

}  // namespace

MeterReading mean_and_standard_error(std::span<const double> values) {
  MeterReading r;
  r.samples = int(values.size());
  if (values.empty()) return r;
  double sum = 0.0;
  for (double v : values) sum += v;
  r.value = sum / double(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - r.value) * (v - r.value);
  if (values.size() > 1) r.standard_error = std::sqrt(squares / double(values.size() - 1) / double(values.size()));
  return r;
}

int replicates_for(int samples) {
  if (samples < 2) return 1;
  return std::clamp(samples / 16, 2, 16);
}

MeterReading measure_illuminance_lx(const TransportScene& scene, Vec3 position_m, Vec3 normal,
                                    const TabulatedSpectrum& v, int samples, uint64_t seed) {
  IndependentSampler sampler(seed);
  const LightReference ref{position_m, normal};
  std::vector<double> per_sample(size_t(std::max(samples, 0)), 0.0);
  const int batches = replicates_for(samples);
  const int base = samples / batches, extra = samples % batches;
  for (int i = 0, batch = 0, first = 0; i < samples; ++i) {
    const int batch_size = base + (batch < extra ? 1 : 0);
    const int k = i - first;  // the sample's place in its batch
    if (k + 1 == batch_size) {
      ++batch;
      first = i + 1;
    }
    sampler.start_pixel_sample(0, 0, uint32_t(i));
    // Stratified wavelengths within the batch: its k-th sample draws its hero from the k-th of the batch's
    // equal-probability strata.
    const float u = std::min((float(k) + sampler.next_1d()) / float(batch_size), std::nextafter(1.0f, 0.0f));
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(u);
    SampledSpectrum irradiance(0.0f);  // W/(m²·nm) per lane
    for (const auto& light : *scene.lights) {
      const auto s = light->sample_li(ref, lambda, sampler.next_2d());
      if (!s) continue;
      const float cos_theta = dot(normal, s->wi);
      if (!(cos_theta > 0.0f)) continue;
      Ray shadow{offset_ray_origin(position_m, normal, s->wi, scene.scene_scale), s->wi};
      // Aimed at the light point lifted off the light's surface, and stopped just short of it, so that an area
      // light's own surface does not shadow it (transport/integrators/path_integrator.h, shadow_segment).
      const ShadowSegment segment = shadow_segment(shadow.origin, position_m, *s, scene.scene_scale);
      shadow.direction = segment.direction;
      if (std::isfinite(segment.length)) shadow.t_max = segment.length * (1.0f - 1e-4f);
      // Through glazing panes as the path integrator's shadow rays go (transport/integrators/shadow_passage.h), so
      // lux behind a window agrees with the render: the pane's straight-through transmittance at this angle, per lane.
      SampledSpectrum transmittance(1.0f);
      if (scene.geometry) {
        const std::optional<ShadowPassage> passage = trace_shadow(scene, shadow, lambda);
        if (!passage) continue;
        transmittance = passage->transmittance;
      }
      irradiance = irradiance + s->radiance * transmittance * Float4(cos_theta / s->pdf_solid_angle);
    }
    // E_v = K_m ∫ E(λ) V(λ) dλ, one lane at a time: E(λ_j) V(λ_j) / p(λ_j), averaged over the lanes.
    double estimate = 0.0;
    for (int j = 0; j < kLaneCount; ++j)
      estimate += double(irradiance[j]) * v.value(lambda.lambda_nm(j)) / double(lambda.pdf()[j]);
    per_sample[size_t(i)] = kMaxLuminousEfficacy_lm_W * estimate / kLaneCount;
  }
  return batch_mean_and_standard_error(per_sample, batches);
}

MeterReading measure_luminance_nt(const Film& film, const PixelBounds& window) {
  const double nits_per_y = film.response().luminance_nits_per_unit_y();
  if (!(nits_per_y > 0.0))
    throw InputError({}, "a luminance meter needs a CIE XYZ film; this one records " + film.response().description());
  std::vector<double> pixels;
  for (int y = window.y0; y < window.y1; ++y)
    for (int x = window.x0; x < window.x1; ++x) pixels.push_back(film.pixel_value(x, y)[1] * nits_per_y);
  return mean_and_standard_error(pixels);
}

}  // namespace rimu
