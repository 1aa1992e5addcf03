#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include "test_support.h"

namespace rimu::test {

SpectralLibrary& library() {
  static SpectralLibrary instance = SpectralLibrary::at_default_location();
  return instance;
}

}  // namespace rimu::test
