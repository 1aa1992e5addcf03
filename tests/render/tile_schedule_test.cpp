// The order of a pass's tiles (render/tile_schedule.h): the costliest first, predicted from each tile's last pass,
// and an adaptive render whose tiles were handed out in timing-dependent orders is still bit-identical across
// thread counts.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>

#include "integration_support.h"
#include "render/film/adaptive_sampling.h"
#include "render/tile_schedule.h"

using namespace rimu;

TEST_CASE("tile schedule: untimed tiles go in image order, or by their planned samples when these differ") {
  TileSchedule schedule(4);
  CHECK(schedule.order({16, 16, 16, 16}) == std::vector<size_t>{0, 1, 2, 3});
  CHECK(schedule.order({4, 64, 16, 64}) == std::vector<size_t>{1, 3, 2, 0});
}

TEST_CASE("tile schedule: a tile's cost is its last pass's seconds per sample times its samples now") {
  TileSchedule schedule(4);
  schedule.record(0, 1.0, 100);  // 10 ms a sample
  schedule.record(1, 0.1, 100);  // 1 ms
  schedule.record(2, 0.4, 100);  // 4 ms
  schedule.record(3, 0.2, 100);  // 2 ms
  CHECK(schedule.order({16, 16, 16, 16}) == std::vector<size_t>{0, 2, 3, 1});
  // Tile 1 takes 20 times the samples of the others now: 20 ms against 10, 4 and 2.
  CHECK(schedule.order({16, 320, 16, 16}) == std::vector<size_t>{1, 0, 2, 3});
  // A tile that took no samples keeps its last estimate; a tile that takes none now costs nothing.
  schedule.record(0, 0.0, 0);
  CHECK(schedule.order({16, 16, 16, 0}) == std::vector<size_t>{0, 2, 1, 3});
}

TEST_CASE("tile schedule: a tile never timed is predicted at the timed tiles' mean seconds per sample") {
  TileSchedule schedule(3);
  schedule.record(0, 0.3, 100);  // 3 ms a sample
  schedule.record(2, 0.1, 100);  // 1 ms: tile 1 is taken at 2 ms
  CHECK(schedule.order({10, 10, 10}) == std::vector<size_t>{0, 1, 2});
  CHECK(schedule.order({10, 10, 25}) == std::vector<size_t>{0, 2, 1});
}

TEST_CASE("tile schedule: an adaptive render on 1 and on 2 threads gives a bit-identical film and counts") {
  // The Cornell box's centre, 64×64 (16 tiles of unequal cost: the light, the blocks, the walls), adaptive sampling
  // with a threshold no pixel reaches for eight passes of the schedule (1, 2, 4, 8, 16, 16, 16, 16 samples): from
  // the second pass on the tiles go in the order their timings predict, which differs from run to run.
  const auto scene = load_scene(default_scene_path(test::library()), test::library());
  const PixelBounds crop{96, 96, 160, 160};
  struct Result {
    std::vector<double> bits;
    std::vector<int> samples;
  };
  auto render_adaptive = [&](int threads) {
    Film film(FilmOptions{scene->settings.width, scene->settings.height, crop, 0},
              SpectralResponse::cie_xyz(test::library()));
    AdaptiveSamplingSettings settings;
    settings.noise_threshold = 1e-6;
    settings.max_spp = 1 << 20;
    AdaptiveSampling sampling(film, settings);
    RenderOptions options;
    options.samples_per_pixel = 1 << 20;
    options.threads = threads;
    options.seed = 5;
    options.adaptive = &sampling;
    int started = 0;
    options.start_pass = [&](int, int count) {
      if (started++ == 8) return false;
      sampling.plan_pass(count);
      return true;
    };
    options.after_pass = [&](int reached) { sampling.after_pass(film, reached); };
    render(*scene, test::filter_of(*scene), film, options);
    Result r{test::film_bits(film), {}};
    for (int y = crop.y0; y < crop.y1; ++y)
      for (int x = crop.x0; x < crop.x1; ++x) r.samples.push_back(sampling.samples(x, y));
    return r;
  };
  const Result one = render_adaptive(1), two = render_adaptive(2);
  REQUIRE(one.bits.size() == two.bits.size());
  CHECK(std::memcmp(one.bits.data(), two.bits.data(), one.bits.size() * sizeof(double)) == 0);
  CHECK(one.samples == two.samples);
  // The counts are unequal (the schedule had different costs to order), and every pass's samples were taken.
  const auto [fewest, most] = std::minmax_element(one.samples.begin(), one.samples.end());
  CHECK(*most > *fewest);
}
