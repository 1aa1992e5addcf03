#include "render/version.h"

#ifndef RIMU_VERSION
#define RIMU_VERSION "unknown"
#endif

namespace rimu {

const char* rimu_version() { return RIMU_VERSION; }

}  // namespace rimu
