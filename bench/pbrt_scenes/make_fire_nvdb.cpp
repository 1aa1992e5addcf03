// Writes the NanoVDB file of bench/pbrt_scenes/fire_nanovdb.pbrt: a ball of radius 8 voxels (voxel 0.1 m, index
// 0..16 on each axis, world [-0.8, 0.8]) with a "density" grid of 1 and a "temperature" grid of 1500 K at the rim
// rising linearly to 2000 K at the centre. Uses only NanoVDB's headers (Debian's libnanovdb-dev, as Rimu does).
//   g++ -std=c++17 -O1 bench/pbrt_scenes/make_fire_nvdb.cpp -o /tmp/make_fire_nvdb && /tmp/make_fire_nvdb OUT.nvdb
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>

#include <cmath>
#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.nvdb\n", argv[0]);
    return 1;
  }
  std::vector<nanovdb::GridHandle<>> grids;
  for (const bool temperature : {false, true}) {
    nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
    auto voxels = builder.getAccessor();
    for (int z = -8; z <= 8; ++z)
      for (int y = -8; y <= 8; ++y)
        for (int x = -8; x <= 8; ++x) {
          const double r = std::sqrt(double(x * x + y * y + z * z));
          if (r > 8) continue;
          voxels.setValue(nanovdb::Coord(x + 8, y + 8, z + 8), temperature ? float(1500 + 500 * (1 - r / 8)) : 1.0f);
        }
    grids.push_back(builder.getHandle<>(0.1, nanovdb::Vec3d(-0.8), temperature ? "temperature" : "density"));
  }
  nanovdb::io::writeGrids(argv[1], grids);
  return 0;
}
