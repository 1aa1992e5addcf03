// The version and the git commit Rimu was built from: written into output metadata and printed by every tool's
// --version.
#pragma once

namespace rimu {

/// The project version from CMake (project(Rimu VERSION ...)), e.g. "0.1.0".
const char* rimu_version();

/// The abbreviated git commit of the source tree at configure time (cmake/GitCommit.cmake), or "unknown" when the
/// tree was not a git checkout.
const char* rimu_git_commit();

}  // namespace rimu
