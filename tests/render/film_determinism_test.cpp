// Tiles merged in any order, serially or in parallel, give a bit-identical film.
#include <doctest/doctest.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "render/film/film.h"
#include "test_support.h"
#include "transport/sampling/sampler.h"

using namespace rimu;

namespace {

constexpr int kWidth = 24, kHeight = 16, kTile = 8, kSpp = 16, kBins = 12;

std::vector<PixelBounds> tiles() {
  std::vector<PixelBounds> out;
  for (int y = 0; y < kHeight; y += kTile)
    for (int x = 0; x < kWidth; x += kTile) out.push_back({x, y, std::min(x + kTile, kWidth), std::min(y + kTile, kHeight)});
  return out;
}

// The samples of one tile: a deterministic function of (pixel, sample index), as a renderer's sampler is.
void render_tile(FilmTile& tile) {
  const PixelBounds& b = tile.bounds();
  for (int y = b.y0; y < b.y1; ++y) {
    for (int x = b.x0; x < b.x1; ++x) {
      for (uint32_t s = 0; s < kSpp; ++s) {
        const uint64_t h = mix_bits((uint64_t(y) << 40) ^ (uint64_t(x) << 20) ^ s);
        const float u = float(h >> 40) * 0x1p-24f;
        const float l = float((h >> 8) & 0xFFFF) * 0x1p-12f;  // radiance in [0, 16)
        tile.add_sample(x, y, Float4(l, 0.5f * l, 2.0f * l, 0.1f), SampledWavelengths::sample_visible(u));
      }
    }
  }
}

std::vector<double> snapshot(const Film& film) {
  std::vector<double> out;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const auto v = film.pixel_value(x, y);
      out.insert(out.end(), v.begin(), v.end());
      for (int b = 0; b < kBins; ++b) out.push_back(film.spectral_value(x, y, b));
    }
  }
  return out;
}

}  // namespace

TEST_CASE("films fed the same tiles in different orders and threads are bit-identical") {
  const SpectralResponse xyz = SpectralResponse::cie_xyz(test::library());
  const FilmOptions options{kWidth, kHeight, {}, kBins};
  std::vector<PixelBounds> order = tiles();

  // Two passes per tile (as a progressive renderer does): pass order is fixed, tile order within a pass is not.
  Film serial(options, xyz);
  for (int pass = 0; pass < 2; ++pass)
    for (const PixelBounds& b : order) {
      FilmTile tile = serial.make_tile(b);
      render_tile(tile);
      serial.merge_tile(tile);
    }

  Film shuffled(options, xyz);
  std::mt19937 rng(7);
  for (int pass = 0; pass < 2; ++pass) {
    std::shuffle(order.begin(), order.end(), rng);
    for (const PixelBounds& b : order) {
      FilmTile tile = shuffled.make_tile(b);
      render_tile(tile);
      shuffled.merge_tile(tile);
    }
  }

  Film parallel(options, xyz);
  for (int pass = 0; pass < 2; ++pass)
    tbb::parallel_for(size_t(0), order.size(), [&](size_t i) {
      FilmTile tile = parallel.make_tile(order[i]);
      render_tile(tile);
      parallel.merge_tile(tile);  // tiles are disjoint: no lock
    });

  const std::vector<double> a = snapshot(serial), b = snapshot(shuffled), c = snapshot(parallel);
  REQUIRE(a.size() == b.size());
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
  CHECK(std::memcmp(a.data(), c.data(), a.size() * sizeof(double)) == 0);
  CHECK(serial.sample_counts().accepted == uint64_t(2 * kWidth * kHeight * kSpp));
  CHECK(parallel.sample_counts().accepted == serial.sample_counts().accepted);
  CHECK(serial.weight_sum(5, 5) == 2 * kSpp);
  // Not trivially equal: the pixels differ from each other.
  CHECK(a[0] != a[3 + kBins]);
}
