// A heterogeneous medium on a voxel grid: density d(x) times spectral coefficients per unit density, with a coarse
// majorant grid for null-collision tracking.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "transport/media/homogeneous_medium.h"
#include "transport/geometry/ray.h"
#include "transport/geometry/transform.h"

namespace rimu {

class NanoVdbGrid;

/// How densities between voxel centres are found.
enum class GridInterpolation {
  voxel,      ///< piecewise constant: the voxel containing x
  trilinear,  ///< trilinear between the 8 nearest voxel centres, voxels outside the grid counting 0 (pbrt-v4's
              ///< SampledGrid: the density fades to 0 over the outer half voxel)
};

/// Densities on an nx × ny × nz grid filling the axis-aligned box [bounds_min, bounds_max] of the grid's own space
/// (m), placed in the world by `world_from_grid` (any invertible affine map; identity: the box is in world space).
///
/// σ_a(x, λ) = d(x)·σ_a(λ), σ_s(x, λ) = d(x)·σ_s(λ); d = 0 outside the box. Majorants are maxima per block of
/// voxels: exact maxima for voxel lookup; for trilinear lookup the maxima over the block's voxels and their
/// neighbours one voxel beyond (a trilinear value is a convex combination of those), so no interpolated value
/// exceeds its block's majorant.
///
/// File format (.rvol, "Rimu volume", little-endian; written by write_grid_file and by tools, read at load):
///     8 bytes  magic "RIMUVOL1"
///     3 × int32 nx, ny, nz (each 1..4096)
///     nx·ny·nz × float32 densities, x fastest, then y, then z; finite and ≥ 0.
/// The box and the spectra come from the scene file, so one density file can be reused at any size.
///
/// The densities may instead be a sparse NanoVDB grid (nanovdb_grid.h): the grid's space is then the file's index
/// space (voxel centres at integers), the box is the active voxels' box — with trilinear lookups NanoVDB's own
/// [min, max + 1] (its world box, which pbrt-v4 clips to), with voxel lookups half a voxel beyond the outer centres
/// as for a dense grid — and the majorant blocks are NanoVDB's leaves, computed from the tree at load.
class GridMedium {
 public:
  /// Throws InputError if a size is 0, the data size is not nx·ny·nz, a density is negative or not finite,
  /// or the box is empty.
  GridMedium(int nx, int ny, int nz, std::vector<float> densities, Vec3 bounds_min, Vec3 bounds_max,
             SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m, float g,
             GridInterpolation interpolation = GridInterpolation::voxel,
             const std::optional<Transform>& world_from_grid = std::nullopt);
  /// Densities from a NanoVDB grid, placed in the world by `world_from_medium` after the file's own
  /// index-to-world map. Throws InputError if the combined map is not invertible.
  GridMedium(std::shared_ptr<const NanoVdbGrid> sparse, SpectrumPtr sigma_a_per_m, SpectrumPtr sigma_s_per_m, float g,
             GridInterpolation interpolation, const std::optional<Transform>& world_from_medium = std::nullopt);

  /// The density at a world point (0 outside the box).
  float density(Vec3 p) const;
  GridInterpolation interpolation() const { return interpolation_; }
  /// σ_a, σ_s at a world point, given the per-unit-density coefficients at the path's wavelengths.
  MediumCoefficients coefficients(Vec3 p, const MediumCoefficients& per_unit_density) const {
    return coefficients_in_grid(grid_from_world_ ? grid_from_world_->point(p) : p, per_unit_density);
  }
  /// The same at a point of the grid's own space (for_each_majorant_segment's grid-space ray).
  MediumCoefficients coefficients_in_grid(Vec3 p_grid, const MediumCoefficients& per_unit_density) const {
    const float d = density_in_grid(p_grid);
    return {per_unit_density.sigma_a_per_m * Float4(d), per_unit_density.sigma_s_per_m * Float4(d)};
  }
  /// The coefficients per unit density at the path's wavelengths.
  MediumCoefficients unit_coefficients(const SampledWavelengths& lambda) const { return unit_.coefficients(lambda); }
  const HenyeyGreenstein& phase() const { return unit_.phase(); }
  /// σ_a and σ_s per unit density (1/m).
  const SpectrumPtr& sigma_a() const { return unit_.sigma_a(); }
  const SpectrumPtr& sigma_s() const { return unit_.sigma_s(); }

  /// Calls segment(t0, t1, max_density, grid_ray) for consecutive pieces of the ray inside the box over
  /// [ray.t_min, t_max], in order, each with the largest density of the majorant cell it crosses (a 3D-DDA over the
  /// majorant grid, Amanatides & Woo 1987); grid_ray is the ray in the grid's space, with the same parameter t.
  /// Stops early when segment returns false.
  template <typename F>
  void for_each_majorant_segment(const Ray& ray, float t_max, F&& segment) const;

  /// Majorant cells are blocks of B³ voxels. A NanoVDB grid's are its 8³ leaves (kSparseBlock). A dense grid's side
  /// B is 4, 8 or 16, whichever makes tracking cheapest by an estimate made at load (choose_majorants in
  /// grid_medium.cpp): small blocks give tight majorants (fewer null collisions, each a density lookup), large ones
  /// fewer cells for the DDA to cross; a dense cloud wants the first, a thin fog the second.
  static constexpr int kSparseBlock = 8;
  /// B, the majorant blocks' side in voxels.
  int majorant_block() const { return block_; }

  /// The density at a point of the grid's space.
  float density_in_grid(Vec3 p) const;

 private:
  void set_transform(const std::optional<Transform>& world_from_grid);
  /// A dense grid's majorant blocks: block_, mx_..mz_ and majorant_ (see majorant_block).
  void choose_majorants(const std::optional<Transform>& world_from_grid);
  bool clip(const Ray& ray, float t_max, float& t0, float& t1) const;
  float voxel(int x, int y, int z) const {
    return x < 0 || y < 0 || z < 0 || x >= nx_ || y >= ny_ || z >= nz_ ? 0.0f : density_[size_t((z * ny_ + y) * nx_ + x)];
  }
  int nx_, ny_, nz_;
  std::vector<float> density_;                // empty when sparse_ holds the densities
  std::shared_ptr<const NanoVdbGrid> sparse_;  // shared: copies of a Medium share one tree
  Vec3 min_, max_, voxel_size_;
  Vec3 majorant_min_;                 // the majorant grid's corner: min_, or NanoVDB's leaf-aligned corner
  int mx_, my_, mz_;                  // majorant grid size
  int block_ = kSparseBlock;          // majorant block side in voxels
  std::vector<float> majorant_;       // max density per block
  HomogeneousMedium unit_;
  GridInterpolation interpolation_;
  std::optional<Transform> grid_from_world_;  // empty: the grid's space is the world
};

/// Parses the bytes of an .rvol file (format above) into nx, ny, nz and densities. Throws InputError naming `name`
/// if the magic is wrong, a size is outside 1..4096, or the byte count is not exactly the header's (checked before
/// the densities are allocated).
void parse_grid_bytes(std::string_view bytes, const std::string& name, int& nx, int& ny, int& nz,
                      std::vector<float>& densities);
/// parse_grid_bytes on a file read by read_input_file (a regular file of at most kMaxBinaryFileBytes).
void read_grid_file(const std::filesystem::path& path, int& nx, int& ny, int& nz, std::vector<float>& densities);
/// Writes an .rvol file.
void write_grid_file(const std::filesystem::path& path, int nx, int ny, int nz, const std::vector<float>& densities);

/// A procedural cloud density on an n³ grid: a union of soft spheres (smoothstep falloff) whose centres and radii
/// follow a fixed seed, peaked at 1. For demos, tests and the benchmark.
std::vector<float> procedural_cloud_density(int n, uint32_t seed);

// ---- implementation of the template ----

template <typename F>
void GridMedium::for_each_majorant_segment(const Ray& world_ray, float t_max, F&& segment) const {
  // An affine map keeps the ray's parameter: the grid-space ray (direction not unit) has the same t everywhere.
  Ray ray = world_ray;
  if (grid_from_world_) {
    ray.origin = grid_from_world_->point(world_ray.origin);
    ray.direction = grid_from_world_->vector(world_ray.direction);
  }
  float t0, t1;
  if (!clip(ray, t_max, t0, t1)) return;
  // The DDA walks majorant cells; positions are in cell units.
  const Vec3 cell_size{voxel_size_.x * float(block_), voxel_size_.y * float(block_), voxel_size_.z * float(block_)};
  const int size[3] = {mx_, my_, mz_};
  const Vec3 entry = ray.origin + ray.direction * t0;
  int cell[3], step[3];
  float t_next[3], t_delta[3];
  for (int a = 0; a < 3; ++a) {
    const float local = (entry[a] - majorant_min_[a]) / cell_size[a];
    cell[a] = std::clamp(int(local), 0, size[a] - 1);
    const float d = ray.direction[a];
    if (d > 0.0f) {
      step[a] = 1;
      t_next[a] = t0 + ((float(cell[a] + 1)) * cell_size[a] + majorant_min_[a] - entry[a]) / d;
      t_delta[a] = cell_size[a] / d;
    } else if (d < 0.0f) {
      step[a] = -1;
      t_next[a] = t0 + (float(cell[a]) * cell_size[a] + majorant_min_[a] - entry[a]) / d;
      t_delta[a] = -cell_size[a] / d;
    } else {
      step[a] = 0;
      t_next[a] = INFINITY;
      t_delta[a] = INFINITY;
    }
  }
  float t = t0;
  while (t < t1) {
    const int axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2) : (t_next[1] < t_next[2] ? 1 : 2);
    const float t_exit = std::fmin(t_next[axis], t1);
    const float m = majorant_[size_t((cell[2] * my_ + cell[1]) * mx_ + cell[0])];
    if (t_exit > t && !segment(t, t_exit, m, static_cast<const Ray&>(ray))) return;
    t = t_exit;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= size[axis]) return;
    t_next[axis] += t_delta[axis];
  }
}

}  // namespace rimu
