#include "spectral/version.h"

// Both come from the build (src/spectral/CMakeLists.txt); the fallbacks keep a stray compile honest.
#ifndef RIMU_VERSION
#define RIMU_VERSION "unknown"
#endif
#ifndef RIMU_GIT_COMMIT
#define RIMU_GIT_COMMIT "unknown"
#endif

namespace rimu {

const char* rimu_version() { return RIMU_VERSION; }

const char* rimu_git_commit() { return RIMU_GIT_COMMIT; }

}  // namespace rimu
