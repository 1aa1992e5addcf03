// The "lights" section of the JSON scene format (radiometric units; see docs/scene-format.md).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/image/rgb_radiance_image.h"
#include "render/scene/rgb_transport_inputs.h"
#include "render/scene/scene_load_context.h"
#include "render/scene/photometric_units.h"
#include "render/scene/scene_daylight.h"
#include "render/scene/scene_ies_light.h"
#include "render/scene/scene_light_emission.h"
#include "render/scene/scene_light_groups.h"
#include "render/scene/scene_portals.h"
#include "transport/lights/distant_light.h"
#include "transport/lights/environment_light.h"
#include "transport/lights/light_spectrum.h"
#include "transport/lights/point_light.h"
#include "transport/lights/projection_light.h"
#include "transport/lights/spot_light.h"
#include "spectral/photometry/light_units.h"

namespace rimu::scene_loading {
namespace {

Vec3 unit_direction(const JsonCursor& c) {
  const Vec3 d = c.vec3();
  if (!(length(d) > 0.0f)) c.fail("a direction cannot be zero");
  return normalize(d);
}

std::unique_ptr<Light> load_environment(const JsonCursor& l, LoadContext& context);
std::unique_ptr<Light> load_projection(const JsonCursor& l, LoadContext& context);

std::unique_ptr<Light> load_light(const JsonCursor& l, LoadContext& context) {
  const std::string type =
      l.at("type").choice({"point", "spot", "distant", "environment", "ies", "goniometric", "cie_sky", "sun", "projection"});
  if (type == "ies") return load_ies_light(l, context);
  if (type == "projection") return load_projection(l, context);
  if (type == "cie_sky") return load_cie_sky_light(l, context);
  if (type == "sun") return load_sun_light(l, context);
  // A goniometric image's default frame: image centre (local +z) along +y, as pbrt's after its y-z swap.
  if (type == "goniometric")
    return load_goniometric_image_light(l, context,
                                        l.has("frame") ? l.at("frame").frame() : Frame{{1, 0, 0}, {0, 0, 1}, {0, 1, 0}});
  if (type == "point") {
    only_light_keys(l, {"type", "name", "light_group", "position", "intensity"});
    const EmitterGeometry geometry{EmitterKind::point};
    return std::make_unique<PointLight>(l.at("position").vec3(),
                                        parse_light_emission(l, "intensity", geometry, context));
  }
  if (type == "spot") {
    only_light_keys(l, {"type", "name", "light_group", "position", "direction", "cone_angle_deg", "falloff_start_deg", "intensity"});
    const double outer = l.at("cone_angle_deg").number(0.01, 179.9) / 2.0;
    const double inner = l.has("falloff_start_deg") ? l.at("falloff_start_deg").number(0.0, 2.0 * outer) / 2.0 : outer;
    const EmitterGeometry geometry{EmitterKind::spot, inner, outer, spot_power_convention(l)};
    return std::make_unique<SpotLight>(l.at("position").vec3(), unit_direction(l.at("direction")), inner, outer,
                                       parse_light_emission(l, "intensity", geometry, context));
  }
  if (type == "distant") {
    only_light_keys(l, {"type", "name", "light_group", "direction", "irradiance", "angular_diameter_deg"});
    const EmitterGeometry geometry{EmitterKind::distant};
    return std::make_unique<DistantLight>(unit_direction(l.at("direction")),
                                          parse_light_emission(l, "irradiance", geometry, context),
                                          l.number_or("angular_diameter_deg", 0.0, 0.0, 90.0));
  }
  return load_environment(l, context);
}

// An emission image's pixel RGB times the light's scale is its radiance in film units; single-precision radiance
// overflows near 3.4e38, so (like a light's amount, kMaxLightAmount) it may be at most 1e30. Without this check a
// pixel of FLT_MAX upsamples to infinite coefficients and every sample that sees it is discarded: a black map, or a
// silently missing sun. The first pixel past the limit in reading order is named.
void check_emission_pixels(const JsonCursor& image_key, const std::string& file, const RgbImage& image,
                           double scale) {
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const Rgb rgb = image.pixel(x, y);
      const double largest = std::max({std::abs(rgb.r), std::abs(rgb.g), std::abs(rgb.b)});
      if (!(largest * scale <= kMaxLightAmount)) {
        char text[160];
        std::snprintf(text, sizeof text, "pixel (%d, %d) is (%g, %g, %g)", x, y, rgb.r, rgb.g, rgb.b);
        image_key.fail("'" + file + "': " + text + (scale == 1.0 ? "" : " times \"scale\" " + std::to_string(scale)) +
                       ": an emission image's radiance may be at most 1e30 per component (beyond, "
                       "single-precision radiance overflows)");
      }
    }
}

std::unique_ptr<Light> load_environment(const JsonCursor& l, LoadContext& context) {
  only_light_keys(l, {"type", "name", "light_group", "radiance", "image", "colour_space", "encoding", "scale", "mapping", "frame",
                      "portals"});
  PortalSet portals = load_portals(l);
  std::unique_ptr<EnvironmentLight> light;
  if (l.has("image")) {
    if (l.has("radiance")) l.at("radiance").fail("give either radiance or image, not both");
    if (has_light_amount(l) || l.has("spectrum"))
      l.fail("an image environment is scaled by 'scale' (film units), not by a photometric amount");
    const EmissionImage emission = load_emission_image(l, l.number_or("scale", 1.0, 0.0, 1e30), context);
    const EnvironmentMapping mapping = l.has("mapping") && l.at("mapping").choice({"equirectangular", "equal_area_octahedral"}) ==
                                                                  "equal_area_octahedral"
                                           ? EnvironmentMapping::equal_area_octahedral
                                           : EnvironmentMapping::equirectangular;
    const int width = emission.pixels->width(), height = emission.pixels->height();
    if (mapping == EnvironmentMapping::equal_area_octahedral && width != height)
      l.at("image").fail("an equal-area octahedral image must be square, not " + std::to_string(width) + " x " +
                         std::to_string(height));
    // Scenes are y-up: by default the image's local n (equirectangular: top row; octahedral: centre) is +y and its
    // s (left edge; middle of the right edge) is +x (environment_light.h). Pixel values are in film units, like
    // every RGB emission (SpectrumInputContext::emission_rgb_scale).
    const Frame frame = l.has("frame") ? l.at("frame").frame() : Frame{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    light = std::make_unique<EnvironmentLight>(emission.pixels, emission.scale, frame, mapping);
  } else {
    only_light_keys(l, {"type", "name", "light_group", "radiance", "portals"});
    const EmitterGeometry geometry{EmitterKind::environment};
    light = std::make_unique<EnvironmentLight>(parse_light_emission(l, "radiance", geometry, context));
  }
  light->set_portals(std::move(portals));
  return light;
}

std::unique_ptr<Light> load_projection(const JsonCursor& l, LoadContext& context) {
  l.only_keys({"type", "name", "light_group", "position", "direction", "up", "frame", "fov_deg", "image", "colour_space",
               "encoding", "white_intensity_cd", "luminous_power_lm"});
  // The frame: given whole ([right, up, axis], as the pbrt importer writes it), or from the axis and an up direction
  // (default +y) made perpendicular to it; right = axis × up, so the picture is seen upright from behind the projector.
  Frame frame;
  if (l.has("frame")) {
    if (l.has("direction") || l.has("up")) l.at("frame").fail("give either frame or direction (and up), not both");
    frame = l.at("frame").frame();
  } else {
    const Vec3 axis = unit_direction(l.at("direction"));
    const Vec3 up_given = l.has("up") ? unit_direction(l.at("up")) : Vec3{0, 1, 0};
    const Vec3 right = cross(axis, up_given);
    if (!(length(right) > 1e-4f))
      (l.has("up") ? l.at("up") : l.at("direction")).fail("the projector's up direction is parallel to its direction: give \"up\"");
    frame.n = axis;
    frame.s = normalize(right);
    frame.t = cross(frame.s, axis);
  }
  const double fov_deg = l.at("fov_deg").number(0.01, 179.0);
  if (l.has("white_intensity_cd") == l.has("luminous_power_lm"))
    l.fail("a projector takes one of white_intensity_cd (the candela of a pixel of luminance 1) and luminous_power_lm");
  // The pixels scaled so that a pixel of luminance Y has Y candela (emission_rgb_scale: cd/m² per film unit, the
  // same conversion for a luminous intensity), then the amount.
  const EmissionImage pixels = load_emission_image(l, 1.0 / context.spectra.emission_rgb_scale(), context);
  const Vec3 position = l.at("position").vec3();
  double white_cd = 0.0;
  if (const auto cd = l.find("white_intensity_cd")) {
    white_cd = cd->number(1e-30, 1e30);
  } else {
    const ProjectionLight unit(position, frame, fov_deg, pixels.pixels, pixels.scale);
    const double lm_per_cd = unit.luminance_weighted_solid_angle_sr();
    if (!(lm_per_cd > 0.0)) l.at("image").fail("the image is black: the projector would emit nothing");
    white_cd = l.at("luminous_power_lm").number(1e-30, 1e30) / lm_per_cd;
  }
  if (!(white_cd * pixels.scale <= 1e30)) l.fail("the projector's intensity exceeds 1e30");
  return std::make_unique<ProjectionLight>(position, frame, fov_deg, pixels.pixels, pixels.scale * white_cd);
}

}  // namespace

std::shared_ptr<const RgbImage> load_rgb_image(const JsonCursor& value, const std::filesystem::path& path) {
  const auto given = value.find("encoding");
  const bool given_srgb = given && given->choice({"srgb", "linear"}) == "srgb";
  try {
    ImageEncoding encoding = default_encoding_for(path);
    if (given) encoding.srgb_transfer = given_srgb;
    return std::make_shared<const RgbImage>(RgbImage::read(path, encoding));
  } catch (const InputError& error) {
    SourceLocation where = error.where();
    where.key = value.path();
    throw InputError(where, error.explanation());
  }
}

EmissionImage load_emission_image(const JsonCursor& l, double scale, LoadContext& context) {
  const std::filesystem::path path = context.spectra.scene_directory() / l.at("image").string();
  const std::shared_ptr<const RgbImage> image = load_rgb_image(l, path);
  const std::string space = l.string_or("colour_space", "srgb-linear");
  check_emission_pixels(l.at("image"), path.string(), *image, scale);
  // Pixel values are film units, like every RGB emission (SpectrumInputContext::emission_rgb_scale); in rgb
  // transport the pixels are used as given, already film units (render/scene/rgb_transport_inputs.h).
  if (context.spectra.rgb_transport())
    return {std::make_shared<RgbLaneRadianceImage>(image, RgbColourSpace::named(space)), scale};
  const auto upsampler = context.spectra.upsampler(space, l.has("colour_space") ? l.at("colour_space") : l);
  return {std::make_shared<RgbRadianceImage>(image, upsampler), scale * context.spectra.emission_rgb_scale()};
}

void load_lights(const JsonCursor& section, LoadContext& context) {
  for (size_t i = 0; i < section.size(); ++i) {
    const JsonCursor light = section.at(i);
    const std::string where = light.path();
    context.scene.light_names.push_back(light.is_object() && light.has("name") && light.at("name").is_string()
                                            ? "'" + light.at("name").string() + "' (" + where + ")"
                                            : "the light " + where);
    if (light.is_object() && light.has("include")) {
      const nlohmann::json merged = included_light(light, context.spectra.scene_directory());
      context.scene.photometric_lights = context.scene.photometric_lights || uses_photometric_units(merged);
      const JsonCursor definition(merged, light.file(), light.path());
      context.scene.lights.push_back(load_light(definition, context));
      read_light_group(definition, context.scene);
    } else {
      context.scene.lights.push_back(load_light(light, context));
      read_light_group(light, context.scene);
    }
  }
}

}  // namespace rimu::scene_loading
