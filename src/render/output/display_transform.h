// The OpenColorIO adapter: scene-linear film values to display-encoded RGB, with Rimu's errors.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/film/spectral_response.h"
#include "spectral/colour_spaces/matrix3.h"

namespace rimu {

/// How a film becomes a picture on a display.
struct DisplayOptions {
  double exposure_ev = 0.0;     ///< scene values are multiplied by 2^exposure_ev before the view transform
  std::string view = "Standard";  ///< a view of data/ocio/config.ocio: "Standard", "ACES 1.0 SDR" or "Raw"
  std::string display = "sRGB";
  std::filesystem::path ocio_config;  ///< empty: <data>/ocio/config.ocio (find_data_directory())
  /// For camera films: the camera-to-XYZ matrix (render/film/camera_colour_matrix.h) that turns the written R, G, B into
  /// XYZ before the view transform. Unset: the raw sensor R, G, B are shown as if they were linear Rec.709.
  std::optional<Matrix3> camera_to_xyz;
};

/// The display exposure accepted, ±kMaxDisplayExposure_ev stops: beyond it 2^EV leaves the range of a float
/// (2^±126) for ordinary film values and the image is all black or all white.
inline constexpr double kMaxDisplayExposure_ev = 60.0;

/// A CPU colour processor from a film's scene-linear channels to the display's encoded RGB.
///
/// Wraps OpenColorIO (in a module loaded on first use), which reports errors by throwing OCIO::Exception: every failure while loading the config or
/// building the processor becomes an InputError naming the config file and the display/view (listing the views
/// that exist), so callers see Rimu's error style only. The source colour space follows the film: XYZ films
/// use "CIE-XYZ - Scene-linear" (the config's scene reference); camera films "Camera RGB - as Linear Rec.709".
class DisplayTransform {
 public:
  /// Loads the config and builds the processor (setup cost: milliseconds; do it once).
  DisplayTransform(ResponseKind film_kind, const DisplayOptions& options);
  ~DisplayTransform();
  DisplayTransform(DisplayTransform&&) noexcept;
  DisplayTransform& operator=(DisplayTransform&&) noexcept;

  /// Applies exposure and the view transform in place to interleaved RGB floats (pixel_count × 3).
  void apply(std::vector<float>& rgb, size_t pixel_count) const;

  /// The config file actually used.
  const std::filesystem::path& config_path() const { return config_path_; }

 private:
  struct Processor;
  std::unique_ptr<Processor> processor_;
  std::filesystem::path config_path_;
  float exposure_scale_ = 1.0f;
};

/// The OCIO source colour space Rimu uses for a film kind (see DisplayTransform).
const char* film_colour_space(ResponseKind kind);

/// True once a DisplayTransform has loaded the OpenColorIO module (librimu_ocio.so) in this process: OpenColorIO is
/// loaded on first use, by programs that write or check a display image (display_module/display_module_api.h).
bool display_library_loaded();

}  // namespace rimu
