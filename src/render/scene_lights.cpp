// The "lights" section of the JSON scene format (radiometric units; see docs/scene-format.md).
#include <cmath>

#include "render/rgb_environment_image.h"
#include "render/scene_load_context.h"
#include "transport/distant_light.h"
#include "transport/environment_light.h"
#include "transport/light_spectrum.h"
#include "transport/point_light.h"
#include "transport/spot_light.h"

namespace rimu::scene_loading {
namespace {

LightSpectrum spectrum_of(const JsonCursor& light, const char* key, LoadContext& context) {
  return LightSpectrum(context.spectra.parse(light.at(key), SpectrumRole::emission), 1.0);
}

Vec3 unit_direction(const JsonCursor& c) {
  const Vec3 d = c.vec3();
  if (!(length(d) > 0.0f)) c.fail("a direction cannot be zero");
  return normalize(d);
}

std::unique_ptr<Light> load_light(const JsonCursor& l, LoadContext& context) {
  const std::string type = l.at("type").choice({"point", "spot", "distant", "environment"});
  if (type == "point") {
    l.only_keys({"type", "name", "position", "intensity"});
    return std::make_unique<PointLight>(l.at("position").vec3(), spectrum_of(l, "intensity", context));
  }
  if (type == "spot") {
    l.only_keys({"type", "name", "position", "direction", "cone_angle_deg", "falloff_start_deg", "intensity"});
    const double outer = l.at("cone_angle_deg").number(0.01, 179.9) / 2.0;
    const double inner = l.has("falloff_start_deg") ? l.at("falloff_start_deg").number(0.0, 2.0 * outer) / 2.0 : outer;
    return std::make_unique<SpotLight>(l.at("position").vec3(), unit_direction(l.at("direction")), inner, outer,
                                       spectrum_of(l, "intensity", context));
  }
  if (type == "distant") {
    l.only_keys({"type", "name", "direction", "irradiance", "angular_diameter_deg"});
    return std::make_unique<DistantLight>(unit_direction(l.at("direction")), spectrum_of(l, "irradiance", context),
                                          l.number_or("angular_diameter_deg", 0.0, 0.0, 90.0));
  }
  l.only_keys({"type", "name", "radiance", "image", "colour_space", "encoding", "scale"});
  if (l.has("image")) {
    if (l.has("radiance")) l.at("radiance").fail("give either radiance or image, not both");
    const std::filesystem::path path = context.spectra.scene_directory() / l.at("image").string();
    const std::shared_ptr<const RgbImage> image = load_rgb_image(l, path);
    const std::string space = l.string_or("colour_space", "srgb-linear");
    const auto upsampler = context.spectra.upsampler(space, l.has("colour_space") ? l.at("colour_space") : l);
    // Scenes are y-up: the image's top row is +y and its left edge looks along +x (environment_light.h). Pixel
    // values are in film units, like every RGB emission (SpectrumInputContext::emission_rgb_scale).
    return std::make_unique<EnvironmentLight>(std::make_shared<RgbEnvironmentImage>(image, upsampler),
                                              l.number_or("scale", 1.0, 0.0, 1e30) * context.spectra.emission_rgb_scale(),
                                              Frame{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});
  }
  l.only_keys({"type", "name", "radiance"});
  return std::make_unique<EnvironmentLight>(spectrum_of(l, "radiance", context));
}

}  // namespace

std::shared_ptr<const RgbImage> load_rgb_image(const JsonCursor& value, const std::filesystem::path& path) {
  ImageEncoding encoding = default_encoding_for(path);
  if (const auto e = value.find("encoding")) encoding.srgb_transfer = e->choice({"srgb", "linear"}) == "srgb";
  try {
    return std::make_shared<const RgbImage>(RgbImage::read(path, encoding));
  } catch (const InputError& error) {
    SourceLocation where = error.where();
    where.key = value.path();
    throw InputError(where, error.explanation());
  }
}

void load_lights(const JsonCursor& section, LoadContext& context) {
  for (size_t i = 0; i < section.size(); ++i) context.scene.lights.push_back(load_light(section.at(i), context));
}

}  // namespace rimu::scene_loading
