// The NanoVDB density source of the grid medium (transport/media/nanovdb_grid.h): tiny .nvdb files written at test
// time with NanoVDB's own builder and writer, read back uncompressed, ZIP and BLOSC; densities against the dense grid
// medium with the same values; majorants that bound every lookup; transmittance through a constant box; and the
// load errors, each naming the file.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include <nanovdb/util/GridBuilder.h>

#include "spectral/error.h"
#include "test_support.h"
#include "transport/media/medium.h"
#include "transport/media/nanovdb_grid.h"
#include "transport/media/nanovdb_io.h"
#include "transmittance_statistics.h"

namespace rimu {
namespace {

const SpectrumPtr kSigmaA = std::make_shared<ConstantSpectrum>(0.3), kSigmaS = std::make_shared<ConstantSpectrum>(0.5);

// 3 × 2 × 2 voxels, x fastest, placed at index (5, −3, 7) + (x, y, z): an offset that is not leaf-aligned, and a
// box that straddles the leaf border at index 8 in z.
const std::vector<float> kDensity = {0.4f, 1.3f, 0.2f, 0.9f, 0.1f, 1.6f, 1.1f, 0.3f, 0.7f, 0.5f, 1.8f, 0.6f};
constexpr int kOx = 5, kOy = -3, kOz = 7;
constexpr double kVoxelM = 0.5;
const nanovdb::Vec3d kOrigin(1.0, 2.0, 3.0);  // world position of index (0, 0, 0)

template <typename T>
void write(const std::filesystem::path& path, nanovdb::GridBuilder<T>& builder, const std::string& name,
           nanovdb::io::Codec codec = nanovdb::io::Codec::NONE) {
  nanovdb::io::writeGrid(path.string(), builder.template getHandle<>(kVoxelM, kOrigin, name), codec);
}

void write_small(const std::filesystem::path& path, nanovdb::io::Codec codec) {
  nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
  auto accessor = builder.getAccessor();
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x)
        accessor.setValue(nanovdb::Coord(kOx + x, kOy + y, kOz + z), kDensity[size_t((z * 2 + y) * 3 + x)]);
  write(path, builder, "density", codec);
}

// The same densities as a dense grid medium: voxel (x, y, z) spans index [o + x − ½, o + x + ½], so world
// [origin + (o − ½)·h, …] per axis.
GridMedium dense_twin(GridInterpolation interpolation) {
  const Vec3 lo{float(kOrigin[0] + (kOx - 0.5) * kVoxelM), float(kOrigin[1] + (kOy - 0.5) * kVoxelM),
                float(kOrigin[2] + (kOz - 0.5) * kVoxelM)};
  const Vec3 hi = lo + Vec3{float(3 * kVoxelM), float(2 * kVoxelM), float(2 * kVoxelM)};
  return GridMedium(3, 2, 2, kDensity, lo, hi, kSigmaA, kSigmaS, 0.0f, interpolation);
}

std::string load_error(const std::filesystem::path& path, const std::string& grid = "density") {
  try {
    NanoVdbGrid::load(path, grid);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("nanovdb grid: the same densities as the dense grid medium, from uncompressed, ZIP and BLOSC files") {
  const test::ScratchFolder folder("nanovdb_same");
  for (const auto codec : {nanovdb::io::Codec::NONE, nanovdb::io::Codec::ZIP, nanovdb::io::Codec::BLOSC}) {
    CAPTURE(nanovdb::io::toStr(codec));
    const auto path = folder / "small.nvdb";
    write_small(path, codec);
    const auto sparse = NanoVdbGrid::load(path, "density");
    CHECK(sparse->active_voxel_count() == 12);
    CHECK(sparse->index_min() == std::array<int, 3>{kOx, kOy, kOz});
    CHECK(sparse->index_max() == std::array<int, 3>{kOx + 2, kOy + 1, kOz + 1});
    for (const auto interpolation : {GridInterpolation::voxel, GridInterpolation::trilinear}) {
      const GridMedium nvdb(sparse, kSigmaA, kSigmaS, 0.0f, interpolation);
      const GridMedium dense = dense_twin(interpolation);
      // Voxel centres hold the written values, in either lookup.
      for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
          for (int x = 0; x < 3; ++x) {
            const Vec3 centre{float(kOrigin[0] + (kOx + x) * kVoxelM), float(kOrigin[1] + (kOy + y) * kVoxelM),
                              float(kOrigin[2] + (kOz + z) * kVoxelM)};
            CHECK(nvdb.density(centre) == doctest::Approx(kDensity[size_t((z * 2 + y) * 3 + x)]).epsilon(1e-5));
          }
      // Random points over the box and half a box beyond it, in index units q. Voxel lookups: equal everywhere, 0
      // outside. Trilinear: pbrt-v4's box [min, max + 1] (NanoVDB's world box), so equal to the dense twin (box
      // [min − ½, max + ½]) where both boxes hold q, 0 outside [min, max + 1], and the sparse grid's own trilinear
      // fade between max + ½ and max + 1.
      std::mt19937 rng(3);
      std::uniform_real_distribution<float> u(-0.5f, 1.5f);
      const int origin[3] = {kOx, kOy, kOz}, size[3] = {3, 2, 2};
      for (int i = 0; i < 500; ++i) {
        double q[3];
        for (int a = 0; a < 3; ++a) q[a] = origin[a] - 0.5 + size[a] * u(rng);
        const Vec3 p{float(kOrigin[0] + q[0] * kVoxelM), float(kOrigin[1] + q[1] * kVoxelM),
                     float(kOrigin[2] + q[2] * kVoxelM)};
        CAPTURE(p.x);
        CAPTURE(p.y);
        CAPTURE(p.z);
        bool in_both = true, outside_sparse = false;
        for (int a = 0; a < 3; ++a) {
          const double lo = origin[a], hi = origin[a] + size[a] - 1;
          in_both = in_both && q[a] >= lo + 1e-4 && q[a] <= hi + 0.5 - 1e-4;
          outside_sparse = outside_sparse || q[a] < lo - 1e-4 || q[a] > hi + 1 + 1e-4;
        }
        if (interpolation == GridInterpolation::voxel || in_both)
          CHECK(nvdb.density(p) == doctest::Approx(dense.density(p)).epsilon(1e-4).scale(1e-6));
        else if (outside_sparse)
          CHECK(nvdb.density(p) == 0.0f);
      }
      CHECK(nvdb.density({0.0f, 0.0f, 0.0f}) == 0.0f);
    }
    // Trilinear halfway between the centres of voxels x = 0 and 1 (y = z = 0): the mean of 0.4 and 1.3.
    const GridMedium trilinear(sparse, kSigmaA, kSigmaS, 0.0f, GridInterpolation::trilinear);
    CHECK(trilinear.density({float(kOrigin[0] + (kOx + 0.5) * kVoxelM), float(kOrigin[1] + kOy * kVoxelM),
                             float(kOrigin[2] + kOz * kVoxelM)}) == doctest::Approx(0.85).epsilon(1e-5));
  }
}

TEST_CASE("nanovdb grid: every lookup along a ray is below its segment's majorant") {
  // Background 0.01 over a 30³ box from index −6 (leaves from −8 to 24) with spikes next to leaf borders: a
  // trilinear lookup spreads a spike one voxel into the neighbouring leaf's block, whose majorant must include it.
  const test::ScratchFolder folder("nanovdb_majorant");
  nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
  auto accessor = builder.getAccessor();
  for (int z = -6; z < 24; ++z)
    for (int y = -6; y < 24; ++y)
      for (int x = -6; x < 24; ++x) accessor.setValue(nanovdb::Coord(x, y, z), 0.01f);
  for (int k : {-1, 0, 7, 8, 15, 16}) accessor.setValue(nanovdb::Coord(k, k, k), 5.0f);
  accessor.setValue(nanovdb::Coord(7, 3, 12), 3.0f);
  write(folder / "spikes.nvdb", builder, "density");
  const auto sparse = NanoVdbGrid::load(folder / "spikes.nvdb", "density");
  const Transform placement = Transform::rotate(20.0f, {0, 0, 1});
  for (const auto interpolation : {GridInterpolation::voxel, GridInterpolation::trilinear}) {
    const GridMedium medium(sparse, kSigmaA, kSigmaS, 0.0f, interpolation, placement);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int checked = 0, violations = 0, above_background = 0;
    for (int r = 0; r < 400; ++r) {
      // Index box [−6.5, 23.5]³ → world via the file's map (0.5 m voxels from (1, 2, 3)), then the rotation.
      const auto world = [&](float ix, float iy, float iz) {
        return placement.point({float(kOrigin[0] + ix * kVoxelM), float(kOrigin[1] + iy * kVoxelM),
                                float(kOrigin[2] + iz * kVoxelM)});
      };
      const Vec3 target = world(-6.5f + 30 * u(rng), -6.5f + 30 * u(rng), -6.5f + 30 * u(rng));
      const Vec3 from = world(-20 + 60 * u(rng), -20 + 60 * u(rng), -20.0f);
      const Ray ray{from, normalize(target - from)};
      medium.for_each_majorant_segment(ray, 100.0f, [&](float t0, float t1, float majorant, const Ray&) {
        // Inside the segment only: a point rounded onto a block face may read the voxel across it (the spikes sit
        // on faces), which a continuous distance sample does with probability ~1e-7.
        for (int k = 1; k < 16; ++k) {
          const float d = medium.density(ray.origin + ray.direction * (t0 + (t1 - t0) * float(k) / 16.0f));
          ++checked;
          above_background += d > 0.02f;
          if (d > majorant * (1.0f + 1e-5f)) ++violations;
        }
        return true;
      });
    }
    CHECK(checked > 10000);
    CHECK(above_background > 0);  // the rays do meet spikes
    CHECK(violations == 0);
  }
}

TEST_CASE("nanovdb grid: ratio-tracking transmittance through a constant box equals exp(-sigma_t d)") {
  // 16³ voxels of density 0.2 at index [0, 15]³ (two leaves per axis), 0.5 m voxels. A ray along x through voxel
  // centres (y = z = 7) crosses the box [0, 16] (NanoVDB's world box, as pbrt-v4 clips it): density 0.2 between the
  // outer centres (15 voxels) and, trilinearly, a ramp from 0.2 to 0 over the voxel beyond the last centre (mean
  // 0.1): ∫ d = 0.2·15 + 0.1·1 = 3.1 voxel units = 1.55 m.
  const test::ScratchFolder folder("nanovdb_box");
  nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
  auto accessor = builder.getAccessor();
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) accessor.setValue(nanovdb::Coord(x, y, z), 0.2f);
  write(folder / "box.nvdb", builder, "density", nanovdb::io::Codec::ZIP);
  const Medium medium(GridMedium(NanoVdbGrid::load(folder / "box.nvdb", "density"), kSigmaA, kSigmaS, 0.0f,
                                 GridInterpolation::trilinear));
  const double sigma_t = 0.8, expected = std::exp(-sigma_t * 1.55);
  const Ray ray{{float(kOrigin[0] - 2.0), float(kOrigin[1] + 7 * kVoxelM), float(kOrigin[2] + 7 * kVoxelM)}, {1, 0, 0}};
  const test::TransmittanceStatistics s = test::transmittance_statistics(medium, ray, 20.0f, 100000);
  const double mean = s.mean, standard_error = s.standard_error;
  CAPTURE(mean);
  CAPTURE(expected);
  CAPTURE(standard_error);
  CHECK(std::fabs(mean - expected) <= 4.5 * standard_error + 1e-7);
}

TEST_CASE("nanovdb grid: load errors name the file and what was expected") {
  const test::ScratchFolder folder("nanovdb_errors");
  const auto good = folder / "good.nvdb";
  write_small(good, nanovdb::io::Codec::NONE);
  CHECK(load_error(good) == "no error");

  const std::string missing = load_error(folder / "missing.nvdb");
  CHECK(missing.find("missing.nvdb") != std::string::npos);
  CHECK(missing.find("no such file") != std::string::npos);

  const std::string text = load_error(folder.write("text.nvdb", "not a volume at all, just some text"));
  CHECK(text.find("text.nvdb") != std::string::npos);
  CHECK(text.find("not a NanoVDB file") != std::string::npos);

  // The file of another major version: the header's version word (bytes 8-11) rewritten to 29.3.0.
  std::ifstream in(good, std::ios::binary);
  const std::string original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string bytes = original;
  const uint32_t old_version = 29u << 21 | 3u << 10;
  bytes.replace(8, 4, reinterpret_cast<const char*>(&old_version), 4);
  const std::string version = load_error(folder.write("old.nvdb", bytes));
  CAPTURE(version);
  CHECK(version.find("old.nvdb") != std::string::npos);
  CHECK(version.find("written by NanoVDB 29.3.0") != std::string::npos);
  CHECK(version.find("this build reads NanoVDB " + std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) + ".x") !=
        std::string::npos);

  // A damaged metadata block claiming a 1 TB grid (its first uint64, after the 16-byte header): refused before
  // NanoVDB would allocate it.
  std::string huge = original;
  const uint64_t terabyte = uint64_t(1) << 40;
  huge.replace(16, 8, reinterpret_cast<const char*>(&terabyte), 8);
  const std::string size = load_error(folder.write("huge.nvdb", huge));
  CAPTURE(size);
  CHECK(size.find("huge.nvdb") != std::string::npos);
  CHECK(size.find("claims 1099511627776 bytes, more than the file holds") != std::string::npos);

  // A flipped byte inside the grid's buffer (uncompressed: the file's last gridSize bytes), in the tree's data (its
  // node offsets and counts, bytes 672-735 of the buffer), which NanoVDB's stored checksum covers: refused before
  // any lookup follows a damaged offset.
  uint64_t grid_bytes = 0;
  std::memcpy(&grid_bytes, original.data() + 16, 8);
  std::string flipped = original;
  flipped[original.size() - size_t(grid_bytes) + 700] ^= 0x5a;
  const std::string damaged = load_error(folder.write("flipped.nvdb", flipped));
  CAPTURE(damaged);
  CHECK(damaged.find("flipped.nvdb") != std::string::npos);
  CHECK(damaged.find("grid \"density\" is damaged: ") != std::string::npos);

  const std::string name = load_error(good, "temperature");
  CAPTURE(name);
  CHECK(name.find("good.nvdb") != std::string::npos);
  CHECK(name.find("no grid named \"temperature\"; the file holds \"density\" (float)") != std::string::npos);

  nanovdb::GridBuilder<double> doubles(0.0);
  doubles.getAccessor().setValue(nanovdb::Coord(0, 0, 0), 1.0);
  write(folder / "double.nvdb", doubles, "density");
  const std::string type = load_error(folder / "double.nvdb");
  CAPTURE(type);
  CHECK(type.find("double.nvdb") != std::string::npos);
  CHECK(type.find("holds double values; a density grid must hold float values") != std::string::npos);

  nanovdb::GridBuilder<float> infinite(0.0f);
  infinite.getAccessor().setValue(nanovdb::Coord(2, 3, 4), 1.0f);
  infinite.getAccessor().setValue(nanovdb::Coord(2, 3, 5), INFINITY);
  write(folder / "inf.nvdb", infinite, "density");
  const std::string inf = load_error(folder / "inf.nvdb");
  CAPTURE(inf);
  CHECK(inf.find("inf.nvdb") != std::string::npos);
  CHECK(inf.find("at voxel (2, 3, 5); densities must be finite") != std::string::npos);

  // Negative values are clamped at 0 by lookups (the majorants never go below 0 either).
  nanovdb::GridBuilder<float> negative(0.0f);
  negative.getAccessor().setValue(nanovdb::Coord(0, 0, 0), -1.0f);
  negative.getAccessor().setValue(nanovdb::Coord(1, 0, 0), 1.0f);
  write(folder / "negative.nvdb", negative, "density");
  const GridMedium clamped(NanoVdbGrid::load(folder / "negative.nvdb", "density"), kSigmaA, kSigmaS, 0.0f,
                           GridInterpolation::voxel);
  CHECK(clamped.density({float(kOrigin[0]), float(kOrigin[1]), float(kOrigin[2])}) == 0.0f);
  CHECK(clamped.density({float(kOrigin[0] + kVoxelM), float(kOrigin[1]), float(kOrigin[2])}) == 1.0f);
}

}  // namespace rimu
