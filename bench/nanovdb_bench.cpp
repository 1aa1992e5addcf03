// Memory and density-lookup cost of the grid medium's two density sources, dense (.rvol) and sparse NanoVDB
// (.nvdb), on the same procedural cloud, from one command:
//
//   cmake --build build -j2 --target rimu-nanovdb-bench && build/bin/rimu-nanovdb-bench
//
// Writes the cloud (procedural_cloud_density, n³ voxels) as an .nvdb file in a temporary folder with NanoVDB's
// builder (voxels of density 0 left out, so the file is sparse), loads it, and times density() at random points of
// the box and at points 0.3 voxels apart along random rays (what tracking does), for voxel and trilinear lookup.
// Options: --n N (default 256), --lookups M (default 4000000).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>

#include <CLI/CLI.hpp>
#include <nanovdb/util/GridBuilder.h>

#include "transport/media/grid_medium.h"
#include "transport/media/nanovdb_grid.h"
#include "transport/media/nanovdb_io.h"

using namespace rimu;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ns per density() over `points` (the sum is printed so the loop is not optimised away).
double ns_per_lookup(const GridMedium& medium, const std::vector<Vec3>& points, double& sum) {
  const auto start = std::chrono::steady_clock::now();
  double s = 0.0;
  for (const Vec3& p : points) s += medium.density(p);
  sum += s;
  return seconds_since(start) * 1e9 / double(points.size());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Dense against NanoVDB grid media: memory per voxel and density lookup cost");
  int n = 256, lookups = 4000000;
  app.add_option("--n", n, "voxels per side of the procedural cloud")->check(CLI::Range(8, 1024));
  app.add_option("--lookups", lookups, "density lookups per measurement")->check(CLI::Range(1000, 100000000));
  CLI11_PARSE(app, argc, argv);

  const std::vector<float> density = procedural_cloud_density(n, 1);
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "rimu_nanovdb_bench.nvdb";
  {
    nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
    auto accessor = builder.getAccessor();
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          if (const float d = density[size_t((z * n + y) * n + x)]; d > 0.0f) accessor.setValue(nanovdb::Coord(x, y, z), d);
    // Voxel (x, y, z) centred at ((x + ½)/n, …): the dense grid's layout on the unit box.
    nanovdb::io::writeGrid(file.string(), builder.getHandle<>(1.0 / n, nanovdb::Vec3d(0.5 / n), "density"),
                           nanovdb::io::Codec::NONE);
  }
  const auto load_start = std::chrono::steady_clock::now();
  const auto sparse = NanoVdbGrid::load(file, "density");
  const double load_s = seconds_since(load_start);
  const uint64_t file_bytes = std::filesystem::file_size(file);
  std::filesystem::remove(file);

  const SpectrumPtr one = std::make_shared<ConstantSpectrum>(1.0);
  const uint64_t dense_bytes = uint64_t(n) * uint64_t(n) * uint64_t(n) * sizeof(float);
  std::printf("cloud %d³: %llu active voxels (%.1f%% of the box)\n", n, (unsigned long long)sparse->active_voxel_count(),
              100.0 * double(sparse->active_voxel_count()) / double(n) / double(n) / double(n));
  std::printf("dense .rvol densities: %.1f MB (%.2f bytes per active voxel)\n", double(dense_bytes) / 1e6,
              double(dense_bytes) / double(sparse->active_voxel_count()));
  std::printf("NanoVDB: file %.1f MB, in memory %.1f MB with majorants (%.2f bytes per active voxel), load %.3f s\n",
              double(file_bytes) / 1e6, double(sparse->memory_bytes()) / 1e6,
              double(sparse->memory_bytes()) / double(sparse->active_voxel_count()), load_s);

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec3> random_points(static_cast<size_t>(lookups));
  std::vector<Vec3> ray_points;
  for (Vec3& p : random_points) p = {u(rng), u(rng), u(rng)};
  const float step = 0.3f / float(n);
  while (ray_points.size() < size_t(lookups)) {
    const Vec3 from{u(rng), u(rng), u(rng)};
    const Vec3 direction = normalize(Vec3{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f});
    for (float t = 0.0f; t < 1.0f && ray_points.size() < size_t(lookups); t += step) ray_points.push_back(from + direction * t);
  }
  double sum = 0.0;
  std::printf("ns per density() lookup (%d lookups, one thread):\n", lookups);
  std::printf("%-10s %-12s %12s %12s\n", "lookup", "source", "random", "along rays");
  for (const auto interpolation : {GridInterpolation::voxel, GridInterpolation::trilinear}) {
    const char* name = interpolation == GridInterpolation::voxel ? "voxel" : "trilinear";
    const GridMedium dense(n, n, n, density, {0, 0, 0}, {1, 1, 1}, one, one, 0.0f, interpolation);
    const GridMedium nvdb(sparse, one, one, 0.0f, interpolation);
    for (const GridMedium* medium : {&dense, &nvdb}) {
      const double random_ns = ns_per_lookup(*medium, random_points, sum);
      const double ray_ns = ns_per_lookup(*medium, ray_points, sum);
      std::printf("%-10s %-12s %12.1f %12.1f\n", name, medium == &dense ? "dense" : "NanoVDB", random_ns, ray_ns);
    }
  }
  std::printf("(checksum %.3f)\n", sum);
  return 0;
}
