#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include "test_support.h"

namespace rimu::test {

SpectralLibrary& library() {
  static SpectralLibrary instance = SpectralLibrary::at_default_location();
  return instance;
}

std::filesystem::path test_data(const std::string& name) { return std::filesystem::path(RIMU_TEST_DATA_DIR) / name; }

}  // namespace rimu::test
