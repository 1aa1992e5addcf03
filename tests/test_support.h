// Shared helpers for Rimu's tests.
#pragma once

#include <filesystem>

#include "spectral/spectral_library.h"

namespace rimu::test {

/// The project's data folder, found the way the binaries find it (RIMU_DATA, then beside the executable).
SpectralLibrary& library();

/// tests/data, for test-only tables (e.g. the Sharma 2005 CIEDE2000 pairs).
inline std::filesystem::path test_data(const std::string& name) { return std::filesystem::path(RIMU_TEST_DATA_DIR) / name; }

}  // namespace rimu::test
