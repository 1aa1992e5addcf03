#include "transport/media/grid_medium.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>

#include "spectral/error.h"
#include "spectral/io/input_file.h"
#include "transport/geometry/ray_box_clip.h"
#include "transport/media/nanovdb_grid.h"

namespace rimu {

GridMedium::GridMedium(int nx, int ny, int nz, std::vector<float> densities, Vec3 bounds_min, Vec3 bounds_max,
                       SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m, float g, GridInterpolation interpolation,
                       const std::optional<Transform>& world_from_grid)
    : nx_(nx), ny_(ny), nz_(nz), density_(std::move(densities)), min_(bounds_min), max_(bounds_max),
      majorant_min_(bounds_min), unit_(std::move(sigma_a_per_m), std::move(sigma_s_per_m), g),
      interpolation_(interpolation) {
  set_transform(world_from_grid);
  if (nx < 1 || ny < 1 || nz < 1) throw InputError({}, "a voxel grid needs at least one voxel per axis");
  if (density_.size() != size_t(nx) * size_t(ny) * size_t(nz))
    throw InputError({}, "the voxel grid holds " + std::to_string(density_.size()) + " values, expected nx*ny*nz");
  for (float d : density_)
    if (!(d >= 0.0f) || !std::isfinite(d)) throw InputError({}, "voxel densities must be finite and >= 0");
  const Vec3 extent = max_ - min_;
  if (!(extent.x > 0.0f && extent.y > 0.0f && extent.z > 0.0f)) throw InputError({}, "the medium's box is empty");
  voxel_size_ = {extent.x / float(nx), extent.y / float(ny), extent.z / float(nz)};
  choose_majorants(world_from_grid);
}

namespace {
// Block maxima of side `block` over an n-voxel grid, with `margin` voxels beyond each block (trilinear lookups read
// one voxel past the block). Blocks of side 2B are maxima of 2³ blocks of side B with the same margin: their voxel
// ranges [2Bb − m, 2Bb + 2B + m) are the union of the children's, so coarser levels are reductions, not new passes.
struct BlockMaxima {
  int block, nx, ny, nz;
  std::vector<float> maxima;
};

BlockMaxima coarser(const BlockMaxima& fine) {
  BlockMaxima out{fine.block * 2, (fine.nx + 1) / 2, (fine.ny + 1) / 2, (fine.nz + 1) / 2, {}};
  out.maxima.assign(size_t(out.nx) * out.ny * out.nz, 0.0f);
  for (int z = 0; z < fine.nz; ++z)
    for (int y = 0; y < fine.ny; ++y)
      for (int x = 0; x < fine.nx; ++x) {
        float& m = out.maxima[size_t((z / 2 * out.ny + y / 2) * out.nx + x / 2)];
        m = std::fmax(m, fine.maxima[size_t((z * fine.ny + y) * fine.nx + x)]);
      }
  return out;
}

}  // namespace

void GridMedium::choose_majorants(const std::optional<Transform>& world_from_grid) {
  const int margin = interpolation_ == GridInterpolation::trilinear ? 1 : 0;
  BlockMaxima level{4, (nx_ + 3) / 4, (ny_ + 3) / 4, (nz_ + 3) / 4, {}};
  level.maxima.assign(size_t(level.nx) * level.ny * level.nz, 0.0f);
  for (int bz = 0; bz < level.nz; ++bz)
    for (int by = 0; by < level.ny; ++by)
      for (int bx = 0; bx < level.nx; ++bx) {
        float m = 0.0f;
        for (int z = std::max(bz * 4 - margin, 0); z < std::min((bz + 1) * 4 + margin, nz_); ++z)
          for (int y = std::max(by * 4 - margin, 0); y < std::min((by + 1) * 4 + margin, ny_); ++y)
            for (int x = std::max(bx * 4 - margin, 0); x < std::min((bx + 1) * 4 + margin, nx_); ++x)
              m = std::fmax(m, density_[size_t((z * ny_ + y) * nx_ + x)]);
        level.maxima[size_t((bz * level.ny + by) * level.nx + bx)] = m;
      }

  // Cost of tracking per voxel of ray length, in DDA steps: a ray crosses about 1.5/B block faces per voxel
  // (|dx| + |dy| + |dz| averaged over directions is 1.5), and makes σ̄·v·E[majorant] tentative collisions, each a
  // density lookup worth ~3 DDA steps (σ̄ the largest σ_t per unit density, v a voxel's length in metres, E the
  // blocks' volume-weighted mean majorant: a ray spends its length in blocks in proportion to their volume). On the
  // pbrt-v3 cloud (σ̄·v ≈ 2) the estimate picks 4; measured there, render time with B = 4 was 0.87 of B = 8's and
  // B = 16's 1.08 (docs/benchmarks.md, "pbrt-v3 scenes", cloud's third round).
  const Vec3 world_voxel = world_from_grid ? Vec3{length(world_from_grid->vector({voxel_size_.x, 0, 0})),
                                                  length(world_from_grid->vector({0, voxel_size_.y, 0})),
                                                  length(world_from_grid->vector({0, 0, voxel_size_.z}))}
                                           : voxel_size_;
  // σ̄ bounded by the spectra's own maxima (the lanes' largest σ_t is at most their sum).
  const double largest_unit_sigma_t =
      std::max(0.0, unit_.sigma_a()->max_value()) + std::max(0.0, unit_.sigma_s()->max_value());
  const double collisions_per_voxel_at_density_1 =
      largest_unit_sigma_t * (world_voxel.x + world_voxel.y + world_voxel.z) / 3.0;
  constexpr double kLookupInDdaSteps = 3.0;
  const auto cost = [&](const BlockMaxima& l) {
    double weighted = 0.0;  // Σ majorant × voxels of the block inside the grid
    for (int bz = 0; bz < l.nz; ++bz)
      for (int by = 0; by < l.ny; ++by)
        for (int bx = 0; bx < l.nx; ++bx) {
          const double voxels = double(std::min(l.block, nx_ - bx * l.block)) * std::min(l.block, ny_ - by * l.block) *
                                std::min(l.block, nz_ - bz * l.block);
          weighted += voxels * l.maxima[size_t((bz * l.ny + by) * l.nx + bx)];
        }
    const double mean_majorant = weighted / (double(nx_) * ny_ * nz_);
    return 1.5 / l.block + kLookupInDdaSteps * collisions_per_voxel_at_density_1 * mean_majorant;
  };
  BlockMaxima best = level;
  double best_cost = cost(level);
  for (int k = 0; k < 2; ++k) {  // B = 8, 16
    level = coarser(level);
    const double c = cost(level);
    if (c < best_cost) best = level, best_cost = c;
  }
  block_ = best.block;
  mx_ = best.nx, my_ = best.ny, mz_ = best.nz;
  majorant_ = std::move(best.maxima);
}

GridMedium::GridMedium(std::shared_ptr<const NanoVdbGrid> sparse, SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m,
                       float g, GridInterpolation interpolation, const std::optional<Transform>& world_from_medium)
    : sparse_(std::move(sparse)), unit_(std::move(sigma_a_per_m), std::move(sigma_s_per_m), g),
      interpolation_(interpolation) {
  static_assert(kSparseBlock == 8, "the sparse grid's majorant blocks are NanoVDB's 8³ leaves");
  set_transform(world_from_medium ? *world_from_medium * sparse_->world_from_index() : sparse_->world_from_index());
  const auto& lo = sparse_->index_min();
  const auto& hi = sparse_->index_max();
  nx_ = hi[0] - lo[0] + 1, ny_ = hi[1] - lo[1] + 1, nz_ = hi[2] - lo[2] + 1;
  voxel_size_ = {1.0f, 1.0f, 1.0f};
  const NanoVdbGrid::Blocks& blocks = sparse_->blocks();
  if (interpolation_ == GridInterpolation::trilinear) {
    // pbrt-v4's box: the grid's world box, which NanoVDB takes as the index box [min, max + 1] (GridStats.h: the
    // inclusive max offset by one). A hot grid's edge is where this shows: a box half a voxel lower adds a cool,
    // absorbing skin of fading temperature in front of the fire (8 % darker on a 17³ cube against pbrt-v4).
    // Majorant cells then start at the leaves' own corners, so every point of the box lies in a block whose
    // trilinear maximum (its voxels and those one beyond) bounds it.
    min_ = {float(lo[0]), float(lo[1]), float(lo[2])};
    max_ = {float(hi[0]) + 1.0f, float(hi[1]) + 1.0f, float(hi[2]) + 1.0f};
    majorant_min_ = {float(blocks.first_voxel[0]), float(blocks.first_voxel[1]), float(blocks.first_voxel[2])};
  } else {
    // Voxel v spans [v − ½, v + ½] in index space; blocks likewise, so a nearest-voxel lookup stays in its block.
    min_ = {float(lo[0]) - 0.5f, float(lo[1]) - 0.5f, float(lo[2]) - 0.5f};
    max_ = {float(hi[0]) + 0.5f, float(hi[1]) + 0.5f, float(hi[2]) + 0.5f};
    majorant_min_ = {float(blocks.first_voxel[0]) - 0.5f, float(blocks.first_voxel[1]) - 0.5f,
                     float(blocks.first_voxel[2]) - 0.5f};
  }
  mx_ = blocks.count[0], my_ = blocks.count[1], mz_ = blocks.count[2];
  majorant_ = interpolation_ == GridInterpolation::trilinear ? blocks.trilinear_max : blocks.voxel_max;
}

void GridMedium::set_transform(const std::optional<Transform>& world_from_grid) {
  if (world_from_grid) grid_from_world_ = box_from_world(*world_from_grid);
}

float GridMedium::density(Vec3 p) const { return density_in_grid(grid_from_world_ ? grid_from_world_->point(p) : p); }

float GridMedium::density_in_grid(Vec3 p) const {
  if (sparse_) {
    // Clipped at the box as a dense grid is: the trilinear density fades over the outer half voxel.
    if (!(p.x >= min_.x && p.y >= min_.y && p.z >= min_.z && p.x < max_.x && p.y < max_.y && p.z < max_.z))
      return 0.0f;
    return sparse_->density({p.x, p.y, p.z}, interpolation_);
  }
  const Vec3 local = p - min_;
  const Vec3 cells{local.x / voxel_size_.x, local.y / voxel_size_.y, local.z / voxel_size_.z};
  const int x = int(std::floor(cells.x)), y = int(std::floor(cells.y)), z = int(std::floor(cells.z));
  if (x < 0 || y < 0 || z < 0 || x >= nx_ || y >= ny_ || z >= nz_) return 0.0f;
  if (interpolation_ == GridInterpolation::voxel) return density_[size_t((z * ny_ + y) * nx_ + x)];
  // Trilinear between voxel centres (at integer + ½ in voxel units).
  const Vec3 s{cells.x - 0.5f, cells.y - 0.5f, cells.z - 0.5f};
  const int ix = int(std::floor(s.x)), iy = int(std::floor(s.y)), iz = int(std::floor(s.z));
  const float fx = s.x - float(ix), fy = s.y - float(iy), fz = s.z - float(iz);
  const auto lerp = [](float f, float a, float b) { return a + f * (b - a); };
  float d[8];  // the 8 corners, x fastest
  if (ix >= 0 && iy >= 0 && iz >= 0 && ix + 1 < nx_ && iy + 1 < ny_ && iz + 1 < nz_) {
    // All inside (nearly every lookup): direct loads, no bounds test per voxel.
    const size_t sy = size_t(nx_), sz = size_t(nx_) * size_t(ny_);
    const float* p0 = &density_[(size_t(iz) * size_t(ny_) + size_t(iy)) * size_t(nx_) + size_t(ix)];
    d[0] = p0[0], d[1] = p0[1], d[2] = p0[sy], d[3] = p0[sy + 1];
    d[4] = p0[sz], d[5] = p0[sz + 1], d[6] = p0[sz + sy], d[7] = p0[sz + sy + 1];
  } else {
    for (int k = 0; k < 8; ++k) d[k] = voxel(ix + (k & 1), iy + ((k >> 1) & 1), iz + (k >> 2));
  }
  return lerp(fz, lerp(fy, lerp(fx, d[0], d[1]), lerp(fx, d[2], d[3])),
              lerp(fy, lerp(fx, d[4], d[5]), lerp(fx, d[6], d[7])));
}

bool GridMedium::clip(const Ray& ray, float t_max, float& t0, float& t1) const {
  return clip_ray_to_box(ray, t_max, min_, max_, t0, t1);
}

void parse_grid_bytes(std::string_view bytes, const std::string& name, int& nx, int& ny, int& nz,
                      std::vector<float>& densities) {
  constexpr size_t kHeaderBytes = 8 + 3 * sizeof(int32_t);
  if (bytes.size() < kHeaderBytes || std::memcmp(bytes.data(), "RIMUVOL1", 8) != 0)
    throw InputError({name, 0, ""}, "not a RIMUVOL1 voxel grid: expected the 8 bytes \"RIMUVOL1\" and three int32 "
                                    "sizes, then the densities");
  int32_t n[3];
  std::memcpy(n, bytes.data() + 8, sizeof n);
  for (int32_t v : n)
    if (v < 1 || v > 4096)
      throw InputError({name, 0, ""}, "the header's grid sizes are " + std::to_string(n[0]) + " × " +
                                          std::to_string(n[1]) + " × " + std::to_string(n[2]) +
                                          "; each must be 1..4096");
  // The sizes are checked against the bytes present before anything is allocated: a damaged header must not
  // allocate gigabytes for a file of a few bytes.
  const uint64_t count = uint64_t(n[0]) * uint64_t(n[1]) * uint64_t(n[2]);
  const uint64_t expected_bytes = kHeaderBytes + count * sizeof(float);
  if (bytes.size() != expected_bytes)
    throw InputError({name, 0, ""}, "the header announces " + std::to_string(n[0]) + " × " + std::to_string(n[1]) +
                                        " × " + std::to_string(n[2]) + " voxels, which take " +
                                        std::to_string(expected_bytes) + " bytes with the header, but the file has " +
                                        std::to_string(bytes.size()) + " bytes");
  nx = n[0], ny = n[1], nz = n[2];
  densities.resize(size_t(count));
  std::memcpy(densities.data(), bytes.data() + kHeaderBytes, size_t(count) * sizeof(float));
}

void read_grid_file(const std::filesystem::path& path, int& nx, int& ny, int& nz, std::vector<float>& densities) {
  parse_grid_bytes(read_input_file(path, kMaxBinaryFileBytes), path.string(), nx, ny, nz, densities);
}

void write_grid_file(const std::filesystem::path& path, int nx, int ny, int nz, const std::vector<float>& densities) {
  std::ofstream out(path, std::ios::binary);
  const int32_t n[3] = {nx, ny, nz};
  out.write("RIMUVOL1", 8);
  out.write(reinterpret_cast<const char*>(n), sizeof n);
  out.write(reinterpret_cast<const char*>(densities.data()), std::streamsize(densities.size() * sizeof(float)));
}

std::vector<float> procedural_cloud_density(int n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> centre(0.3f, 0.7f), radius(0.12f, 0.25f);
  struct Blob {
    Vec3 c;
    float r;
  };
  std::vector<Blob> blobs;
  for (int i = 0; i < 12; ++i) blobs.push_back({{centre(rng), centre(rng) * 0.8f + 0.05f, centre(rng)}, radius(rng)});
  std::vector<float> d(size_t(n) * size_t(n) * size_t(n));
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const Vec3 p{(float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n), (float(z) + 0.5f) / float(n)};
        float v = 0.0f;
        for (const Blob& b : blobs) {
          const float s = std::clamp(1.0f - length(p - b.c) / b.r, 0.0f, 1.0f);
          v = std::fmax(v, s * s * (3.0f - 2.0f * s));  // smoothstep: soft edges
        }
        d[size_t((z * n + y) * n + x)] = v;
      }
  return d;
}

}  // namespace rimu
