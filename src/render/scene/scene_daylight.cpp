#include "render/scene/scene_daylight.h"

#include <cmath>
#include <numbers>

#include "render/scene/scene_light_emission.h"
#include "render/scene/scene_portals.h"
#include "render/scene/sun_position_input.h"
#include "spectral/photometry/light_units.h"
#include "transport/lights/distant_light.h"
#include "transport/lights/sky/cie_sky_light.h"

namespace rimu::scene_loading {
namespace {

/// The sun's angular diameter seen from Earth, about 0.53° (0.524°-0.542° over the year).
constexpr double kSunAngularDiameterDeg = 0.53;
/// The daylight a sky emits unless "cct" or "spectrum" says otherwise: CIE D65.
constexpr double kDefaultSkyCctK = 6504.0;

}  // namespace

std::unique_ptr<Light> load_cie_sky_light(const JsonCursor& l, LoadContext& context) {
  l.only_keys({"type", "name", "light_group", "sky_type", "sun_position", "diffuse_horizontal_illuminance_lx", "zenith_luminance_nt",
               "cct", "spectrum", "up", "north", "portals"});
  const int type = l.at("sky_type").integer(1, kCieSkyTypeCount);
  const HorizonFrame frame = horizon_frame(l);
  const CieSkyParameters& parameters = cie_sky_parameters(type);
  const bool azimuthally_uniform = parameters.c == 0.0 && parameters.e == 0.0;  // types 1, 3, 5
  SunPosition sun;
  if (l.has("sun_position")) {
    sun = parse_sun_position(l.at("sun_position"), frame);
    if (sun.elevation_deg < 0.0)
      context.scene.warnings.push_back(sun_below_horizon_warning(
          context.scene.light_names.back(), sun,
          "the CIE standard sky is defined for a sun above the horizon, and its luminance distribution is extrapolated"));
  } else if (azimuthally_uniform) {
    sun.elevation_deg = 90.0;  // the distribution does not depend on the sun
    sun.direction = frame.up;
  } else {
    l.fail("sky type " + std::to_string(type) + " (" + cie_sky_description(type) +
           ") depends on where the sun is: give \"sun_position\"");
  }

  // The spectrum every sky element has: a CIE D-series daylight at "cct", or any "spectrum".
  SpectrumPtr shape;
  if (l.has("spectrum")) {
    if (l.has("cct")) l.at("cct").fail("give either cct or spectrum, not both");
    shape = context.spectra.parse(l.at("spectrum"), SpectrumRole::emission);
  } else {
    const double cct = l.has("cct") ? l.at("cct").number(4000.0, 25000.0) : kDefaultSkyCctK;
    const nlohmann::json daylight = {{"daylight", cct}};
    shape = context.spectra.parse(JsonCursor(daylight, l.file(), l.path() + "/cct"), SpectrumRole::emission);
  }
  const ShapeIntegrals shape_luminous =
      l.blame([&] { return shape_integrals(*shape, context.spectra.library().photopic_v()); });

  // Calibration: the zenith luminance, given or from the diffuse horizontal illuminance E = L_z ∫ L/L_z cos θ dω.
  const bool by_illuminance = l.has("diffuse_horizontal_illuminance_lx");
  if (by_illuminance == l.has("zenith_luminance_nt"))
    l.fail("give exactly one of diffuse_horizontal_illuminance_lx and zenith_luminance_nt");
  const double sun_zenith = (90.0 - sun.elevation_deg) * std::numbers::pi / 180.0;
  const CieSkyIntegrals integrals =
      integrate_cie_sky(parameters, {std::sin(sun_zenith), 0.0, std::cos(sun_zenith)});
  double zenith_luminance_nt = 0.0;
  if (by_illuminance) {
    const JsonCursor amount = l.at("diffuse_horizontal_illuminance_lx");
    const double lux = amount.number(kMinLightAmount, kMaxLightAmount);
    zenith_luminance_nt = lux / integrals.cosine_weighted_sr;
  } else {
    zenith_luminance_nt = l.at("zenith_luminance_nt").number(kMinLightAmount, kMaxLightAmount);
  }
  const double scale = zenith_luminance_nt / shape_luminous.luminous;
  if (!std::isfinite(scale) || !(scale > 0.0))
    l.fail("the calibration gives a spectral scale of " + std::to_string(scale) + " for this spectrum");
  auto sky = std::make_unique<CieSkyLight>(type, frame.up, sun.direction, LightSpectrum(std::move(shape), scale), integrals);
  sky->set_portals(load_portals(l));
  return sky;
}

std::unique_ptr<Light> load_sun_light(const JsonCursor& l, LoadContext& context) {
  only_light_keys(l, {"type", "name", "light_group", "sun_position", "irradiance", "angular_diameter_deg", "up", "north"});
  const HorizonFrame frame = horizon_frame(l);
  const SunPosition sun = parse_sun_position(l.at("sun_position"), frame);
  const EmitterGeometry geometry{EmitterKind::distant};
  LightSpectrum irradiance = parse_light_emission(l, "irradiance", geometry, context);
  if (sun.elevation_deg < 0.0) {
    context.scene.warnings.push_back(sun_below_horizon_warning(context.scene.light_names.back(), sun,
                                                               "this sun light gives no light"));
    irradiance = LightSpectrum(irradiance.shape(), 0.0);
  }
  return std::make_unique<DistantLight>(sun.direction, std::move(irradiance),
                                        l.number_or("angular_diameter_deg", kSunAngularDiameterDeg, 0.0, 90.0));
}

}  // namespace rimu::scene_loading
