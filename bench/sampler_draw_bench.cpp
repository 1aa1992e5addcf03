// Cost of one sampler draw (issue 8's time-per-sample target): the random numbers a camera sample consumes,
// without the rest of the path. A camera sample of the Cornell box draws ~20 dimensions: one start_pixel_sample
// and then a mix of next_1d/next_2d (pixel, lens, wavelength, then per bounce light choice, light position, BSDF
// lobe and direction, Russian roulette). BM_CameraSample replays that mix, so its time per item is what the
// sampler adds to one camera sample. Build Release and run
//   build/bin/rimu-sampler-draw-bench
// (pin to one core with `taskset -c 1` on a shared machine; the figures are CPU time per item).
#include <benchmark/benchmark.h>

#include <memory>

#include "transport/sampling/sampler.h"
#include "transport/sampling/sobol_sampler.h"

namespace {

using namespace rimu;

// One pixel sample: 1 start + 2D pixel, 2D lens, 1D wavelength, then 4 bounces of (1D light, 2D light position,
// 1D lobe, 2D direction, 1D roulette): 1 + 2 + 2 + 1 + 4·7 = 34 dimensions in 15 + 1 calls.
float camera_sample(Sampler& sampler, int x, int y, uint32_t index) {
  sampler.start_pixel_sample(x, y, index);
  float sum = 0;
  const Vec2 film = sampler.next_2d(), lens = sampler.next_2d();
  sum += film.x + film.y + lens.x + lens.y + sampler.next_1d();
  for (int bounce = 0; bounce < 4; ++bounce) {
    sum += sampler.next_1d();
    const Vec2 light = sampler.next_2d();
    sum += light.x + light.y + sampler.next_1d();
    const Vec2 direction = sampler.next_2d();
    sum += direction.x + direction.y + sampler.next_1d();
  }
  return sum;
}

// Visits 64×64 pixels, `samples_per_pixel` consecutive samples of each pixel before the next pixel: 1 is the
// worst case for per-pixel caching, 16 is the render loop's order from its sixth pass on (renderer.cpp).
void run_camera_samples(benchmark::State& state, SamplerKind kind, uint32_t samples_per_pixel) {
  const std::unique_ptr<Sampler> sampler = make_sampler(kind, 1);
  uint32_t index = 0, first_index = 0;
  int x = 0, y = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(camera_sample(*sampler, x, y, index));
    if (++index - first_index < samples_per_pixel) continue;
    index = first_index;
    if (++x == 64) x = 0, ++y;
    if (y == 64) y = 0, first_index += samples_per_pixel, index = first_index;
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel("items = camera samples of 34 dimensions (16 calls)");
}

void BM_CameraSample_Independent(benchmark::State& state) { run_camera_samples(state, SamplerKind::independent, 1); }
BENCHMARK(BM_CameraSample_Independent);
void BM_CameraSample_Sobol(benchmark::State& state) { run_camera_samples(state, SamplerKind::sobol, 1); }
BENCHMARK(BM_CameraSample_Sobol);
void BM_CameraSample16PerPixel_Independent(benchmark::State& state) {
  run_camera_samples(state, SamplerKind::independent, 16);
}
BENCHMARK(BM_CameraSample16PerPixel_Independent);
void BM_CameraSample16PerPixel_Sobol(benchmark::State& state) { run_camera_samples(state, SamplerKind::sobol, 16); }
BENCHMARK(BM_CameraSample16PerPixel_Sobol);

// A single 2D draw after a start (the per-draw cost without the start's hashing).
void run_draw_2d(benchmark::State& state, SamplerKind kind) {
  const std::unique_ptr<Sampler> sampler = make_sampler(kind, 1);
  uint32_t index = 0;
  int draws = 0;
  sampler->start_pixel_sample(3, 5, index);
  for (auto _ : state) {
    benchmark::DoNotOptimize(sampler->next_2d());
    if (++draws == 32) draws = 0, sampler->start_pixel_sample(3, 5, ++index);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_Draw2D_Independent(benchmark::State& state) { run_draw_2d(state, SamplerKind::independent); }
BENCHMARK(BM_Draw2D_Independent);
void BM_Draw2D_Sobol(benchmark::State& state) { run_draw_2d(state, SamplerKind::sobol); }
BENCHMARK(BM_Draw2D_Sobol);

}  // namespace

BENCHMARK_MAIN();
