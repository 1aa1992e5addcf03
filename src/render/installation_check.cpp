#include "render/installation_check.h"

#include <exception>
#include <functional>

#include "render/image/image_library.h"
#include "render/image/loadable_module.h"
#include "render/output/display_transform.h"
#include "spectral/io/data_directory.h"

namespace rimu {

std::vector<InstallationItem> check_installation() {
  std::vector<InstallationItem> items;
  const auto check = [&items](const std::string& name, const std::function<std::string()>& find) {
    InstallationItem item{name, false, ""};
    try {
      item.detail = find();
      item.ok = true;
    } catch (const std::exception& e) {
      item.detail = e.what();
    }
    items.push_back(item);
  };
  const auto loaded_from = [](const std::string& file_name) {
    for (const auto& [name, path] : loaded_modules())
      if (name == file_name) return path;
    return std::string("(loaded)");
  };
  check("data folder", [] { return find_data_directory().string(); });
  check("OpenImageIO module (image textures, JPEG/TIFF output)", [&] {
    (void)image_library();
    return loaded_from("librimu_oiio.so");
  });
  check("FreeImage module (PFM and HDR images)", [&] {
    (void)freeimage_library();
    return loaded_from("librimu_freeimage.so");
  });
  check("OpenColorIO module and config (display images)", [&] {
    const DisplayTransform transform(ResponseKind::cie_xyz, DisplayOptions{});
    return loaded_from("librimu_ocio.so") + ", config " + transform.config_path().string();
  });
  return items;
}

}  // namespace rimu
