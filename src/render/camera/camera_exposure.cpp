#include "render/camera/camera_exposure.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/daylight.h"
#include "spectral/error.h"

namespace rimu {
namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

}  // namespace

std::string WhiteBalanceSettings::describe() const {
  switch (kind) {
    case Kind::none: return "none";
    case Kind::cct: return number_text(cct_k) + " K";
    case Kind::daylight: return "daylight " + number_text(cct_k) + " K";
    case Kind::illuminant: return "illuminant " + illuminant;
  }
  return "none";
}

std::optional<WhiteBalanceSettings> WhiteBalanceSettings::from_description(const std::string& text) {
  WhiteBalanceSettings wb;
  if (text == "none") return wb;
  const std::string illuminant = "illuminant ", daylight = "daylight ";
  if (text.rfind(illuminant, 0) == 0 && text.size() > illuminant.size()) {
    wb.kind = Kind::illuminant;
    wb.illuminant = text.substr(illuminant.size());
    return wb;
  }
  const bool is_daylight = text.rfind(daylight, 0) == 0;
  const std::string kelvin = is_daylight ? text.substr(daylight.size()) : text;
  double k = 0.0;
  char unit = 0, extra = 0;
  if (std::sscanf(kelvin.c_str(), "%lf %c%c", &k, &unit, &extra) != 2 || unit != 'K' || !(k > 0.0)) return std::nullopt;
  wb.kind = is_daylight ? Kind::daylight : Kind::cct;
  wb.cct_k = k;
  return wb;
}

void check_camera_option(double value, const PhysicalCameraRange& range, const std::string& option) {
  if (value >= range.min && value <= range.max) return;
  throw InputError({"", 0, option}, std::string("expected ") + range.what + " in " + number_text(range.min) + " to " +
                                        number_text(range.max) + ", got " + number_text(value));
}

WhiteBalanceSettings parse_white_balance_option(const std::string& text, SpectralLibrary& library,
                                                const std::string& option) {
  WhiteBalanceSettings wb;
  if (text == "none") return wb;
  double k = 0.0;
  char unit = 0, extra = 0;
  const int n = std::sscanf(text.c_str(), "%lf%c%c", &k, &unit, &extra);
  if (n == 1 || (n == 2 && (unit == 'K' || unit == 'k'))) {
    if (!(k >= kMinCct_k && k <= kMaxCct_k))
      throw InputError({"", 0, option}, "a white-balance temperature must be in 1000-25000 K, got '" + text + "'");
    wb.kind = WhiteBalanceSettings::Kind::cct;
    wb.cct_k = k;
    return wb;
  }
  try {
    library.illuminant(text);
  } catch (const InputError& e) {
    throw InputError({"", 0, option}, "expected none, a temperature in K or an illuminant name: " + e.explanation());
  }
  wb.kind = WhiteBalanceSettings::Kind::illuminant;
  wb.illuminant = text;
  return wb;
}

double parse_shutter_time_s(const std::string& text, const std::string& option) {
  double a = 0.0, b = 1.0;
  char slash = 0, extra = 0;
  const int n = std::sscanf(text.c_str(), "%lf%c%lf%c", &a, &slash, &b, &extra);
  const bool ok = (n == 1) || (n == 3 && slash == '/');
  const double t = a / b;
  if (!ok || !std::isfinite(t) || !(t > 0.0))
    throw InputError({"", 0, option}, "expected a positive shutter time in seconds, e.g. 0.01 or 1/100; got '" + text + "'");
  return t;
}

SpectrumPtr white_balance_illuminant(const WhiteBalanceSettings& white_balance, SpectralLibrary& library) {
  switch (white_balance.kind) {
    case WhiteBalanceSettings::Kind::none: return nullptr;
    case WhiteBalanceSettings::Kind::cct:
      return std::make_shared<BlackbodySpectrum>(white_balance.cct_k, BlackbodySpectrum::Scale::peak_one);
    case WhiteBalanceSettings::Kind::daylight:
      return std::make_shared<TabulatedSpectrum>(daylight_spectrum(library.daylight_basis(), white_balance.cct_k));
    case WhiteBalanceSettings::Kind::illuminant: return library.illuminant(white_balance.illuminant);
  }
  return nullptr;
}

FilmOutputTransform film_output_transform(const CameraExposureSettings& camera, const SpectralResponse& response,
                                          SpectralLibrary& library) {
  FilmOutputTransform t;
  if (camera.exposure) t.scale = film_exposure_scale(*camera.exposure, response);
  // A colour-corrected camera film has its white balance in its matrix (SpectralResponse::colour_corrected).
  if (response.white_balance_in_curves()) return t;
  if (const SpectrumPtr white = white_balance_illuminant(camera.white_balance, library))
    t.channel_matrix = white_balance_matrix(*white, response, library);
  return t;
}

std::map<std::string, std::string> exposure_metadata(const CameraExposureSettings& camera,
                                                     const FilmOutputTransform& transform) {
  std::map<std::string, std::string> m;
  if (camera.white_balance.kind != WhiteBalanceSettings::Kind::none)
    m["whiteBalance"] = camera.white_balance.describe();
  if (!camera.exposure) return m;
  const PhysicalCameraSettings& e = *camera.exposure;
  m["iso"] = number_text(e.iso);
  m["shutterSeconds"] = number_text(e.shutter_s);
  m["fNumber"] = number_text(e.f_number);
  m["exposureCompensationEV"] = number_text(e.exposure_compensation_ev);
  m["EV"] = number_text(exposure_value(e));
  m["meteredLuminanceNits"] = number_text(metered_luminance_nt(e));
  m["exposureScale"] = number_text(transform.scale);
  return m;
}

}  // namespace rimu
