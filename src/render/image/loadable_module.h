// Rimu's optional libraries live in modules of their own (lib/rimu/librimu_*.so), loaded on first use, so that a
// process that does not need one never pays for loading it: OpenImageIO (~250 libraries, ~120 MiB of resident
// memory and ~0.25 s of CPU), FreeImage for PFM and HDR images (~3 MiB) and OpenColorIO for display images (~3 MiB
// and the relocation of its libraries; render/output/display_transform.h). Each module exports one function returning
// its table of functions, whose first member is the table's int version.
#pragma once

#include <atomic>
#include <string>
#include <utility>
#include <vector>

namespace rimu {

/// Where one module is looked for, in order: `environment_variable` if set (then only there: a wrong one is an
/// error); `<exe>/../lib/rimu/<file_name>` (the build tree and an installed tree); the install prefix's and then the
/// build tree's path recorded at compile time ("" if none; for the Python module, whose executable is python3).
struct ModuleLocation {
  const char* file_name;
  const char* environment_variable;
  const char* install_path;
  const char* build_path;
  const char* purpose;       ///< the error message's words: "OpenImageIO module (needed to …)"
  const char* entry_symbol;  ///< the extern "C" function returning the table
  int api_version;           ///< the table's first member must equal it, or the module is refused as stale
  /// Calls the entry function found at `symbol` through its own type (call_module_entry<Api>): calling it through
  /// another function pointer type is undefined (clang's -fsanitize=function stops there).
  const void* (*call_entry)(void* symbol);
};

/// ModuleLocation::call_entry for a module whose entry function returns `const Api*`.
template <typename Api>
const void* call_module_entry(void* symbol) {
  return reinterpret_cast<const Api* (*)()>(symbol)();
}

/// Loads the module (RTLD_LOCAL: its libraries' symbols stay inside it) and returns what its entry function
/// returns; sets `loaded`. Not thread-safe by itself: callers load once, in a function-local static. Throws
/// RenderError (exit 2: the installation, not the user's input) naming the places tried and dlopen's message.
const void* load_module(const ModuleLocation& module, std::atomic<bool>& loaded);

/// The modules loaded so far in this process: each one's file name and the path it was loaded from.
std::vector<std::pair<std::string, std::string>> loaded_modules();

}  // namespace rimu
