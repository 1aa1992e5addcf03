#include "render/image/loadable_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "spectral/error.h"

namespace rimu {
namespace {

// Where each module was loaded from, by file name.
std::mutex loaded_paths_mutex;
std::map<std::string, std::string> loaded_paths;

std::vector<std::filesystem::path> candidate_paths(const ModuleLocation& module) {
  if (const char* env = std::getenv(module.environment_variable); env && *env) return {env};
  std::vector<std::filesystem::path> paths;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back(exe.parent_path() / ".." / "lib" / "rimu" / module.file_name);
  // For a program that is not installed beside it (the Python module runs inside python3).
  if (*module.install_path) paths.emplace_back(module.install_path);
  if (*module.build_path) paths.emplace_back(module.build_path);
  return paths;
}

}  // namespace

const void* load_module(const ModuleLocation& module, std::atomic<bool>& loaded) {
  std::string tried;
  for (const auto& path : candidate_paths(module)) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      tried += "\n  " + path.string() + ": no such file";
      continue;
    }
    // RTLD_LOCAL: the library's symbols stay inside the module, so they cannot clash with anything else loaded.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      tried += "\n  " + path.string() + ": " + dlerror();
      continue;
    }
    void* entry = dlsym(handle, module.entry_symbol);
    const void* api = entry ? module.call_entry(entry) : nullptr;
    // Every module's function table starts with its int api_version.
    if (!api || *static_cast<const int*>(api) != module.api_version) {
      tried += "\n  " + path.string() + ": not a module of this Rimu build (rebuild or reinstall it)";
      continue;
    }
    {
      const std::lock_guard<std::mutex> lock(loaded_paths_mutex);
      loaded_paths[module.file_name] = path.lexically_normal().string();
    }
    loaded.store(true);
    return api;  // the handle stays open for the life of the process
  }
  throw RenderError(std::string("cannot load Rimu's ") + module.purpose + "; set " + module.environment_variable +
                    " or reinstall Rimu. Tried:" + tried);
}

std::vector<std::pair<std::string, std::string>> loaded_modules() {
  const std::lock_guard<std::mutex> lock(loaded_paths_mutex);
  return {loaded_paths.begin(), loaded_paths.end()};
}

}  // namespace rimu
