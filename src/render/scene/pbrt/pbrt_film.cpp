// pbrt-v4's Film and the camera's shutter as Rimu's film and physical camera.
//
// pbrt-v4 (PixelSensor::Create) records sensor RGB = r · ∫ s̄(λ) L(λ) dλ with the imaging ratio r = t · S / 100
// (t = the camera's shutterclose − shutteropen, default 1 − 0; S = the film's "iso", default 100), so a pixel
// value is exactly proportional to t·S. Rimu's physical camera (render/camera/physical_camera.h) writes
// s · film value with s = 0.18 · 2^EC · t S / (K N²) · nits_per_unit_y (K = 12.5): with EC = 0 and
// N² = 0.18 · 100 · nits_per_unit_y / K the two agree for every t and S, Rimu's film value 1 being pbrt's 1 nit
// (pbrt_appearance.cpp). pbrt has no aperture in its imaging ratio; that f-number is only the unit conversion.
//
// White balance (pbrt's "whitebalance" T, default 0 = none for the cie1931 sensor, 6500 for a camera sensor): the
// source white is pbrt's Spectra::D(T), CIE daylight at the CCT T · 1.4388/1.4380 (a blackbody below 4000 K).
#include <cmath>
#include <filesystem>

#include "render/camera/camera_exposure.h"
#include "render/scene/pbrt/pbrt_converter.h"
#include "render/film/spectral_response.h"
#include "spectral/error.h"

namespace rimu {
namespace {

// Rimu's reflected-meter constant and mid grey (physical_camera.h), which the f-number below cancels.
constexpr double kMeterConstant = 12.5, kMidGrey = 0.18;
// pbrt-v4's imaging ratio is t · S / 100.
constexpr double kPbrtIsoReference = 100.0;

}  // namespace

void PbrtConverter::film(const PbrtStatement& s) {
  const std::string& type = s.strings[0];
  PbrtParams p(*this, s, "Film \"" + type + "\"");
  film_where_ = s.where;
  if (type == "gbuffer") {
    ignore("Film \"gbuffer\": the auxiliary channels (albedo, position, normals, depth, variance) are not written; "
           "the colour image is, as from the \"rgb\" film",
           s.where);
    p.string("coordinatesystem", "camera");  // only says in which frame the unwritten channels would be
  } else if (type == "spectral") {
    // pbrt's spectral film: nbuckets equal buckets over [lambdamin, lambdamax] (default 16 over 360-830 nm)
    // beside the RGB image. Rimu's spectral_bins are N equal bins over 360-830 nm.
    const int buckets = p.integer("nbuckets", 16);
    const double lambda_min = p.real("lambdamin", 360.0), lambda_max = p.real("lambdamax", 830.0);
    if (buckets < 1 || buckets > 471) throw InputError(s.where, "Film \"spectral\": \"nbuckets\" must be in 1-471");
    if (lambda_min != 360.0 || lambda_max != 830.0)
      ignore("Film \"spectral\" \"lambdamin\"/\"lambdamax\" other than 360/830 nm (Rimu's bins always span 360-830 nm)",
             s.where);
    film_["spectral_bins"] = buckets;
  } else if (type != "rgb") {
    ignore("Film \"" + type + "\" (rendered as the \"rgb\" film)", s.where);
  }
  width_ = p.integer("xresolution", 1280);
  height_ = p.integer("yresolution", 720);
  if (width_ < 1 || height_ < 1 || width_ > 32768 || height_ > 32768)
    throw InputError(s.where, "Film: xresolution and yresolution must be in 1-32768");
  film_["resolution"] = {width_, height_};
  film_crop(p, s);
  p.string("filename", "");  // the output is rimu's -o
  // pbrt writes half floats by default; Rimu writes 32-bit floats unless run with --half (they hold the same image
  // and more, so pbrt's implicit default is not listed). An explicit "savefp16" true asks for half floats: listed.
  if (p.boolean("savefp16", false))
    ignore("Film \"savefp16\" true (Rimu writes 32-bit floats unless run with --half)", s.where);
  p.real("diagonal", 35.0);     // the sensor's size in mm: only pbrt's "realistic" camera uses it (listed there)
  const double max_component = p.real("maxcomponentvalue", INFINITY);
  // pbrt-v4 scales each sample's sensor RGB (after the imaging ratio, before white balance) so that its largest
  // component is at most this: Rimu's film "max_sample_value" is the same rule on its written channels.
  if (max_component > 0.0 && max_component <= 1e30)
    film_["max_sample_value"] = max_component;
  else if (!std::isinf(max_component))
    ignore("Film \"maxcomponentvalue\" " + std::to_string(max_component) + " (not > 0: Rimu does not clamp)", s.where);

  film_iso_.reset();
  if (const PbrtParam* iso = p.get("iso", {PbrtParamType::real})) {
    if (iso->numbers.size() != 1) throw InputError(iso->where, "Film: \"iso\" takes one value");
    film_iso_ = iso->numbers[0];
    if (!(*film_iso_ >= kIsoRange.min && *film_iso_ <= kIsoRange.max))
      throw InputError(iso->where, "Film: \"iso\" must be in 0.001-10000000");
  }
  film_white_balance_k_ = p.real("whitebalance", 0.0);
  if (!(film_white_balance_k_ == 0.0 || (film_white_balance_k_ >= 1000.0 && film_white_balance_k_ <= 25000.0)))
    throw InputError(s.where, "Film: \"whitebalance\" must be 0 (none) or a temperature in 1000-25000 K");
  film_sensor_ = p.string("sensor", "cie1931");
  film_.erase("response");
  if (film_sensor_ != "cie1931") {
    // pbrt-v4's camera curves ship as data/spectra/cameras/pbrt_physlight_<sensor>_10nm.csv. pbrt-v4 writes the
    // sensor's R, G, B through its 24-patch fit to XYZ under the white-balance illuminant (PixelSensor): Rimu's
    // colour-corrected camera film is that pipeline.
    const std::string camera = "pbrt_physlight_" + film_sensor_ + "_10nm";
    try {
      SpectralResponse::camera_rgb(library_, camera);
    } catch (const InputError&) {
      throw InputError(s.where, "Film: unknown \"sensor\" \"" + film_sensor_ +
                                    "\"; expected cie1931 or one of pbrt-v4's camera sensors (canon_eos_5d_mkiv, "
                                    "nikon_d850, sony_ilce_9, … as in data/spectra/cameras/pbrt_physlight_*.csv)");
    }
    film_["response"] = "camera-xyz:" + camera;
  }
  // A camera sensor is balanced too (pbrt-v4's default 6500 K), to the colour space's white in pbrt.
  if ((film_white_balance_k_ != 0.0 || film_sensor_ != "cie1931") && state_.colour_space != "srgb-linear" &&
      state_.colour_space != "rec2020" &&
      state_.colour_space != "display-p3")
    ignore("Film \"whitebalance\" under ColorSpace " + state_.colour_space +
               " (Rimu balances to D65; pbrt to the colour space's white)",
           s.where);
}

void PbrtConverter::camera_shutter(PbrtParams& p) {
  shutter_given_ = p.get("shutteropen", {PbrtParamType::real}) || p.get("shutterclose", {PbrtParamType::real});
  shutter_open_ = p.real("shutteropen", 0.0);
  shutter_close_ = p.real("shutterclose", 1.0);
  shutter_s_ = shutter_close_ - shutter_open_;
  if (!(shutter_s_ > 0.0))
    throw InputError(p.where(), "Camera: \"shutterclose\" must be later than \"shutteropen\" (the shutter would not "
                                "open: pbrt-v4 refuses this too)");
  if (shutter_given_ && !(shutter_s_ >= kShutterRange_s.min && shutter_s_ <= kShutterRange_s.max))
    throw InputError(p.where(), "Camera: the shutter time shutterclose − shutteropen must be in 1e-9 to 1e6 s");
}

void PbrtConverter::finish_exposure(json& camera) const {
  if (film_iso_ || shutter_given_) {
    const double f_number = std::sqrt(kMidGrey * kPbrtIsoReference * nits_per_unit_y_ / kMeterConstant);
    camera["exposure"] = {{"iso", film_iso_.value_or(kPbrtIsoReference)},
                          {"shutter_s", shutter_s_},
                          {"f_number", f_number},
                          {"compensation_ev", 0.0}};
  }
  double white_k = film_white_balance_k_;
  if (film_sensor_ != "cie1931" && white_k == 0.0) white_k = 6500.0;  // pbrt-v4's default for camera sensors
  if (white_k == 0.0) return;
  // pbrt's Spectra::D(T) works at the CCT T·1.4388/1.4380 (the D illuminants' names date from c2 = 1.4380e-2
  // m·K) and falls back to a blackbody below 4000 K.
  const double cct_k = white_k * 1.4388 / 1.4380;
  if (cct_k < 4000.0)
    camera["white_balance"] = {{"cct", cct_k}};
  else if (cct_k <= 25000.0)
    camera["white_balance"] = {{"daylight_cct", cct_k}};
  else
    throw InputError(film_where_, "Film: \"whitebalance\" " + std::to_string(white_k) +
                                      " K is beyond CIE daylight's 25000 K");
}

}  // namespace rimu
