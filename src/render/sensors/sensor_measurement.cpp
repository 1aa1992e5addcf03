#include "render/sensors/sensor_measurement.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "spectral/colorimetry/photometry_constants.h"
#include "spectral/error.h"
#include "transport/integrators/irradiance_estimator.h"
#include "transport/sampling/bit_mixing.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {
namespace {

// One meter point of the flattened list: where, what head it has (plane, cylinder), and whether it reads
// illuminance (else the luminance along receptor.direction).
struct MeterPoint {
  Vec3 position;
  MeterReceptor receptor;
  bool illuminance = true;
};

MeterReceptor point_receptor(const PointSensor& p) {
  switch (p.kind) {
    case PointSensor::Kind::cylindrical: return {MeterReceptor::Shape::cylinder, p.direction, {}};
    case PointSensor::Kind::semi_cylindrical: return {MeterReceptor::Shape::semi_cylinder, p.direction, p.facing};
    default: return {MeterReceptor::Shape::plane, p.direction, {}};
  }
}

std::vector<MeterPoint> meter_points(const SensorSettings& sensors) {
  std::vector<MeterPoint> points;
  points.reserve(sensors.point_count());
  for (const IlluminanceGrid& g : sensors.grids)
    for (int j = 0; j < g.count_v; ++j)
      for (int i = 0; i < g.count_u; ++i)
        points.push_back({g.point(i, j), {MeterReceptor::Shape::plane, g.normal, {}}, true});
  for (const PointSensor& p : sensors.points)
    points.push_back({p.position, point_receptor(p), p.kind != PointSensor::Kind::luminance});
  return points;
}

// The spectral weightings of one measurement: photopic always, the others when asked (scale · Σ_j Xⱼ w(λⱼ)/pⱼ / 4).
struct Weighting {
  const TabulatedSpectrum* w = nullptr;
  double scale = 0.0;
};
constexpr int kWeightings = 3;  // photopic, scotopic, melanopic

// The weighted values of one path's lanes (dead lanes, pdf 0, carry nothing), or false for an estimate the film
// would discard (NaN, infinite, negative). Weightings without a function are left at 0.
bool weighted_values(const SampledSpectrum& x, const SampledWavelengths& lambda, const Weighting (&weightings)[kWeightings],
                     double (&values)[kWeightings]) {
  for (double& v : values) v = 0.0;
  for (int j = 0; j < kLaneCount; ++j) {
    const float pdf = lambda.pdf()[j];
    if (pdf == 0.0f) continue;
    if (!std::isfinite(x[j]) || x[j] < 0.0f || !std::isfinite(pdf) || pdf < 0.0f) return false;
    for (int k = 0; k < kWeightings; ++k)
      if (weightings[k].w) values[k] += double(x[j]) * weightings[k].w->value(lambda.lambda_nm(j)) / double(pdf);
  }
  for (int k = 0; k < kWeightings; ++k) values[k] *= weightings[k].scale / double(kLaneCount);
  return true;
}

struct Accumulator {
  double sum = 0, squares = 0;
  int count = 0;
};

// A point's reading from its replicates' sums: the mean of the replicate means (replicates whose every sample was
// discarded are left out), its standard error from their spread. One replicate: the textbook s/√n of its samples,
// which overstates the error of a scrambled Sobol' sequence's mean (SensorMeasureOptions::replicates).
MeterReading replicate_reading(const Accumulator* replicates, int count) {
  MeterReading r;
  if (count == 1) {
    const Accumulator& a = replicates[0];
    r.samples = a.count;
    if (a.count == 0) return r;
    r.value = a.sum / a.count;
    if (a.count > 1)
      r.standard_error = std::sqrt(std::max(0.0, (a.squares - a.sum * r.value) / double(a.count - 1)) / a.count);
    return r;
  }
  std::vector<double> means;
  int samples = 0;
  for (int k = 0; k < count; ++k) {
    samples += replicates[k].count;
    if (replicates[k].count > 0) means.push_back(replicates[k].sum / replicates[k].count);
  }
  r = mean_and_standard_error(means);
  r.samples = samples;
  return r;
}

GridReadings grid_statistics(std::vector<MeterReading> points) {
  GridReadings g;
  g.points = std::move(points);
  if (g.points.empty()) return g;
  g.e_min_lx = g.e_max_lx = g.points.front().value;
  double sum = 0.0;
  for (const MeterReading& p : g.points) {
    g.e_min_lx = std::min(g.e_min_lx, p.value);
    g.e_max_lx = std::max(g.e_max_lx, p.value);
    sum += p.value;
  }
  g.e_avg_lx = sum / double(g.points.size());
  g.u0 = g.e_avg_lx > 0.0 ? g.e_min_lx / g.e_avg_lx : 0.0;
  return g;
}

}  // namespace

void check_sensor_scene(const Scene& scene, const std::string& where) {
  if (scene.has_media())
    throw InputError({where, 0, "/sensors"}, "sensors are not measured in scenes with participating media yet "
                                             "(\"media\"): remove the media or the sensors");
  if (scene.settings.integrator.wavelengths == WavelengthMode::rgb)
    throw InputError({where, 0, "/sensors"}, "sensors need spectral transport: rgb lanes are not wavelengths, so "
                                             "lux cannot be weighted by V(λ); use integrator.wavelengths \"hero\"");
}

SensorReadings measure_sensors(const Scene& scene, const SensorSettings& sensors, const TabulatedSpectrum& v,
                               const SensorMeasureOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_sensor_scene(scene, scene.source);
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(options.threads));

  // E_out of the daylight-factor grids first: a scene without its overcast sky fails before any sample.
  std::vector<std::optional<double>> outdoor_lx;
  for (size_t g = 0; g < sensors.grids.size(); ++g)
    outdoor_lx.push_back(sensors.grids[g].daylight_factor
                             ? std::optional<double>(overcast_sky_horizontal_illuminance_lx(
                                   scene, v, {"", 0, "/sensors/grids/" + std::to_string(g) + "/daylight_factor"}))
                             : std::nullopt);
  const TransportScene view = scene.transport_view();
  PathIntegratorSettings settings = scene.settings.integrator;
  settings.guiding = false;  // the receptor's paths are unguided (no field is learned for them)
  const IrradianceEstimator estimator(view, settings);
  if ((sensors.quantities.scotopic && !options.scotopic_v_prime) || (sensors.quantities.melanopic && !options.melanopic))
    throw std::logic_error("measure_sensors: a quantity was asked for without its weighting function");
  const Weighting weightings[kWeightings] = {
      {&v, kMaxLuminousEfficacy_lm_W},
      {sensors.quantities.scotopic ? options.scotopic_v_prime : nullptr, kMaxScotopicLuminousEfficacy_lm_W},
      {sensors.quantities.melanopic ? options.melanopic : nullptr, 1.0 / kMelanopicEfficacyD65_W_lm}};
  const std::vector<MeterPoint> points = meter_points(sensors);
  const int replicates = options.replicates > 0 ? std::min(options.replicates, std::max(options.samples, 1))
                                                : replicates_for(options.samples);
  // sums[(p·kWeightings + k)·replicates + r]: point p, weighting k, replicate r.
  std::vector<Accumulator> sums(points.size() * kWeightings * size_t(replicates));
  // Replicate r scrambles the sequence with its own seed (a hash of the scene's seed and r), so the replicates are
  // independent randomisations of the same point set; it takes samples/R samples, the first replicates one more
  // when R does not divide the count.
  std::vector<std::unique_ptr<Sampler>> prototypes;
  for (int r = 0; r < replicates; ++r)
    prototypes.push_back(make_sampler(options.sampler, mix_bits(options.seed ^ (0x9e3779b97f4a7c15ull * uint64_t(r + 1)))));
  std::atomic<bool> stopped{false};
  std::atomic<uint64_t> discarded{0};

  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (int r = 0; r < replicates; ++r) {
      std::unique_ptr<Sampler> sampler = prototypes[size_t(r)]->clone();
      const int replicate_samples = options.samples / replicates + (r < options.samples % replicates ? 1 : 0);
      for (size_t p = range.begin(); p != range.end(); ++p) {
        if (options.stop_requested && options.stop_requested()) {
          stopped = true;
          return;
        }
        const MeterPoint& point = points[p];
        // Each point is its own "pixel" of the sampler (x, y = the index's low and high halves), so its samples are
        // the same whichever thread takes it.
        const int x = int(p & 0xffff), y = int(p >> 16);
        for (int s = 0; s < replicate_samples; ++s) {
          sampler->start_pixel_sample(x, y, uint32_t(s));
          const SampledWavelengths lambda =
              sample_path_wavelengths(settings.wavelengths, *sampler, scene.wavelength_density.get());
          const SampledSpectrum value =
              point.illuminance ? estimator.irradiance(point.position, point.receptor, lambda, *sampler)
                                : estimator.radiance(Ray{point.position, point.receptor.direction}, lambda, *sampler);
          double values[kWeightings];
          if (!weighted_values(value, lambda, weightings, values)) {
            ++discarded;
            continue;
          }
          for (int k = 0; k < kWeightings; ++k) {
            Accumulator& acc = sums[(p * kWeightings + size_t(k)) * size_t(replicates) + size_t(r)];
            acc.sum += values[k];
            acc.squares += values[k] * values[k];
            ++acc.count;
          }
        }
      }
    }
  });
  const auto reading = [&](size_t p, int k) {
    return replicate_reading(&sums[(p * kWeightings + size_t(k)) * size_t(replicates)], replicates);
  };

  SensorReadings readings;
  readings.interrupted = stopped;
  readings.discarded_samples = discarded;
  const bool scotopic = weightings[1].w != nullptr, melanopic = weightings[2].w != nullptr;
  size_t next = 0;
  for (const IlluminanceGrid& g : sensors.grids) {
    std::vector<MeterReading> grid_points, scotopic_points, melanopic_points;
    for (int k = 0; k < g.count_u * g.count_v; ++k, ++next) {
      grid_points.push_back(reading(next, 0));
      if (scotopic) scotopic_points.push_back(reading(next, 1));
      if (melanopic) melanopic_points.push_back(reading(next, 2));
    }
    readings.grids.push_back(grid_statistics(std::move(grid_points)));
    readings.grids.back().scotopic_points = std::move(scotopic_points);
    readings.grids.back().melanopic_points = std::move(melanopic_points);
    if (const std::optional<double> e_out = outdoor_lx[readings.grids.size() - 1])
      readings.grids.back().daylight_factor = daylight_factors(readings.grids.back().points, *e_out);
  }
  for (size_t k = 0; k < sensors.points.size(); ++k, ++next) {
    readings.meters.push_back(reading(next, 0));
    if (scotopic) readings.meters_scotopic.push_back(reading(next, 1));
    if (melanopic) readings.meters_melanopic.push_back(reading(next, 2));
  }
  readings.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return readings;
}

}  // namespace rimu
