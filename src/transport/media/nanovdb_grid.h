// A sparse density grid read from a NanoVDB file (.nvdb): the file's tree stays the lookup structure, so a cloud
// hundreds of voxels on a side costs what its leaves cost, never a dense array.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "transport/geometry/transform.h"
#include "transport/media/grid_medium.h"

namespace rimu {

/// One float grid of a .nvdb file, in its index space (voxel centres at integer coordinates). NanoVDB's headers
/// stay in the .cpp: only the file that reads and samples the tree compiles them.
class NanoVdbGrid {
 public:
  /// Reads the float grid `grid_name` from the .nvdb file at `path` (uncompressed, ZIP or BLOSC). Throws InputError
  /// naming the file if it is missing, is not a NanoVDB file, was written by another major version of NanoVDB than
  /// this build reads, has no grid of that name or no active voxel, holds a grid that is not float, or holds a
  /// value that is not finite (the first one's voxel is named), or if the grid's stated size exceeds the file's
  /// (uncompressed) or 16 GiB (checked before NanoVDB allocates it), or fails NanoVDB's quick validation (headers
  /// and the checksum of the grid, tree and root data; not the nodes). Negative values are allowed; lookups clamp
  /// at 0.
  static std::shared_ptr<const NanoVdbGrid> load(const std::filesystem::path& path, const std::string& grid_name);
  /// True if the .nvdb file at `path` names a grid `grid_name` (its headers only; false for a file NanoVDB cannot
  /// read, which load() then reports).
  static bool has_grid(const std::filesystem::path& path, const std::string& grid_name);
  ~NanoVdbGrid();
  NanoVdbGrid(const NanoVdbGrid&) = delete;
  NanoVdbGrid& operator=(const NanoVdbGrid&) = delete;

  /// The active voxels' bounding box in index space, both corners inclusive.
  const std::array<int, 3>& index_min() const { return index_min_; }
  const std::array<int, 3>& index_max() const { return index_max_; }
  /// The file's index-to-world map (an affine map; NanoVDB stores no other kind in a float grid).
  const Transform& world_from_index() const { return world_from_index_; }

  /// max(0, value) at an index-space point: the voxel whose centre is nearest, or trilinear between the 8 nearest
  /// voxel centres (NanoVDB's SampleFromVoxels, order 1, as pbrt-v4's NanoVDBMedium). Voxels the file leaves out
  /// read as the grid's background. Costs one tree descent per lookup (a fresh ReadAccessor: thread-safe).
  float density(std::array<float, 3> index_point, GridInterpolation interpolation) const;

  /// Majorants on blocks of 8³ voxels aligned with NanoVDB's leaves: block (bx, by, bz) holds voxels
  /// first_voxel + 8·(bx, by, bz) + [0, 8)³ and the blocks cover the active box.
  struct Blocks {
    std::array<int, 3> first_voxel{}, count{};
    std::vector<float> voxel_max;      ///< max(0, values) of the block's voxels: bounds voxel lookups
    std::vector<float> trilinear_max;  ///< also over the voxels one beyond the block: bounds trilinear lookups
  };
  const Blocks& blocks() const { return blocks_; }

  /// Bytes held: the grid's buffer as NanoVDB lays it out, plus the majorant blocks.
  uint64_t memory_bytes() const;
  uint64_t active_voxel_count() const { return active_voxels_; }

 private:
  struct Handle;  // NanoVDB's GridHandle
  NanoVdbGrid() = default;
  std::unique_ptr<Handle> handle_;
  const void* grid_ = nullptr;  // the nanovdb::FloatGrid inside handle_
  std::array<int, 3> index_min_{}, index_max_{};
  Transform world_from_index_;
  Blocks blocks_;
  uint64_t active_voxels_ = 0;
};

}  // namespace rimu
