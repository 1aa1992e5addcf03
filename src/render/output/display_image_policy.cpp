#include "render/output/display_image_policy.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "render/camera/physical_camera.h"

namespace rimu {

std::optional<double> metered_display_exposure_ev(const Film& film, const DisplayOptions& options,
                                                  double compensation_ev) {
  const double mean_y = mean_display_luminance(film, options);
  if (!(mean_y > 0.0) || !std::isfinite(mean_y)) return std::nullopt;
  return std::clamp(compensation_ev + std::log2(kMeterMidGrey / mean_y), -kMaxDisplayExposure_ev,
                    kMaxDisplayExposure_ev);
}

void write_policy_display_image(const std::filesystem::path& path, const Film& film, DisplayOptions options,
                                const DisplayImagePolicy& policy, std::ostream& log) {
  std::ostringstream notes;  // formatted here, so the caller's stream keeps its own precision
  if (policy.camera_fit) {
    const CameraColourFit& fit = *policy.camera_fit;
    options.camera_to_xyz = display_camera_to_xyz(fit, policy.white_balanced);
    notes << "rimu: " << film.response().description() << ": the display image shows the camera's R, G, B through "
          << "a camera-to-XYZ matrix fitted to the " << fit.patch_count << " ColorChecker patches under D65 (mean "
          << "CIEDE2000 " << std::setprecision(3) << fit.mean_delta_e2000 << ", max " << fit.max_delta_e2000 << " on "
          << fit.worst_patch << "); the EXR keeps the raw R, G, B with the matrix in 'cameraToXYZ'\n";
  }
  if (policy.metered) {
    const double mean_y = mean_display_luminance(film, options);
    if (const auto ev = metered_display_exposure_ev(film, options, options.exposure_ev)) {
      options.exposure_ev = *ev;
      notes << "rimu: photometric lights and no camera \"exposure\": the display image is metered, its mean "
               "luminance ("
            << std::setprecision(4) << mean_y * policy.nits_per_unit_y << " nt) shown as 18 % grey (display "
            << "exposure " << std::showpos << std::fixed << std::setprecision(2) << *ev << std::noshowpos
            << std::defaultfloat << " EV); the EXR stays in film units. Set the camera's \"exposure\" or "
            << "--iso/--shutter/--f-number for a physical exposure (docs/light-units.md)\n";
    }
  }
  if (!policy.quiet) log << notes.str();
  const DisplayLevels levels = write_display_image(path, film, options);
  std::ostringstream warnings;
  warnings << std::fixed << std::setprecision(0);
  if (levels.black_fraction >= kNearlyAllPixels)
    warnings << "rimu: warning: " << levels.black_fraction * 100.0 << " % of " << path.string()
             << " is nearly black (every channel at most " << kNearlyBlackCode << "/255): raise it with --exposure "
             << "<stops>, or give the camera an \"exposure\" block (docs/light-units.md)\n";
  if (levels.clipped_fraction >= kNearlyAllPixels)
    warnings << "rimu: warning: " << levels.clipped_fraction * 100.0 << " % of " << path.string()
             << " is clipped (some channel at 255): lower it with --exposure -<stops>, or give the camera an "
             << "\"exposure\" block (docs/light-units.md)\n";
  log << warnings.str();
}

}  // namespace rimu
