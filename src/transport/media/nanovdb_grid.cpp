#include "transport/media/nanovdb_grid.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>  // GridValidator.h uses std::cerr without including it
#include <stdexcept>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include "spectral/error.h"
#include "spectral/io/input_file.h"
#include "transport/media/nanovdb_io.h"

namespace rimu {

struct NanoVdbGrid::Handle {
  nanovdb::GridHandle<nanovdb::HostBuffer> grid;
};

namespace {

std::string version_string(uint32_t packed) {
  // nanovdb::Version packs major << 21 | minor << 10 | patch.
  return std::to_string(packed >> 21) + "." + std::to_string((packed >> 10) & 2047u) + "." +
         std::to_string(packed & 1023u);
}

// NanoVDB's reader answers a wrong file with a std::runtime_error whose text is meant for a developer; the
// header's magic number and version are read here first so that the two common cases get a plain message.
void check_header(const std::filesystem::path& path, const std::string& name) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw InputError({name, 0, ""}, "no such file");
  std::ifstream in(path, std::ios::binary);
  unsigned char header[12] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  const char* expected = "NanoVDB";
  if (!in || std::memcmp(header, expected, 7) != 0)
    throw InputError({name, 0, ""}, "not a NanoVDB file: expected the magic number \"NanoVDB\" in its first bytes");
  uint32_t packed = 0;
  std::memcpy(&packed, header + 8, 4);
  // Later NanoVDB releases changed the magic's last character ('0' → '1', '2') together with the layout; either
  // way the file's version says why it cannot be read.
  if (header[7] != '0' || (packed >> 21) != NANOVDB_MAJOR_VERSION_NUMBER)
    throw InputError({name, 0, ""}, "written by NanoVDB " + version_string(packed) + " (magic \"NanoVDB" +
                                        char(header[7]) + "\"); this build reads NanoVDB " +
                                        std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) +
                                        ".x files (magic \"NanoVDB0\"): convert the file with that version's "
                                        "nanovdb_convert, or build Rimu against a matching libnanovdb-dev");
}

std::string grid_names(const std::filesystem::path& path) {
  std::string names;
  for (const nanovdb::io::GridMetaData& m : nanovdb::io::readGridMetaData(path.string()))
    names += (names.empty() ? "\"" : ", \"") + m.gridName + "\" (" + nanovdb::toStr(m.gridType) + ")";
  return names.empty() ? "no grid" : names;
}

// NanoVDB allocates the size a grid's metadata states before reading it: a damaged header must not allocate
// gigabytes for a small file. An uncompressed grid is stored as is, so its size cannot exceed the file's; a
// compressed one may (deflate expands up to 1032:1), up to the limit of every binary input.
void check_grid_size(const std::filesystem::path& path, const std::string& name, const std::string& grid_name) {
  const uint64_t file_bytes = std::filesystem::file_size(path);
  for (const nanovdb::io::GridMetaData& m : nanovdb::io::readGridMetaData(path.string())) {
    if (m.gridName != grid_name) continue;
    const uint64_t limit = m.codec == nanovdb::io::Codec::NONE ? file_bytes : uint64_t(kMaxBinaryFileBytes);
    if (m.gridSize > limit)
      throw InputError({name, 0, ""}, "grid \"" + grid_name + "\" claims " + std::to_string(m.gridSize) +
                                          " bytes, more than " +
                                          (m.codec == nanovdb::io::Codec::NONE ? "the file holds (" : "the limit (") +
                                          std::to_string(limit) + " bytes): the file is damaged");
    return;
  }
}

// Whether the tree's node arrays lie inside the grid's buffer, checked before anything follows their offsets (NanoVDB's
// own validator reads the root through them first). Offsets inside the nodes (children, tiles) are not checked.
bool layout_inside(const nanovdb::FloatGrid& grid, uint64_t buffer_bytes) {
  using Tree = nanovdb::FloatTree;
  const auto* base = reinterpret_cast<const uint8_t*>(&grid);
  const auto inside = [&](uint64_t offset, uint64_t bytes) {
    return offset <= buffer_bytes && bytes <= buffer_bytes - offset;
  };
  const uint64_t tree_at = uint64_t(reinterpret_cast<const uint8_t*>(&grid.tree()) - base);
  if (grid.gridSize() > buffer_bytes || !inside(tree_at, sizeof(Tree::DataType))) return false;
  const Tree::DataType& tree = *grid.tree().data();
  const uint64_t root_at = tree_at + tree.mNodeOffset[3];
  if (tree.mNodeOffset[3] > buffer_bytes || !inside(root_at, sizeof(Tree::RootType::DataType))) return false;
  const auto* root = reinterpret_cast<const Tree::RootType*>(base + root_at);
  if (!inside(root_at, Tree::RootType::memUsage(root->tileCount()))) return false;
  const uint64_t node_bytes[3] = {sizeof(Tree::LeafNodeType), sizeof(Tree::Node1), sizeof(Tree::Node2)};
  for (int level = 0; level < 3; ++level)
    if (tree.mNodeCount[level] > 0 && (tree.mNodeOffset[level] > buffer_bytes ||
                                       !inside(tree_at + tree.mNodeOffset[level], tree.mNodeCount[level] * node_bytes[level])))
      return false;
  return true;
}

int floor_div8(int v) { return v >= 0 ? v / 8 : -((7 - v) / 8); }

}  // namespace

NanoVdbGrid::~NanoVdbGrid() = default;

bool NanoVdbGrid::has_grid(const std::filesystem::path& path, const std::string& grid_name) {
  try {
    return nanovdb::io::hasGrid(path.string(), grid_name);
  } catch (const std::exception&) {
    return false;
  }
}

std::shared_ptr<const NanoVdbGrid> NanoVdbGrid::load(const std::filesystem::path& path, const std::string& grid_name) {
  const std::string name = path.string();
  check_header(path, name);
  std::shared_ptr<NanoVdbGrid> result(new NanoVdbGrid());
  result->handle_ = std::make_unique<Handle>();
  try {
    check_grid_size(path, name, grid_name);
    result->handle_->grid = nanovdb::io::readGrid<nanovdb::HostBuffer>(name, grid_name);
    if (!result->handle_->grid)
      throw InputError({name, 0, ""}, "no grid named \"" + grid_name + "\"; the file holds " + grid_names(path));
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const InputError*>(&e)) throw;
    // A damaged or truncated file, or a codec this build lacks.
    throw InputError({name, 0, ""}, std::string("NanoVDB could not read grid \"") + grid_name + "\": " + e.what());
  }
  const nanovdb::FloatGrid* grid = result->handle_->grid.grid<float>();
  if (!grid)
    throw InputError({name, 0, ""}, "grid \"" + grid_name + "\" holds " +
                                        nanovdb::toStr(result->handle_->grid.gridMetaData()->gridType()) +
                                        " values; a density grid must hold float values");
  if (!layout_inside(*grid, result->handle_->grid.size()))
    throw InputError({name, 0, ""}, "grid \"" + grid_name + "\" is damaged: its tree's nodes lie outside its data");
  // Lookups follow the tree's node offsets unchecked, so damage should be refused here. NanoVDB's quick check
  // verifies the headers and the checksum of the grid, tree and root data, where the offsets to the node arrays
  // are; its detailed check would follow the offsets inside the nodes, which nothing has bounded, so damage inside
  // the nodes is not caught.
  if (const std::string damage = nanovdb::GridValidator<float>::check(*grid, false); !damage.empty())
    throw InputError({name, 0, ""}, "grid \"" + grid_name + "\" is damaged: " + damage);
  result->grid_ = grid;
  result->active_voxels_ = grid->activeVoxelCount();
  if (result->active_voxels_ == 0)
    throw InputError({name, 0, ""}, "grid \"" + grid_name + "\" has no active voxel");
  const nanovdb::CoordBBox box = grid->indexBBox();
  const nanovdb::Map& map = grid->map();
  std::array<float, 12> rows{};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rows[size_t(r * 4 + c)] = float(map.mMatD[r * 3 + c]);
    rows[size_t(r * 4 + 3)] = float(map.mVecD[r]);
  }
  bool invertible = false;
  result->world_from_index_ = Transform::from_rows(rows, invertible);
  if (!invertible || !result->world_from_index_.is_finite())
    throw InputError({name, 0, ""}, "grid \"" + grid_name + "\" has a singular or non-finite index-to-world map");

  // Majorants. Every aligned 8³ block in the active box, and the ring of blocks around it (whose voxels a
  // trilinear lookup inside the box can still read), is visited once: a leaf's 512 values are scanned, inactive
  // ones included (the sampler reads them too); a block without a leaf lies inside one tile (or the background),
  // whose single value is read. A voxel at x is read by trilinear lookups in the blocks of x − 1 … x + 1, so a
  // voxel on a block's face also raises the neighbouring block's majorant (the one-voxel dilation of GridMedium).
  Blocks& blocks = result->blocks_;
  std::array<int, 3> first_block{};
  for (int a = 0; a < 3; ++a) {
    result->index_min_[size_t(a)] = box.min()[a];
    result->index_max_[size_t(a)] = box.max()[a];
    first_block[size_t(a)] = floor_div8(box.min()[a]);
    blocks.first_voxel[size_t(a)] = first_block[size_t(a)] * 8;
    blocks.count[size_t(a)] = floor_div8(box.max()[a]) - first_block[size_t(a)] + 1;
  }
  const size_t block_count = size_t(blocks.count[0]) * size_t(blocks.count[1]) * size_t(blocks.count[2]);
  blocks.voxel_max.assign(block_count, 0.0f);
  blocks.trilinear_max.assign(block_count, 0.0f);
  const auto inside = [&](int b, int a) { return b >= 0 && b < blocks.count[size_t(a)]; };
  const auto at = [&](int x, int y, int z) { return size_t((z * blocks.count[1] + y) * blocks.count[0] + x); };
  const auto refuse = [&](nanovdb::Coord ijk, float v) {
    throw InputError({name, 0, ""}, "grid \"" + grid_name + "\" holds the value " + std::to_string(v) +
                                        " at voxel (" + std::to_string(ijk[0]) + ", " + std::to_string(ijk[1]) +
                                        ", " + std::to_string(ijk[2]) + "); densities must be finite");
  };
  auto accessor = grid->getAccessor();
  for (int bz = -1; bz <= blocks.count[2]; ++bz)
    for (int by = -1; by <= blocks.count[1]; ++by)
      for (int bx = -1; bx <= blocks.count[0]; ++bx) {
        const nanovdb::Coord origin(blocks.first_voxel[0] + 8 * bx, blocks.first_voxel[1] + 8 * by,
                                    blocks.first_voxel[2] + 8 * bz);
        // near[k]: the largest value this block lends to its neighbour at offset k (−1, 0, +1 per axis).
        float near[27] = {};
        float own = 0.0f;
        if (const auto* leaf = accessor.probeLeaf(origin)) {
          for (int z = 0; z < 8; ++z)
            for (int y = 0; y < 8; ++y)
              for (int x = 0; x < 8; ++x) {
                const nanovdb::Coord ijk = origin.offsetBy(x, y, z);
                const float raw = leaf->getValue(ijk);
                if (!std::isfinite(raw)) refuse(ijk, raw);
                const float v = std::fmax(raw, 0.0f);
                if (v == 0.0f) continue;
                own = std::fmax(own, v);
                for (int oz = z == 0 ? -1 : 0; oz <= (z == 7 ? 1 : 0); ++oz)
                  for (int oy = y == 0 ? -1 : 0; oy <= (y == 7 ? 1 : 0); ++oy)
                    for (int ox = x == 0 ? -1 : 0; ox <= (x == 7 ? 1 : 0); ++ox) {
                      float& n = near[(oz + 1) * 9 + (oy + 1) * 3 + ox + 1];
                      n = std::fmax(n, v);
                    }
              }
        } else {
          const float raw = accessor.getValue(origin);
          if (!std::isfinite(raw)) refuse(origin, raw);
          own = std::fmax(raw, 0.0f);
          for (float& n : near) n = own;
        }
        if (own == 0.0f) continue;
        if (inside(bx, 0) && inside(by, 1) && inside(bz, 2)) blocks.voxel_max[at(bx, by, bz)] = own;
        for (int oz = -1; oz <= 1; ++oz)
          for (int oy = -1; oy <= 1; ++oy)
            for (int ox = -1; ox <= 1; ++ox) {
              if (!inside(bx + ox, 0) || !inside(by + oy, 1) || !inside(bz + oz, 2)) continue;
              float& m = blocks.trilinear_max[at(bx + ox, by + oy, bz + oz)];
              m = std::fmax(m, near[(oz + 1) * 9 + (oy + 1) * 3 + ox + 1]);
            }
      }
  return result;
}

float NanoVdbGrid::density(std::array<float, 3> p, GridInterpolation interpolation) const {
  const auto* grid = static_cast<const nanovdb::FloatGrid*>(grid_);
  // An accessor caches the path to the last node it visited; one per lookup keeps lookups thread-safe.
  const auto accessor = grid->getAccessor();
  float v;
  if (interpolation == GridInterpolation::trilinear) {
    v = nanovdb::SampleFromVoxels<decltype(accessor), 1, false>(accessor)(nanovdb::Vec3f(p[0], p[1], p[2]));
  } else {
    // Voxel centres are at integer coordinates: the nearest one is the rounded point.
    v = accessor.getValue(nanovdb::Coord(int(std::floor(p[0] + 0.5f)), int(std::floor(p[1] + 0.5f)),
                                         int(std::floor(p[2] + 0.5f))));
  }
  return std::fmax(v, 0.0f);
}

uint64_t NanoVdbGrid::memory_bytes() const {
  return handle_->grid.size() + (blocks_.voxel_max.size() + blocks_.trilinear_max.size()) * sizeof(float);
}

}  // namespace rimu
