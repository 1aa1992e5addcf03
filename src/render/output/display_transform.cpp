#include "render/output/display_transform.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cmath>
#include <sstream>

#include "spectral/io/data_directory.h"
#include "spectral/error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace rimu {

struct DisplayTransform::Processor {
  OCIO::ConstCPUProcessorRcPtr cpu;
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
  OCIO::ConstConfigRcPtr config;
  try {
    config = OCIO::Config::CreateFromFile(config_path_.c_str());
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_.string(), 0, ""}, std::string("cannot load the OpenColorIO config: ") + e.what());
  }
  bool view_known = false;
  std::string views;
  for (int i = 0; i < config->getNumViews(options.display.c_str()); ++i) {
    const std::string v = config->getView(options.display.c_str(), i);
    views += (views.empty() ? "" : ", ") + v;
    view_known |= v == options.view;
  }
  if (!view_known)
    throw InputError({config_path_.string(), 0, "--view"},
                     "unknown view '" + options.view + "' for display '" + options.display + "'; views: " +
                         (views.empty() ? std::string("none (unknown display?)") : views));
  try {
    auto processor = config->getProcessor(film_colour_space(film_kind), options.display.c_str(), options.view.c_str(),
                                          OCIO::TRANSFORM_DIR_FORWARD);
    processor_ = std::make_unique<Processor>(Processor{processor->getDefaultCPUProcessor()});
  } catch (const OCIO::Exception& e) {
    throw InputError({config_path_.string(), 0, "--view"},
                     "cannot build the display transform for view '" + options.view + "': " + e.what());
  }
}

DisplayTransform::~DisplayTransform() = default;
DisplayTransform::DisplayTransform(DisplayTransform&&) noexcept = default;
DisplayTransform& DisplayTransform::operator=(DisplayTransform&&) noexcept = default;

void DisplayTransform::apply(std::vector<float>& rgb, size_t pixel_count) const {
  for (float& v : rgb) v *= exposure_scale_;
  OCIO::PackedImageDesc image(rgb.data(), long(pixel_count), 1, 3);
  processor_->cpu->apply(image);  // throws only for malformed image descriptions, which this one is not
}

}  // namespace rimu
