#include "render/scene/scene_camera.h"

#include "spectral/error.h"

namespace rimu {

PhysicalCameraSettings parse_exposure(const JsonCursor& c) {
  c.only_keys({"iso", "shutter_s", "f_number", "compensation_ev"});
  PhysicalCameraSettings s;
  s.iso = c.at("iso").number(kIsoRange.min, kIsoRange.max);
  s.shutter_s = c.at("shutter_s").number(kShutterRange_s.min, kShutterRange_s.max);
  s.f_number = c.at("f_number").number(kFNumberRange.min, kFNumberRange.max);
  s.exposure_compensation_ev =
      c.number_or("compensation_ev", 0.0, kCompensationRange_ev.min, kCompensationRange_ev.max);
  return s;
}

WhiteBalanceSettings parse_white_balance(const JsonCursor& c, SpectralLibrary& library) {
  WhiteBalanceSettings wb;
  if (c.is_string()) {
    if (c.string() != "none") c.fail("expected \"none\", {\"cct\": K}, {\"daylight_cct\": K} or {\"illuminant\": name}");
    return wb;
  }
  if (!c.is_object() || c.size() != 1)
    c.fail("expected \"none\", {\"cct\": K}, {\"daylight_cct\": K} or {\"illuminant\": name}");
  c.only_keys({"cct", "daylight_cct", "illuminant"});
  if (c.has("cct")) {
    wb.kind = WhiteBalanceSettings::Kind::cct;
    wb.cct_k = c.at("cct").number(kMinCct_k, kMaxCct_k);
    return wb;
  }
  if (c.has("daylight_cct")) {
    wb.kind = WhiteBalanceSettings::Kind::daylight;
    wb.cct_k = c.at("daylight_cct").number(kMinDaylightCct_k, kMaxCct_k);
    return wb;
  }
  wb.kind = WhiteBalanceSettings::Kind::illuminant;
  wb.illuminant = c.at("illuminant").string();
  try {
    library.illuminant(wb.illuminant);
  } catch (const InputError& e) {
    c.at("illuminant").fail(e.explanation());
  }
  return wb;
}

}  // namespace rimu
