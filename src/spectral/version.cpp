#include "spectral/version.h"

// RIMU_VERSION and RIMU_GIT_COMMIT, written by the build (src/spectral/CMakeLists.txt).
#include "rimu_build_info.h"

namespace rimu {

const char* rimu_version() { return RIMU_VERSION; }

const char* rimu_git_commit() { return RIMU_GIT_COMMIT; }

}  // namespace rimu
