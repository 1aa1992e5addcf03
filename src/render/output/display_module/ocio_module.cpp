// OpenColorIO behind the DisplayModuleApi (display_module_api.h): loaded by render/output/display_transform.cpp on
// first use.
#include <OpenColorIO/OpenColorIO.h>

#include <string>

#include "render/output/display_module/display_module_api.h"

namespace OCIO = OCIO_NAMESPACE;

namespace {

using rimu::DisplayModuleFailure;

struct Processor {
  OCIO::ConstCPUProcessorRcPtr cpu;
};

void* create(const std::string& config_path, const std::string& source, const std::string& display,
             const std::string& view, DisplayModuleFailure& failure, std::string& error) {
  OCIO::ConstConfigRcPtr config;
  try {
    config = OCIO::Config::CreateFromFile(config_path.c_str());
  } catch (const OCIO::Exception& e) {
    failure = DisplayModuleFailure::config;
    error = e.what();
    return nullptr;
  }
  bool view_known = false;
  std::string views;
  for (int i = 0; i < config->getNumViews(display.c_str()); ++i) {
    const std::string v = config->getView(display.c_str(), i);
    views += (views.empty() ? "" : ", ") + v;
    view_known |= v == view;
  }
  if (!view_known) {
    failure = DisplayModuleFailure::unknown_view;
    error = views;
    return nullptr;
  }
  try {
    auto processor = config->getProcessor(source.c_str(), display.c_str(), view.c_str(), OCIO::TRANSFORM_DIR_FORWARD);
    return new Processor{processor->getDefaultCPUProcessor()};
  } catch (const OCIO::Exception& e) {
    failure = DisplayModuleFailure::processor;
    error = e.what();
    return nullptr;
  }
}

void apply(const void* processor, float* rgb, long pixel_count) {
  OCIO::PackedImageDesc image(rgb, pixel_count, 1, 3);
  // OpenColorIO throws only for a malformed image description, which this one is not.
  static_cast<const Processor*>(processor)->cpu->apply(image);
}

void destroy(void* processor) { delete static_cast<Processor*>(processor); }

const rimu::DisplayModuleApi kApi{rimu::kDisplayModuleApiVersion, create, apply, destroy};

}  // namespace

extern "C" __attribute__((visibility("default"))) const rimu::DisplayModuleApi* rimu_display_module_api() {
  return &kApi;
}
