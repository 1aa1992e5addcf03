// libFuzzer target: the voxel-grid (.rvol) reader and the grid medium built from what it accepts.
#include "fuzz_support.h"
#include "spectral/spectra/spectrum.h"
#include "transport/media/grid_medium.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return rimu::fuzz::run_reader("fuzz_rvol", [&] {
    // The bytes go straight to the parser read_grid_file uses (it checks the header against the size first).
    int nx = 0, ny = 0, nz = 0;
    std::vector<float> density;
    rimu::parse_grid_bytes(rimu::fuzz::as_text(data, size), "fuzz.rvol", nx, ny, nz, density);
    // What the scene loader does next: the medium validates the densities and builds its majorant grid.
    const auto unit = std::make_shared<rimu::ConstantSpectrum>(1.0);
    const rimu::GridMedium medium(nx, ny, nz, std::move(density), {0, 0, 0}, {1, 1, 1}, unit, unit, 0.0f);
    (void)medium.density({0.5f, 0.5f, 0.5f});
  });
}
