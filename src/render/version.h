// The version string Rimu writes into its outputs.
#pragma once

namespace rimu {

/// The project version from CMake (project(Rimu VERSION ...)), e.g. "0.1.0".
const char* rimu_version();

}  // namespace rimu
