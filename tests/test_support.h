// Shared helpers for Rimu's tests.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "spectral/library/spectral_library.h"
#include "spectral/math_constants.h"
#include "spectral/wavelengths/sampled_wavelengths.h"

namespace rimu::test {

/// π (files take it with `using rimu::test::kPi;`): the libraries' one definition, so that no unity batch of the
/// suite sees two.
using rimu::kPi;

/// Four wavelengths over the visible, 450 nm the hero, each with the pdf of uniform sampling over 360-830 nm: the
/// lanes the light, material and texture tests evaluate spectra at (files take it with `using rimu::test::kLambda;`).
inline const SampledWavelengths kLambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f / 470.0f));

/// The project's data folder, found the way the binaries find it (RIMU_DATA, then beside the executable).
SpectralLibrary& library();

/// tests/data, for test-only tables (e.g. the Sharma 2005 CIEDE2000 pairs).
std::filesystem::path test_data(const std::string& name);

/// A folder of its own per test case (CTest runs test cases as parallel processes, so the name carries the pid and a
/// counter): <temp>/rimu_<name>_<pid>_<n>, created empty and removed with its contents afterwards.
struct ScratchFolder {
  std::filesystem::path path;
  explicit ScratchFolder(const std::string& name) {
    static int counter = 0;
    path = std::filesystem::temp_directory_path() /
           ("rimu_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  std::filesystem::path operator/(const std::string& file) const { return path / file; }
  /// Writes `bytes` to the file `name` in the folder and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& bytes) const {
    const std::filesystem::path file = path / name;
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
  }
};

}  // namespace rimu::test
