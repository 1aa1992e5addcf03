#include "render/metropolis_renderer.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "render/interrupt_flag.h"
#include "render/progress_reporter.h"
#include "transport/sampling/primary_sample_sampler.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {
namespace {

// What one point of primary sample space contributes to the film: the camera path's value where its ray left the
// film, and, with bidirectional path tracing, the light subpath's vertices seen by the camera elsewhere.
struct FilmContribution {
  Vec2 film_px;
  float channels[3] = {0.0f, 0.0f, 0.0f};
};

// A path of the chain: its contributions, its brightness f (the sum of their channels' magnitudes) and the density
// the chains sample it in proportion to (f up to the cap).
struct PathSample {
  std::vector<FilmContribution> contributions;
  float brightness = 0.0f;
  float target = 0.0f;
};

// Splats are summed as integers of this many units per unit of filter pdf × weight × channel / density (at most 2 per
// unit pdf where the brightness is below the cap: weights ≤ 2, densities ≥ the target, the channels' magnitudes sum
// to the brightness): integer sums do not depend on the order of the additions, which the threads decide.
constexpr double kFixedPointUnits = 0x1p31;

class MetropolisLoop {
 public:
  MetropolisLoop(const CameraPathRadiance& radiance, WavelengthMode wavelengths,
                 const TabulatedWavelengthDensity* wavelength_density, bool has_motion, const Camera& camera,
                 const PixelFilter& filter, Film& film)
      : radiance_(radiance),
        wavelengths_(wavelengths),
        wavelength_density_(wavelength_density),
        has_motion_(has_motion),
        camera_(camera),
        filter_(filter),
        film_(film),
        bounds_(film.pixel_bounds()),
        sums_(size_t(bounds_.area()) * 3),
        totals_(size_t(bounds_.area()) * 3, 0.0) {
    filter_peak_ = std::max(1e-30, filter_.pdf({0.0f, 0.0f}));
  }

  // The path the sampler's current point describes, into `s` (its storage reused); `light_splats` is scratch.
  void evaluate(PrimarySampleSampler& sampler, FilmSampleCounts& counts, std::vector<CausticSplat>& light_splats,
                PathSample& s) const {
    s.contributions.clear();
    s.brightness = 0.0f;
    const Vec2 film_u = sampler.next_2d();
    const Vec2 film_px = {float(bounds_.x0) + film_u.x * float(bounds_.width()),
                          float(bounds_.y0) + film_u.y * float(bounds_.height())};
    const Vec2 lens = sampler.next_2d();
    const SampledWavelengths lambda = sample_path_wavelengths(wavelengths_, sampler, wavelength_density_);
    const float time = has_motion_ ? sampler.next_1d() : 0.0f;
    const Ray ray = camera_.generate_ray(film_px.x, film_px.y, lens, time);
    light_splats.clear();
    const SampledSpectrum L = radiance_(ray, lambda, sampler, light_splats);
    FilmContribution camera{film_px};
    if (!film_channels(L, lambda, 1.0f, camera.channels, counts)) return;  // the whole sample is discarded
    ++counts.accepted;
    s.contributions.push_back(camera);
    // A light subpath's splat counts once per pixel of the film, as the render loop's light paths do: each camera
    // sample there traces one for the whole image.
    const float per_pixel = 1.0f / float(bounds_.area());
    const float r = filter_.radius_px();
    for (const CausticSplat& splat : light_splats) {
      // A vertex whose filter footprint misses the film adds nothing (the render loop drops it too).
      if (!(splat.film_px.x > float(bounds_.x0) - r && splat.film_px.x < float(bounds_.x1) + r &&
            splat.film_px.y > float(bounds_.y0) - r && splat.film_px.y < float(bounds_.y1) + r))
        continue;
      FilmContribution seen{splat.film_px};
      if (film_channels(splat.radiance, splat.lambda, per_pixel, seen.channels, counts))
        s.contributions.push_back(seen);
    }
    double brightness = 0.0;
    for (const FilmContribution& c : s.contributions)
      brightness += double(std::abs(c.channels[0])) + double(std::abs(c.channels[1])) + double(std::abs(c.channels[2]));
    s.brightness = float(brightness);
    if (!std::isfinite(s.brightness)) {  // finite channels whose sum overflows
      ++counts.infinite;
      --counts.accepted;
      s.contributions.clear();
      s.brightness = 0.0f;
    }
    s.target = std::min(s.brightness, target_cap_);
  }

  // Caps the chains' density at `cap` (see MetropolisSettings::brightness_cap).
  void set_target_cap(float cap) { target_cap_ = cap; }

  // The film's estimator (FilmTile::add_sample) of `L` at `lambda`: the lanes' L/p with dead lanes left out, averaged,
  // times `scale`. False (and the reason counted) for a value the film would discard: NaN, ±Inf or negative.
  bool film_channels(const SampledSpectrum& L, const SampledWavelengths& lambda, float scale, float channels[3],
                     FilmSampleCounts& counts) const {
    const Float4 pdf = lambda.pdf();
    const Mask4 live = pdf != Float4(0.0f);
    const Float4 lane_value = select(live, L / pdf, Float4(0.0f)) * Float4(scale / float(kLaneCount));
    const Float4 live_radiance = select(live, L, Float4(0.0f));
    if ((is_nan(live_radiance) | is_nan(lane_value)).any()) {
      ++counts.nan;
      return false;
    }
    if (!(is_finite(live_radiance) & is_finite(lane_value)).all()) {
      ++counts.infinite;
      return false;
    }
    if ((live_radiance < Float4(0.0f)).any() || (select(live, pdf, Float4(1.0f)) < Float4(0.0f)).any()) {
      ++counts.negative;
      return false;
    }
    const Response4 c = film_.response().evaluate(lambda);
    channels[0] = sum(lane_value * c.x);
    channels[1] = sum(lane_value * c.y);
    channels[2] = sum(lane_value * c.z);
    return true;
  }

  // Adds `weight` × channels / `density` of each of `s`'s contributions to the pixels its filter reaches (density ≥
  // s.target).
  void splat(const PathSample& s, double weight, double density) {
    if (!(s.target > 0.0f) || !(weight > 0.0) || !(density > 0.0)) return;
    const double scale = weight / density * kFixedPointUnits / filter_peak_;
    for (const FilmContribution& c : s.contributions) splat(c, scale);
  }

  void splat(const FilmContribution& s, double scale) {
    filter_.spread(s.film_px, bounds_.x0, bounds_.y0, bounds_.x1, bounds_.y1, [&](int px, int py, double density) {
      std::atomic<int64_t>* sums = &sums_[pixel_index(px, py) * 3];
      for (int k = 0; k < 3; ++k) {
        // Within ±2⁵⁵ units (a brightness 2²⁴ times the cap), so that no sum can overflow.
        const int64_t units = std::llround(std::clamp(double(s.channels[k]) * density * scale, -0x1p55, 0x1p55));
        if (units != 0) sums[k].fetch_add(units, std::memory_order_relaxed);
      }
    });
  }

  // Moves the pass's sums into the film, which then holds every pass's sums scaled by the current estimate of the
  // mean brightness b (refined by every pass's large steps: the film's earlier passes are rescaled by adding the
  // difference), with `samples_per_pixel` more camera samples' worth per pixel.
  void flush(double brightness_mean, bool rescale_earlier, int samples_per_pixel, const FilmSampleCounts& counts) {
    FilmTile tile = film_.make_tile(bounds_);
    const double unit = filter_peak_ / kFixedPointUnits;
    for (int y = bounds_.y0; y < bounds_.y1; ++y) {
      for (int x = bounds_.x0; x < bounds_.x1; ++x) {
        const size_t i = pixel_index(x, y) * 3;
        double* p = tile.pixel(x, y);
        for (int k = 0; k < 3; ++k) {
          const double before = totals_[i + size_t(k)];
          const double after = before + double(sums_[i + size_t(k)].exchange(0, std::memory_order_relaxed)) * unit;
          totals_[i + size_t(k)] = after;
          p[k] = rescale_earlier ? brightness_mean * after - applied_brightness_ * before
                                 : brightness_mean * (after - before);
        }
        p[FilmTile::kWeight] = double(samples_per_pixel);
      }
    }
    applied_brightness_ = brightness_mean;
    tile.add_sample_counts(counts);
    film_.merge_tile(tile);
  }

 private:
  size_t pixel_index(int x, int y) const {
    return size_t(y - bounds_.y0) * size_t(bounds_.width()) + size_t(x - bounds_.x0);
  }

  const CameraPathRadiance& radiance_;
  WavelengthMode wavelengths_;
  const TabulatedWavelengthDensity* wavelength_density_;
  bool has_motion_;
  const Camera& camera_;
  const PixelFilter& filter_;
  Film& film_;
  PixelBounds bounds_;
  double filter_peak_ = 1.0;
  float target_cap_ = INFINITY;
  std::vector<std::atomic<int64_t>> sums_;  // this pass's splats, fixed point
  std::vector<double> totals_;              // every flushed pass's splats, before the factor b
  double applied_brightness_ = 0.0;         // the b the film's sums carry
};

struct Chain {
  std::unique_ptr<PrimarySampleSampler> sampler;
  PathSample current;
  PathSample proposal;                     // storage reused by every proposal
  std::vector<CausticSplat> light_splats;  // scratch of the integrator's light subpaths
  // The large steps' proposals are independent samples: with the bootstrap's they estimate b.
  double large_step_brightness = 0.0;
  int64_t large_steps = 0;
};

// Chain streams are numbered after every bootstrap stream.
constexpr uint64_t kChainStreamBase = uint64_t(1) << 62;

}  // namespace

RenderStatistics render_metropolis(const CameraPathRadiance& radiance, const MetropolisSettings& settings,
                                   WavelengthMode wavelengths, const TabulatedWavelengthDensity* wavelength_density,
                                   bool has_motion, const Camera& camera, const PixelFilter& filter, Film& film,
                                   const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(options.threads));
  RenderStatistics stats;
  MetropolisLoop loop(radiance, wavelengths, wavelength_density, has_motion, camera, filter, film);
  const int64_t pixels = film.pixel_bounds().area();
  if (pixels <= 0) return stats;

  // Bootstrap: independent paths (each the first point of its own stream), in batches of a fixed size.
  const int64_t bootstrap = std::max<int64_t>(1, std::llround(double(settings.bootstrap_per_pixel) * double(pixels)));
  std::vector<float> brightness(static_cast<size_t>(bootstrap), 0.0f);
  constexpr int64_t kBatch = 4096;
  const size_t batches = size_t((bootstrap + kBatch - 1) / kBatch);
  std::vector<FilmSampleCounts> batch_counts(batches);
  tbb::parallel_for(size_t(0), batches, [&](size_t b) {
    PathSample path;
    std::vector<CausticSplat> scratch;
    for (int64_t i = int64_t(b) * kBatch; i < std::min(bootstrap, int64_t(b + 1) * kBatch); ++i) {
      PrimarySampleSampler sampler(options.seed, uint64_t(i), settings.sigma, settings.large_step_probability);
      sampler.start_iteration();
      loop.evaluate(sampler, batch_counts[b], scratch, path);
      brightness[size_t(i)] = path.brightness;  // uncapped: the cap is set from their mean
    }
  });
  if (settings.brightness_cap > 0.0f) {
    double mean = 0.0;
    for (float f : brightness) mean += double(f);
    mean /= double(bootstrap);
    const float cap = mean > 0.0 ? float(double(settings.brightness_cap) * mean) : INFINITY;
    loop.set_target_cap(cap);
    for (float& f : brightness) f = std::min(f, cap);
  }
  std::vector<double> cumulative(size_t(bootstrap) + 1, 0.0);
  for (size_t i = 0; i < brightness.size(); ++i) cumulative[i + 1] = cumulative[i] + double(brightness[i]);
  double brightness_mean = cumulative.back() / double(bootstrap);

  // Chains start at bootstrap paths chosen in proportion to their brightness.
  const int chain_count = int(std::max<int64_t>(1, std::min<int64_t>(settings.chains, pixels)));
  std::vector<Chain> chains(static_cast<size_t>(chain_count));
  std::vector<FilmSampleCounts> chain_counts(chains.size());
  if (brightness_mean > 0.0) {
    tbb::parallel_for(size_t(0), chains.size(), [&](size_t c) {
      Pcg32 pick;
      pick.increment = (mix_bits(uint64_t(c) ^ mix_bits(options.seed ^ 0x5bd1e995ull)) << 1) | 1u;
      pick.state = mix_bits(uint64_t(c) + options.seed);
      const double target = (double(pick.next_bits()) + 0.5) * 0x1p-32 * cumulative.back();
      size_t i = size_t(std::upper_bound(cumulative.begin() + 1, cumulative.end(), target) - cumulative.begin() - 1);
      i = std::min(i, brightness.size() - 1);
      while (brightness[i] <= 0.0f && i + 1 < brightness.size()) ++i;  // target on a boundary: the next bright one
      Chain& chain = chains[c];
      chain.sampler = std::make_unique<PrimarySampleSampler>(options.seed, uint64_t(i), settings.sigma,
                                                             settings.large_step_probability);
      chain.sampler->start_iteration();
      FilmSampleCounts replay;  // the bootstrap counted this path already
      std::vector<CausticSplat> scratch;
      loop.evaluate(*chain.sampler, replay, scratch, chain.current);
      chain.sampler->accept();
      chain.sampler->continue_in_stream(kChainStreamBase + uint64_t(c));
    });
  }

  FilmSampleCounts bootstrap_counts;
  for (const FilmSampleCounts& c : batch_counts) bootstrap_counts += c;
  bool first_flush = true;
  int done = options.first_sample;
  while (done < options.samples_per_pixel) {
    const int end = std::min(sample_pass_end(done), options.samples_per_pixel);
    const int count = end - done;
    if (options.start_pass && !options.start_pass(done, count)) {
      stats.stopped_by_start_pass = true;
      break;
    }
    const int64_t mutations = int64_t(count) * pixels;
    // The pass's b (bootstrap and the earlier passes' large steps) for the combination with the large steps.
    const double pass_brightness = brightness_mean;
    const double pass_large_density = double(settings.large_step_probability) * pass_brightness;
    std::atomic<bool> stopped{false};
    for (FilmSampleCounts& c : chain_counts) c = FilmSampleCounts{};
    if (brightness_mean > 0.0) {
      tbb::parallel_for(size_t(0), chains.size(), [&](size_t c) {
        if (options.interrupt && options.interrupt->requested()) {
          stopped = true;
          return;
        }
        Chain& chain = chains[c];
        PrimarySampleSampler& sampler = *chain.sampler;
        const int64_t steps = mutations / chain_count + (int64_t(c) < mutations % chain_count ? 1 : 0);
        for (int64_t step = 0; step < steps; ++step) {
          if ((step & 1023) == 1023) {
            if (options.progress) options.progress->add(1024);
            if (options.interrupt && options.interrupt->requested()) {
              stopped = true;
              return;
            }
          }
          sampler.start_iteration();
          PathSample& proposal = chain.proposal;
          loop.evaluate(sampler, chain_counts[c], chain.light_splats, proposal);
          if (sampler.large_step()) {
            chain.large_step_brightness += double(proposal.target);
            ++chain.large_steps;
          }
          const float accept =
              chain.current.target > 0.0f ? std::min(1.0f, proposal.target / chain.current.target) : 1.0f;
          // Expected values (Kelemen et al. 2002): both paths splat, weighted by the chance of each being next. With
          // large_step_mis the large steps are also uniform samples of the image, combined with the chain's by the
          // balance heuristic over the densities f/b and p_large (Kelemen et al.'s combination); without it that
          // density and the large step's own weight are 0.
          const double large = settings.large_step_mis && sampler.large_step() ? 1.0 : 0.0;
          const double large_density = settings.large_step_mis ? pass_large_density : 0.0;
          loop.splat(proposal, double(accept) + large, double(proposal.target) + large_density);
          loop.splat(chain.current, double(1.0f - accept), double(chain.current.target) + large_density);
          if (sampler.next_free_1d() < accept) {
            sampler.accept();
            std::swap(chain.current, proposal);
          } else {
            sampler.reject();
          }
        }
        if (options.progress) options.progress->add(uint64_t(steps % 1024));
      });
    }
    if (stopped) {
      stats.interrupted = true;
      break;
    }
    FilmSampleCounts pass_counts;
    for (const FilmSampleCounts& c : chain_counts) pass_counts += c;
    // b from the bootstrap and every large step so far, summed in chain order.
    double brightness_sum = cumulative.back();
    int64_t brightness_samples = bootstrap;
    for (const Chain& chain : chains) {
      brightness_sum += chain.large_step_brightness;
      brightness_samples += chain.large_steps;
    }
    brightness_mean = brightness_sum / double(brightness_samples);
    if (first_flush) {
      pass_counts += bootstrap_counts;
      first_flush = false;
    }
    if (settings.large_step_mis)
      loop.flush(pass_brightness, false, count, pass_counts);
    else
      loop.flush(brightness_mean, true, count, pass_counts);
    done = end;
    stats.samples_per_pixel_done += count;
    stats.camera_samples += uint64_t(mutations);
    if (options.after_pass) options.after_pass(end);
    if (options.interrupt && options.interrupt->requested()) {
      stats.interrupted = done < options.samples_per_pixel;
      break;
    }
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace rimu
