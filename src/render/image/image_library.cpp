#include "render/image/image_library.h"

#include <dlfcn.h>

#include <atomic>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "spectral/error.h"

namespace rimu {
namespace {

std::atomic<bool> module_loaded{false};

constexpr const char* kModuleName = "librimu_oiio.so";

std::vector<std::filesystem::path> candidate_paths() {
  if (const char* env = std::getenv("RIMU_IMAGE_MODULE"); env && *env) return {env};
  std::vector<std::filesystem::path> paths;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back(exe.parent_path() / ".." / "lib" / "rimu" / kModuleName);
  // For a program that is not installed beside it (the Python module runs inside python3).
#ifdef RIMU_IMAGE_MODULE_INSTALL_PATH
  paths.emplace_back(RIMU_IMAGE_MODULE_INSTALL_PATH);
#endif
#ifdef RIMU_IMAGE_MODULE_BUILD_PATH
  paths.emplace_back(RIMU_IMAGE_MODULE_BUILD_PATH);
#endif
  return paths;
}

const ImageModuleApi& load() {
  std::string tried;
  for (const auto& path : candidate_paths()) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) {
      tried += "\n  " + path.string() + ": no such file";
      continue;
    }
    // RTLD_LOCAL: OpenImageIO's symbols stay inside the module, so they cannot clash with anything else loaded.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      tried += "\n  " + path.string() + ": " + dlerror();
      continue;
    }
    using Entry = const ImageModuleApi* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "rimu_image_module_api"));
    const ImageModuleApi* api = entry ? entry() : nullptr;
    if (!api || api->api_version != kImageModuleApiVersion) {
      tried += "\n  " + path.string() + ": not a module of this Rimu build (rebuild or reinstall it)";
      continue;
    }
    module_loaded.store(true);
    return *api;  // the handle stays open for the life of the process
  }
  throw RenderError("cannot load Rimu's OpenImageIO module (needed to read image textures and write PNG, JPEG "
                    "or TIFF); set RIMU_IMAGE_MODULE or reinstall Rimu. Tried:" + tried);
}

}  // namespace

const ImageModuleApi& image_library() {
  static const ImageModuleApi& api = load();
  return api;
}

bool image_library_loaded() { return module_loaded.load(); }

}  // namespace rimu
