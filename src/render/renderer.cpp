#include "render/renderer.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <type_traits>
#include <vector>

#include "render/film/adaptive_sampling.h"
#include "render/scene/ray_tally.h"
#include "render/tile_schedule.h"
#include "render/film/feature_buffers.h"
#include "render/interrupt_flag.h"
#include "render/metropolis_renderer.h"
#include "render/progress_reporter.h"
#include "transport/guiding/guiding_field.h"
#include "transport/integrators/bidirectional_path_integrator.h"
#include "transport/integrators/caustic_light_tracer.h"
#include "transport/integrators/path_features.h"
#include "transport/integrators/path_integrator.h"
#include "transport/integrators/volumetric_path_integrator.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {
namespace {

constexpr int kTileSize = 16;
// Path guiding's training history (docs/transport.md, "Path guiding", Training): every pass records into one history
// of at most this many samples (28 bytes each, sizeof(GuidingSample): 112 MiB), each pass's share split equally by
// its tiles so that which samples are kept does not depend on the threads. After the first pass, and then after the
// pass that at least doubles the samples of the last fit (1, 3, 7, 15, 31, 63, … samples per pixel into the call,
// or when the history is full), a field is fitted to the whole history and guides the following passes.
constexpr size_t kGuidingSampleBudget = size_t(1) << 22;

std::vector<PixelBounds> make_tiles(const PixelBounds& b) {
  std::vector<PixelBounds> tiles;
  for (int y = b.y0; y < b.y1; y += kTileSize)
    for (int x = b.x0; x < b.x1; x += kTileSize)
      tiles.push_back({x, y, std::min(x + kTileSize, b.x1), std::min(y + kTileSize, b.y1)});
  return tiles;
}

}  // namespace

int sample_pass_end(int sample) {
  constexpr int kLastDoubling = 15;  // passes of 1, 2, 4, 8 end at 1, 3, 7, 15; then passes of 16
  if (sample < kLastDoubling) {
    int end = 1;
    while (end <= sample) end = 2 * end + 1;
    return end;
  }
  return kLastDoubling + ((sample - kLastDoubling) / 16 + 1) * 16;
}

RenderStatistics render(const Scene& scene, const PixelFilter& filter, Film& film, const RenderOptions& options) {
  const TransportScene view = scene.transport_view();
  const Camera camera(scene.camera, scene.settings.width, scene.settings.height);
  // Scenes without media keep the surface integrator: they pay nothing for volumetric transport.
  if (scene.has_media()) {
    const VolumetricScene volumetric{view, &scene.media, &scene.medium_boundaries, scene.camera_medium};
    VolumetricIntegratorSettings settings;
    settings.path = scene.settings.integrator;
    settings.distance = scene.settings.distance_sampling;
    settings.max_depth_includes_media = scene.settings.max_depth_includes_media;
    settings.equiangular = scene.settings.equiangular;
    return render(volumetric, settings, camera, filter, film, options);
  }
  return render(view, scene.settings.integrator, camera, filter, film, options);
}

namespace {

// A tile's caustic splats (transport/integrators/caustic_light_tracer.h) spread over the pixels of `into` by the
// filter's density: the camera samples' offsets have that density, so both parts of the image are filtered alike.
// A pixel's sums are divided by its camera samples, each of which traced one light path for the whole image, so
// each splat counts once per pixel of the rendered area.
void add_caustic_splats(const std::vector<CausticSplat>& splats, const PixelFilter& filter, FilmTile& into) {
  const PixelBounds& area = into.bounds();
  const float per_path = 1.0f / float(double(area.width()) * double(area.height()));
  std::vector<SampledSpectrum> group_slots(size_t(into.light_group_count()));
  for (const CausticSplat& splat : splats) {
    if (!group_slots.empty()) {
      std::fill(group_slots.begin(), group_slots.end(), SampledSpectrum(0.0f));
      group_slots[size_t(splat.light_group)] = splat.radiance;
    }
    filter.spread(splat.film_px, area.x0, area.y0, area.x1, area.y1, [&](int px, int py, double density) {
      into.add_splat(px, py, splat.radiance, splat.lambda, float(density) * per_path,
                     group_slots.empty() ? nullptr : group_slots.data());
    });
  }
}

// A merging pass's wavelengths (transport/integrators/vertex_merging.h): every pixel and light subpath of a bucket
// shares them, so their error is shared too and cancels only over buckets and passes. The first number (the hero's)
// is therefore not random but a low-discrepancy point: bucket k of K takes (k + u_i)/K, u_i = frac(u₀ + i φ⁻¹) the
// Kronecker sequence over the passes i (the sample indices), which spreads the heroes of successive passes evenly
// over the spectrum. Further numbers (independent mode's other lanes) come from `base`.
class PassWavelengthSampler final : public Sampler {
 public:
  PassWavelengthSampler(Sampler& base, float hero_u) : base_(base), hero_u_(hero_u) {}
  void start_pixel_sample(int x, int y, uint32_t sample_index) override { base_.start_pixel_sample(x, y, sample_index); }
  float next_1d() override {
    if (first_) {
      first_ = false;
      return hero_u_;
    }
    return base_.next_1d();
  }
  Vec2 next_2d() override { return {next_1d(), next_1d()}; }
  std::unique_ptr<Sampler> clone() const override { return std::make_unique<PassWavelengthSampler>(base_, hero_u_); }

 private:
  Sampler& base_;
  float hero_u_;
  bool first_ = true;
};

// The render loop over tiles and passes, for any integrator with radiance(ray, lambda, sampler).
template <typename Integrator>
RenderStatistics render_loop(const Integrator& integrator, const PathIntegratorSettings& integrator_settings,
                             const TransportScene& surfaces, const TabulatedWavelengthDensity* wavelength_density,
                             const Camera& camera, const PixelFilter& filter, Film& film, const RenderOptions& options,
                             const VolumetricScene* media = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  constexpr bool kBidirectional = std::is_same_v<Integrator, BidirectionalPathIntegrator>;
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, size_t(options.threads));

  const std::unique_ptr<Sampler> prototype_sampler = make_sampler(options.sampler, options.seed);
  // Feature rays draw from their own stream (the image's samples stay those of a render without features).
  constexpr uint64_t kFeatureSeedSalt = 0x9e3779b97f4a7c15ull;
  const std::unique_ptr<Sampler> feature_prototype =
      options.features ? make_sampler(SamplerKind::independent, options.seed ^ kFeatureSeedSalt) : nullptr;
  const PixelBounds film_bounds = film.pixel_bounds();
  const std::vector<PixelBounds> tiles = make_tiles(film_bounds);
  TileSchedule schedule(tiles.size());
  std::vector<uint64_t> planned_samples(tiles.size());

  RenderStatistics stats;
  // Path guiding: the field the current pass samples from, fitted after the last one. Both integrators guide
  // their surface vertices; the volumetric one leaves its medium vertices to the phase function.
  stats.guiding.active = integrator_settings.guiding;
  // Camera rays carry differentials only where a texture reads them, spaced as this render's samples are: a pixel's
  // spp samples cover it about 1/√spp apart; pbrt-v4's floor of 1/8 keeps high-spp renders from sharpening the
  // lookup below the texels' own noise-free resolution.
  const bool texture_footprints = [&] {
    // The surface integrator holds a TransportScene; the volumetric one holds its surfaces beside the media.
    if constexpr (std::is_same_v<Integrator, PathIntegrator>) return integrator.scene().texture_footprints;
    else if constexpr (kBidirectional) return false;  // its vertices read textures at their finest level
    else return integrator.scene().surfaces.texture_footprints;
  }();
  float differentials_scale = 0.0f;
  if (texture_footprints)
    differentials_scale = std::max(0.125f, 1.0f / std::sqrt(float(std::max(1, options.samples_per_pixel))));
  std::optional<GuidingField> guiding_field;
  GuidingFieldSettings guiding_settings;
  guiding_settings.parallax_mixture = integrator_settings.guiding_mixture;
  std::vector<GuidingSample> guiding_history;  // every pass's records, in pass and tile order, up to the budget
  int next_fit = 1;  // samples per pixel into the call after which the next field is fitted
  // Each tile's records of the current pass. Kept across passes (cleared, not freed): allocating them anew every
  // pass cost a guided render ~9 % of its time in page faults (perf, daylit room 160×90, 64 spp).
  std::vector<std::vector<GuidingSample>> guiding_records;
  // Caustic light tracing (transport/integrators/caustic_light_tracer.h): surfaces only, where the settings ask for
  // it (render() turned it off where the camera or adaptive sampling cannot have it). Each tile's splats of a pass.
  std::optional<CausticLightTracer> caustics;
  if constexpr (std::is_same_v<Integrator, PathIntegrator>)
    if (integrator_settings.caustic_light_tracing) {
      caustics.emplace(surfaces, integrator_settings);
      if (caustics->empty()) caustics.reset();
    }
  // Light paths (the caustic tracer's, the bidirectional integrator's light subpaths) splat onto the film.
  const bool splatting = caustics.has_value() || kBidirectional;
  constexpr uint64_t kCausticSeedSalt = 0x632be59bd9b4e019ull;
  const std::unique_ptr<Sampler> caustic_prototype =
      splatting ? make_sampler(SamplerKind::independent, options.seed ^ kCausticSeedSalt) : nullptr;
  std::vector<std::vector<CausticSplat>> caustic_splats;
  std::vector<char> caustic_done;
  std::optional<FilmTile> caustic_tile;
  // Vertex merging (transport/integrators/vertex_merging.h): before each sample index, a pass of light subpaths
  // (at most one per pixel) from their own stream, in batches of a fixed size joined in order (the pass does not
  // depend on the threads); the camera samples of that index then merge with them.
  std::optional<VertexMergingPass> merging;
  constexpr uint64_t kMergeSeedSalt = 0x2545f4914f6cdd1dull;
  std::unique_ptr<Sampler> merge_prototype;
  int merge_subpaths = 0;
  if constexpr (kBidirectional) {
    if (integrator_settings.vertex_merging) {
      merging.emplace();
      merge_prototype = make_sampler(SamplerKind::independent, options.seed ^ kMergeSeedSalt);
      merge_subpaths = int(std::min<int64_t>(film.pixel_bounds().area(),
                                             std::max(1, integrator_settings.merging.max_light_subpaths)));
      stats.vertex_merging = true;
    }
  }
  const auto trace_merge_pass = [&](int sample_index) {
    if constexpr (kBidirectional) {
      const VertexMergingSettings& m = integrator_settings.merging;
      std::vector<SampledWavelengths> sets;
      const int buckets = std::max(1, m.wavelength_buckets);
      merge_prototype->start_pixel_sample(-1, -1, 0);
      const double golden = 0.6180339887498949;  // φ⁻¹
      const double u_pass = std::fmod(double(merge_prototype->next_1d()) + double(sample_index) * golden, 1.0);
      for (int k = 0; k < buckets; ++k) {
        merge_prototype->start_pixel_sample(-2 - k, -1, uint32_t(sample_index));
        const float hero_u = std::min(float((double(k) + u_pass) / double(buckets)), 0x1.fffffep-1f);
        PassWavelengthSampler pass_sampler(*merge_prototype, hero_u);
        sets.push_back(sample_path_wavelengths(integrator_settings.wavelengths, pass_sampler, wavelength_density));
      }
      merging->start(m.radius(sample_index, surfaces.scene_scale), std::move(sets), merge_subpaths);
      constexpr int kBatch = 4096;
      std::vector<MergeVertexBatch>& merge_batches = merging->batches(size_t((merge_subpaths + kBatch - 1) / kBatch));
      tbb::parallel_for(size_t(0), merge_batches.size(), [&](size_t b) {
        const std::unique_ptr<Sampler> sampler = merge_prototype->clone();
        MergeVertexBatch& batch = merge_batches[b];
        batch.clear();
        const int end = std::min(merge_subpaths, int(b + 1) * kBatch);
        for (int j = int(b) * kBatch; j < end; ++j) {
          sampler->start_pixel_sample(j, 0, uint32_t(sample_index));
          const float time = surfaces.has_motion ? sampler->next_1d() : 0.0f;
          const int bucket = merging->subpath_bucket(j);
          integrator.trace_merge_subpath(merging->wavelengths(bucket), bucket, time, *sampler, batch);
        }
      });
      merging->build();
      stats.merge_radius_m = merging->radius();
      stats.merge_vertices = merging->vertex_count();
      stats.merge_light_subpaths = uint64_t(merge_subpaths);
      stats.merge_memory_bytes = std::max(stats.merge_memory_bytes, merging->memory_bytes());
    }
  };
  // Adaptive sampling ends when every pixel stopped (converged or at its maximum): its pixels take unequal counts, so
  // the schedule's position is no pixel's count and may pass the maximum.
  const auto more_passes = [&] {
    if (options.adaptive) return options.adaptive->active_count() > 0;
    return options.first_sample + stats.samples_per_pixel_done < options.samples_per_pixel;
  };
  while (more_passes()) {
    const int first = options.first_sample + stats.samples_per_pixel_done;
    const int pass_end = sample_pass_end(first);
    const int count = (options.adaptive ? pass_end : std::min(pass_end, options.samples_per_pixel)) - first;
    if (options.start_pass && !options.start_pass(first, count)) {
      stats.stopped_by_start_pass = true;
      break;
    }
    std::vector<std::unique_ptr<FilmTile>> results(tiles.size());
    std::vector<FeatureTile> feature_results(options.features ? tiles.size() : 0);
    std::atomic<bool> stopped{false};
    std::atomic<uint64_t> pass_camera_samples{0};
    // Record while the history has room and a field fitted to it could still guide a later pass (the fit after
    // the pass reaching next_fit must leave a pass to guide).
    const bool train = stats.guiding.active && guiding_history.size() < kGuidingSampleBudget &&
                       first + count < options.samples_per_pixel && options.first_sample + next_fit < options.samples_per_pixel;
    if (train) {
      guiding_records.resize(tiles.size());
    } else if (!guiding_history.empty()) {
      // Training is over for this call (it never resumes: every condition above only becomes false): the field
      // stays, the samples it was fitted to go.
      std::vector<std::vector<GuidingSample>>().swap(guiding_records);
      std::vector<GuidingSample>().swap(guiding_history);
    }
    // The pass's share of the remaining budget, split equally by the tiles so that which samples are kept does not
    // depend on the threads.
    const size_t tile_record_limit = train ? (kGuidingSampleBudget - guiding_history.size()) / tiles.size() : 0;

    // With vertex merging, the pass is taken one sample index at a time (each after its light vertices); else at once.
    const int sub_passes = merging ? count : 1;
    for (int sub_pass = 0; sub_pass < sub_passes && !stopped; ++sub_pass) {
      const int sample_begin = merging ? first + sub_pass : first;
      const int sample_end = merging ? sample_begin + 1 : first + count;
      if (merging) trace_merge_pass(sample_begin);
      // Caustic light tracing: each tile's splats, held until every tile before it has finished, then spread into
      // the pass's splat tile in tile order (commit_splats), so that the image does not depend on the threads and
      // at most the tiles ahead of the slowest one wait in memory. Tiles are then scheduled in index order. The
      // splat tile joins the film when the pass is complete (an interrupted pass drops it with its samples).
      std::mutex splat_mutex;
      size_t next_commit = 0;
      if (splatting) {
        caustic_splats.assign(tiles.size(), {});
        caustic_done.assign(tiles.size(), 0);
        if (sub_pass == 0) caustic_tile.emplace(film.make_tile(film.pixel_bounds()));
      }
      const auto commit_splats = [&](size_t finished) {
        std::lock_guard<std::mutex> lock(splat_mutex);
        caustic_done[finished] = 1;
        for (; next_commit < tiles.size() && caustic_done[next_commit]; ++next_commit) {
          add_caustic_splats(caustic_splats[next_commit], filter, *caustic_tile);
          std::vector<CausticSplat>().swap(caustic_splats[next_commit]);
        }
      };
      // Each tile's samples in this pass (also what it reports when done), from which the schedule predicts its cost:
      // the costliest tiles go first.
      for (size_t t = 0; t < tiles.size(); ++t) {
        const PixelBounds& b = tiles[t];
        uint64_t samples = uint64_t(b.width()) * uint64_t(b.height()) * uint64_t(count);
        if (options.adaptive) {
          samples = 0;
          for (int y = b.y0; y < b.y1; ++y)
            for (int x = b.x0; x < b.x1; ++x) samples += uint64_t(options.adaptive->pass_samples(x, y));
        }
        planned_samples[t] = samples;
      }
      std::vector<size_t> index_order;
      if (splatting) {
        index_order.resize(tiles.size());
        for (size_t t = 0; t < tiles.size(); ++t) index_order[t] = t;
      }
      const std::vector<size_t>& tile_order = splatting ? index_order : schedule.order(planned_samples);

      // Each worker takes the next tile of the order until none is left (list scheduling): a split of the order into
      // ranges, as parallel_for's partitioners make, would give one thread all of the costliest tiles.
      const size_t workers =
          std::min(tiles.size(), tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
      std::atomic<size_t> next_position{0};
      tbb::parallel_for(size_t(0), workers, [&](size_t) {
        std::unique_ptr<Sampler> sampler = prototype_sampler->clone();
        std::unique_ptr<Sampler> feature_sampler = feature_prototype ? feature_prototype->clone() : nullptr;
        std::unique_ptr<Sampler> caustic_sampler = caustic_prototype ? caustic_prototype->clone() : nullptr;
        // Light groups (render/film/film.h): each sample's share per group. A film without groups passes an empty
        // LightGroupRadiance, and the integrator and film skip the per-group work.
        std::vector<SampledSpectrum> group_slots(film.light_groups().size());
        const LightGroupRadiance groups{group_slots.empty() ? nullptr : group_slots.data(), int(group_slots.size())};
        for (size_t position = next_position++; position < tiles.size(); position = next_position++) {
          const size_t t = tile_order[position];
          if (options.interrupt && options.interrupt->requested()) {
            stopped = true;
            return;
          }
          const auto tile_start = std::chrono::steady_clock::now();
          if (!results[t]) {
            results[t] = std::make_unique<FilmTile>(film.make_tile(tiles[t]));
            if (options.features) feature_results[t] = options.features->make_tile(results[t]->bounds());
          }
          FilmTile* const tile = results[t].get();
          PathGuidingContext guiding;
          guiding.field = guiding_field ? &*guiding_field : nullptr;
          guiding.record = train ? &guiding_records[t] : nullptr;
          guiding.record_limit = tile_record_limit;
          const PixelBounds& b = tile->bounds();
          for (int y = b.y0; y < b.y1; ++y) {
            for (int x = b.x0; x < b.x1; ++x) {
              // Adaptive sampling: the pixel's own count for this pass, continuing its own sample indices.
              const int pixel_first = options.adaptive ? options.adaptive->samples(x, y) : sample_begin;
              const int pixel_count = options.adaptive ? options.adaptive->pass_samples(x, y) : sample_end - sample_begin;
              const uint64_t rays_before = rays_traced_by_this_thread();
              for (int s = pixel_first; s < pixel_first + pixel_count; ++s) {
                sampler->start_pixel_sample(x, y, uint32_t(s));
                // Dimension order: film (2), lens (2), wavelengths (1; independent mode 4), the shutter time (1, only
                // in a scene where something moves); then per-bounce ones.
                const FilterSample fs = filter.sample(sampler->next_2d());
                const Vec2 lens = sampler->next_2d();
                SampledWavelengths lambda =
                    sample_path_wavelengths(integrator_settings.wavelengths, *sampler, wavelength_density);
                // Merging: the wavelengths of the sample's bucket (its own draw is kept, so the dimensions line up).
                MergeContext merge_context;
                if (merging) {
                  merge_context = {&*merging, merging->pixel_bucket(x, y, s)};
                  lambda = merging->wavelengths(merge_context.bucket);
                  // The pass's light subpath of this pixel serves its joins where it has the sample's wavelengths
                  // and time (where things move it was traced at its own).
                  const int64_t pixel = int64_t(y - film_bounds.y0) * film_bounds.width() + (x - film_bounds.x0);
                  if (!surfaces.has_motion && pixel < merging->light_subpath_count() &&
                      merging->subpath_bucket(int(pixel)) == merge_context.bucket) {
                    merge_context.reuse_light_subpath = true;
                    merge_context.light_subpath =
                        merging->light_subpath(int(pixel), merge_context.light_subpath_length);
                  }
                }
                const float time = surfaces.has_motion ? sampler->next_1d() : 0.0f;
                const float film_x = float(x) + 0.5f + fs.offset_px.x, film_y = float(y) + 0.5f + fs.offset_px.y;
                const Ray ray = camera.generate_ray(film_x, film_y, lens, time);
                SampledSpectrum radiance;
                if (groups.groups) std::fill(group_slots.begin(), group_slots.end(), SampledSpectrum(0.0f));
                if constexpr (kBidirectional) {
                  // The light subpath from the light paths' own stream, as the caustic tracer's.
                  caustic_sampler->start_pixel_sample(x, y, uint32_t(s));
                  radiance = integrator.radiance(ray, lambda, *sampler, *caustic_sampler, caustic_splats[t], groups,
                                                 merging ? &merge_context : nullptr);
                } else if (differentials_scale > 0.0f) {
                  const RayDifferentials d = camera.generate_differentials(ray, film_x, film_y, lens, differentials_scale);
                  radiance = integrator.radiance(ray, &d, lambda, *sampler, guiding, groups);
                } else {
                  radiance = integrator.radiance(ray, nullptr, lambda, *sampler, guiding, groups);
                }
                if (caustics) {
                  // One light path per camera sample, from its own stream (the camera paths draw what they drew
                  // without it), at the sample's wavelengths and time.
                  caustic_sampler->start_pixel_sample(x, y, uint32_t(s));
                  caustics->trace(lambda, *caustic_sampler, time, camera, caustic_splats[t]);
                }
                if (!options.features && !options.adaptive) {
                  tile->add_sample(x, y, radiance, lambda, fs.weight, groups.groups);
                  continue;
                }
                // The sample's share of the film's sums is read back from the tile, so the half buffers hold exactly
                // what the film does (discarded samples included).
                const double* sums = tile->pixel(x, y);
                const double before[4] = {sums[0], sums[1], sums[2], sums[FilmTile::kWeight]};
                tile->add_sample(x, y, radiance, lambda, fs.weight, groups.groups);
                if (options.adaptive && sums[FilmTile::kWeight] - before[3] > 0.0) {
                  const double weight = sums[FilmTile::kWeight] - before[3];
                  const double value[3] = {(sums[0] - before[0]) / weight, (sums[1] - before[1]) / weight,
                                           (sums[2] - before[2]) / weight};
                  options.adaptive->add_sample_value(x, y, value);
                }
                if (!options.features) continue;
                FeatureSample feature;
                feature.half = s & 1;
                for (int k = 0; k < 3; ++k) feature.beauty_sum[size_t(k)] = sums[k] - before[k];
                feature.beauty_weight = sums[FilmTile::kWeight] - before[3];
                if (feature.beauty_weight > 0.0) {
                  feature_sampler->start_pixel_sample(x, y, uint32_t(s));
                  const PathFeatures f = first_diffuse_features(surfaces, ray, lambda, *feature_sampler, media);
                  feature.albedo = feature_albedo_channels(f, lambda, film.response());
                  feature.normal = f.normal;
                  feature.depth = f.depth;
                }
                feature_results[t].add(x, y, feature);
              }
              if (options.adaptive) options.adaptive->add_rays(x, y, rays_traced_by_this_thread() - rays_before);
            }
          }
          // The samples the tile took, as planned before the pass: uniform, every pixel's; adaptive, each pixel's own
          // count (a render that ends with every pixel stopped is marked complete by its caller).
          const uint64_t tile_samples = planned_samples[t] / uint64_t(sub_passes);
          if (options.progress) options.progress->add(tile_samples);
          pass_camera_samples += tile_samples;
          schedule.record(t, std::chrono::duration<double>(std::chrono::steady_clock::now() - tile_start).count(),
                          tile_samples);
          if (splatting) commit_splats(t);
        }
      });
    }
    if (stopped) {
      stats.interrupted = true;  // the unfinished pass is dropped: every pixel keeps the same sample count
      break;
    }
    for (const auto& tile : results) film.merge_tile(*tile);
    // The light paths' splats of the pass (committed in tile order while it ran), now that it is complete.
    if (splatting) film.merge_tile(*caustic_tile);
    for (const FeatureTile& tile : feature_results) options.features->merge_tile(tile);
    if (train) {
      for (auto& r : guiding_records) {
        guiding_history.insert(guiding_history.end(), r.begin(), r.end());
        r.clear();
      }
    }
    const int done_in_call = first + count - options.first_sample;
    if (train && (done_in_call >= next_fit || guiding_history.size() >= kGuidingSampleBudget)) {
      next_fit = 2 * done_in_call + 1;
      guiding_field = GuidingField::build(guiding_history, done_in_call, guiding_settings,
                                          [](size_t leaves, const std::function<void(size_t)>& fit) {
                                            tbb::parallel_for(size_t(0), leaves, [&](size_t leaf) { fit(leaf); });
                                          });
      ++stats.guiding.training_passes;
      stats.guiding.samples_recorded = guiding_history.size();
      if (guiding_field->memory_bytes() > stats.guiding.memory_bytes) {
        stats.guiding.memory_bytes = guiding_field->memory_bytes();
        stats.guiding.spatial_leaves = guiding_field->leaf_count();
        stats.guiding.directional_nodes = guiding_field->directional_node_count();
      }
    }
    stats.samples_per_pixel_done += count;
    stats.camera_samples += pass_camera_samples.load();
    if (options.after_pass) options.after_pass(first + count);
    if (options.interrupt && options.interrupt->requested()) {
      stats.interrupted = more_passes();
      break;
    }
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

// Metropolis light transport splats paths anywhere on the film and gives every pixel the same sample count: it has
// no per-pixel counts for adaptive sampling, no half buffers for a denoiser, and its splats carry the beauty only
// (no light groups or spectral bins) and bypass the sample clamp (a clamp of each path's value would weight the
// chains' splats, which all have the brightness b, arbitrarily); a partial render (first_sample > 0) could not
// continue the chains.
bool metropolis_possible(const Film& film, const RenderOptions& options) {
  return !options.adaptive && !options.features && options.first_sample == 0 && film.light_groups().empty() &&
         film.binning().count == 0 && !film.max_sample_value();
}

}  // namespace

RenderStatistics render(const TransportScene& transport, const PathIntegratorSettings& integrator_settings,
                        const Camera& camera, const PixelFilter& filter, Film& film, const RenderOptions& options) {
  // Caustic light tracing needs a camera it can connect to (pinhole or thin lens) and one light path per camera sample of every pixel
  // alike (adaptive sampling gives pixels unequal counts, which its splats would be divided by): elsewhere the
  // path tracer keeps every caustic.
  PathIntegratorSettings settings = integrator_settings;
  // Bidirectional path tracing: the same needs; it has caustics of its own and does not guide.
  if (settings.bidirectional && camera.supports_light_tracing() && !options.adaptive) {
    settings.caustic_light_tracing = false;
    settings.guiding = false;
    const BidirectionalPathIntegrator integrator(transport, settings, camera, double(film.pixel_bounds().area()));
    RenderStatistics stats =
        render_loop(integrator, settings, transport, transport.wavelength_density, camera, filter, film, options);
    stats.bidirectional = true;
    return stats;
  }
  if (settings.metropolis && metropolis_possible(film, options)) {
    settings.caustic_light_tracing = false;
    settings.guiding = false;
    if (settings.metropolis_settings.bidirectional && camera.supports_light_tracing()) {
      // Over bidirectional path tracing: one point of primary sample space draws the camera and the light subpath.
      const BidirectionalPathIntegrator integrator(transport, settings, camera, double(film.pixel_bounds().area()));
      const CameraPathRadiance radiance = [&](const Ray& ray, const SampledWavelengths& lambda, Sampler& sampler,
                                              std::vector<CausticSplat>& light_splats) {
        return integrator.radiance(ray, lambda, sampler, sampler, light_splats);
      };
      RenderStatistics stats = render_metropolis(radiance, settings.metropolis_settings, settings.wavelengths,
                                                 transport.wavelength_density, transport.has_motion, camera, filter,
                                                 film, options);
      stats.metropolis = true;
      stats.bidirectional = true;
      return stats;
    }
    const PathIntegrator integrator(transport, settings);
    const CameraPathRadiance radiance = [&](const Ray& ray, const SampledWavelengths& lambda, Sampler& sampler,
                                            std::vector<CausticSplat>&) {
      return integrator.radiance(ray, nullptr, lambda, sampler, PathGuidingContext{});
    };
    RenderStatistics stats = render_metropolis(radiance, settings.metropolis_settings, settings.wavelengths,
                                               transport.wavelength_density, transport.has_motion, camera, filter,
                                               film, options);
    stats.metropolis = true;
    return stats;
  }
  settings.caustic_light_tracing = settings.caustic_light_tracing && camera.supports_light_tracing() && !options.adaptive;
  const PathIntegrator integrator(transport, settings);
  RenderStatistics stats =
      render_loop(integrator, settings, transport, transport.wavelength_density, camera, filter, film, options);
  stats.caustic_light_tracing = settings.caustic_light_tracing;
  return stats;
}

RenderStatistics render(const VolumetricScene& scene, const VolumetricIntegratorSettings& integrator_settings,
                        const Camera& camera, const PixelFilter& filter, Film& film, const RenderOptions& options) {
  if (integrator_settings.path.metropolis && metropolis_possible(film, options)) {
    VolumetricIntegratorSettings settings = integrator_settings;
    settings.path.guiding = false;
    const VolumetricPathIntegrator integrator(scene, settings);
    const CameraPathRadiance radiance = [&](const Ray& ray, const SampledWavelengths& lambda, Sampler& sampler,
                                            std::vector<CausticSplat>&) {
      return integrator.radiance(ray, nullptr, lambda, sampler, PathGuidingContext{});
    };
    RenderStatistics stats = render_metropolis(radiance, settings.path.metropolis_settings, settings.path.wavelengths,
                                               scene.surfaces.wavelength_density, scene.surfaces.has_motion, camera,
                                               filter, film, options);
    stats.metropolis = true;
    return stats;
  }
  const VolumetricPathIntegrator integrator(scene, integrator_settings);
  return render_loop(integrator, integrator_settings.path, scene.surfaces, scene.surfaces.wavelength_density, camera,
                     filter, film, options, &scene);
}

}  // namespace rimu
