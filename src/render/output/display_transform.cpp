#include "render/output/display_transform.h"

#include <atomic>
#include <cmath>
#include <sstream>

#include "render/image/loadable_module.h"
#include "render/output/display_module/display_module_api.h"
#include "spectral/io/data_directory.h"
#include "spectral/error.h"

#ifndef RIMU_DISPLAY_MODULE_INSTALL_PATH
#define RIMU_DISPLAY_MODULE_INSTALL_PATH ""
#endif
#ifndef RIMU_DISPLAY_MODULE_BUILD_PATH
#define RIMU_DISPLAY_MODULE_BUILD_PATH ""
#endif

namespace rimu {
namespace {

std::atomic<bool> ocio_loaded{false};

// OpenColorIO in a module loaded on first use (display_module_api.h says why).
const DisplayModuleApi& display_library() {
  static constexpr ModuleLocation kOpenColorIO{
      "librimu_ocio.so", "RIMU_DISPLAY_MODULE", RIMU_DISPLAY_MODULE_INSTALL_PATH, RIMU_DISPLAY_MODULE_BUILD_PATH,
      "OpenColorIO module (needed to write display images)", "rimu_display_module_api", kDisplayModuleApiVersion,
      &call_module_entry<DisplayModuleApi>};
  static const DisplayModuleApi& api = *static_cast<const DisplayModuleApi*>(load_module(kOpenColorIO, ocio_loaded));
  return api;
}

}  // namespace

bool display_library_loaded() { return ocio_loaded.load(); }

struct DisplayTransform::Processor {
  Processor(const DisplayModuleApi& a, void* h) : api(a), handle(h) {}
  ~Processor() { api.destroy(handle); }
  Processor(const Processor&) = delete;
  Processor& operator=(const Processor&) = delete;
  const DisplayModuleApi& api;
  void* handle;
};

const char* film_colour_space(ResponseKind kind) {
  return kind == ResponseKind::cie_xyz ? "CIE-XYZ - Scene-linear" : "Camera RGB - as Linear Rec.709";
}

DisplayTransform::DisplayTransform(ResponseKind film_kind, const DisplayOptions& options)
    : config_path_(options.ocio_config.empty() ? data_file("ocio/config.ocio") : options.ocio_config),
      exposure_scale_(float(std::exp2(options.exposure_ev))) {
  if (!(std::abs(options.exposure_ev) <= kMaxDisplayExposure_ev))
    throw InputError({"", 0, "--exposure"}, [&] {
                                                  std::ostringstream m;
                                                  m << "the display exposure must be a number of stops in -"
                                                    << kMaxDisplayExposure_ev << " to " << kMaxDisplayExposure_ev
                                                    << ", got " << options.exposure_ev;
                                                  return m.str();
                                                }());
  const DisplayModuleApi& api = display_library();
  DisplayModuleFailure failure = DisplayModuleFailure::none;
  std::string error;
  void* handle = api.create(config_path_.string(), film_colour_space(film_kind), options.display, options.view,
                            failure, error);
  if (!handle) {
    if (failure == DisplayModuleFailure::config)
      throw InputError({config_path_.string(), 0, ""}, "cannot load the OpenColorIO config: " + error);
    if (failure == DisplayModuleFailure::unknown_view)
      throw InputError({config_path_.string(), 0, "--view"},
                       "unknown view '" + options.view + "' for display '" + options.display + "'; views: " +
                           (error.empty() ? std::string("none (unknown display?)") : error));
    throw InputError({config_path_.string(), 0, "--view"},
                     "cannot build the display transform for view '" + options.view + "': " + error);
  }
  processor_ = std::make_unique<Processor>(api, handle);
}

DisplayTransform::~DisplayTransform() = default;
DisplayTransform::DisplayTransform(DisplayTransform&&) noexcept = default;
DisplayTransform& DisplayTransform::operator=(DisplayTransform&&) noexcept = default;

void DisplayTransform::apply(std::vector<float>& rgb, size_t pixel_count) const {
  for (float& v : rgb) v *= exposure_scale_;
  processor_->api.apply(processor_->handle, rgb.data(), long(pixel_count));
}

}  // namespace rimu
