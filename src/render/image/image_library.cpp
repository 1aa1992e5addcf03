#include "render/image/image_library.h"

#include <atomic>
#include <cctype>
#include <fstream>

#include "render/image/image_module/radiance_header.h"
#include "render/image/loadable_module.h"

namespace rimu {
namespace {

#ifndef RIMU_IMAGE_MODULE_INSTALL_PATH
#define RIMU_IMAGE_MODULE_INSTALL_PATH ""
#endif
#ifndef RIMU_IMAGE_MODULE_BUILD_PATH
#define RIMU_IMAGE_MODULE_BUILD_PATH ""
#endif
#ifndef RIMU_FREEIMAGE_MODULE_INSTALL_PATH
#define RIMU_FREEIMAGE_MODULE_INSTALL_PATH ""
#endif
#ifndef RIMU_FREEIMAGE_MODULE_BUILD_PATH
#define RIMU_FREEIMAGE_MODULE_BUILD_PATH ""
#endif

constexpr ModuleLocation kOpenImageIO{
    "librimu_oiio.so", "RIMU_IMAGE_MODULE", RIMU_IMAGE_MODULE_INSTALL_PATH, RIMU_IMAGE_MODULE_BUILD_PATH,
    "OpenImageIO module (needed to read image textures and write JPEG or TIFF)", "rimu_image_module_api",
    kImageModuleApiVersion, &call_module_entry<ImageModuleApi>};
constexpr ModuleLocation kFreeImage{"librimu_freeimage.so", "RIMU_FREEIMAGE_MODULE", RIMU_FREEIMAGE_MODULE_INSTALL_PATH,
                                    RIMU_FREEIMAGE_MODULE_BUILD_PATH, "FreeImage module (needed to read PFM and HDR images)",
                                    "rimu_image_module_api", kImageModuleApiVersion,
                                    &call_module_entry<ImageModuleApi>};

std::atomic<bool> oiio_loaded{false};
std::atomic<bool> freeimage_loaded{false};

// The files the FreeImage module reads: a PFM (its signature: "PF" colour or "Pf" grey and the white space before
// its width) or a Radiance HDR stored in the standard orientation (radiance_header.h).
bool for_freeimage(const std::filesystem::path& path) {
  char magic[3] = {0, 0, 0};
  std::ifstream(path, std::ios::binary).read(magic, 3);
  if (magic[0] == 'P' && (magic[1] == 'F' || magic[1] == 'f') && std::isspace(static_cast<unsigned char>(magic[2])))
    return true;
  return radiance_standard_size(path.string()).has_value();
}

}  // namespace

const ImageModuleApi& image_library() {
  static const ImageModuleApi& api = *static_cast<const ImageModuleApi*>(load_module(kOpenImageIO, oiio_loaded));
  return api;
}

bool image_library_loaded() { return oiio_loaded.load(); }

const ImageModuleApi& freeimage_library() {
  static const ImageModuleApi& api = *static_cast<const ImageModuleApi*>(load_module(kFreeImage, freeimage_loaded));
  return api;
}

const ImageModuleApi& image_reader_for(const std::filesystem::path& path) {
  return for_freeimage(path) ? freeimage_library() : image_library();
}

bool freeimage_library_loaded() { return freeimage_loaded.load(); }

}  // namespace rimu
