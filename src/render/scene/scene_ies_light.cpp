#include "render/scene/scene_ies_light.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include "render/scene/ies_file.h"
#include "spectral/photometry/light_units.h"
#include "transport/lights/equal_area_intensity.h"
#include "transport/lights/goniometric_light.h"

namespace rimu::scene_loading {
namespace {

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// The light's "spectrum" scaled so that one table unit is one candela: K_m Σ S V Δλ = 1.
LightSpectrum per_candela_spectrum(const JsonCursor& l, LoadContext& context, const std::string& type) {
  if (!l.has("spectrum")) l.fail("a" + type + " light needs 'spectrum': its spectral shape, e.g. {\"blackbody\": 3000}");
  const JsonCursor spectrum_key = l.at("spectrum");
  SpectrumPtr shape = context.spectra.parse(spectrum_key, SpectrumRole::emission);
  ShapeIntegrals integrals;
  try {
    integrals = shape_integrals(*shape, context.spectra.library().photopic_v());
  } catch (const InputError& e) {
    spectrum_key.fail(e.explanation());
  }
  if (!std::isfinite(1.0 / integrals.luminous) || !(integrals.luminous > 0.0))
    spectrum_key.fail("the spectrum's luminous integral (" + format_number(integrals.luminous) +
                      ") cannot be normalised to 1 cd");
  return LightSpectrum(std::move(shape), 1.0 / integrals.luminous);
}

}  // namespace

std::unique_ptr<Light> load_goniometric_image_light(const JsonCursor& l, LoadContext& context, const Frame& frame) {
  l.only_keys({"type", "name", "light_group", "image", "encoding", "position", "frame", "spectrum", "luminous_power_lm", "candela_scale"});
  const JsonCursor file = l.at("image");
  const std::shared_ptr<const RgbImage> image = load_rgb_image(l, context.spectra.scene_directory() / file.string());
  if (image->width() != image->height())
    file.fail("an equal-area octahedral image must be square, not " + std::to_string(image->width()) + " x " +
              std::to_string(image->height()));
  if (l.has("luminous_power_lm") && l.has("candela_scale"))
    l.at("candela_scale").fail("give either luminous_power_lm or candela_scale, not both");
  // pbrt-v4 reads one value per pixel: a "Y" channel, or the mean of R, G and B.
  std::vector<double> values;
  values.reserve(size_t(image->width()) * size_t(image->height()));
  double sum = 0.0;
  for (int y = 0; y < image->height(); ++y)
    for (int x = 0; x < image->width(); ++x) {
      const Rgb p = image->pixel(x, y);
      const double v = (double(p.r) + double(p.g) + double(p.b)) / 3.0;
      if (!(v >= 0.0)) file.fail("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is negative: an intensity cannot be");
      values.push_back(v);
      sum += v;
    }
  if (!(sum > 0.0)) file.fail("the image is black: the light would emit nothing");
  const double integral_sr = 4.0 * std::numbers::pi * sum / double(values.size());
  double table_scale = 1.0;
  if (const auto s = l.find("candela_scale")) table_scale = s->number(1e-30, 1e30);
  if (const auto lm = l.find("luminous_power_lm")) table_scale = lm->number(1e-30, 1e30) / integral_sr;
  if (!std::isfinite(table_scale * integral_sr) || !(table_scale * integral_sr > 0.0) || !(table_scale * integral_sr <= 1e30))
    (l.has("luminous_power_lm") ? l.at("luminous_power_lm") : file)
        .fail("the image's intensities give " + format_number(table_scale * integral_sr) +
              " lm; a lamp must give more than 0 and at most 1e30 lm");
  for (double& v : values) v *= table_scale;
  auto table = std::make_shared<const EqualAreaIntensity>(image->width(), std::move(values));
  return std::make_unique<GoniometricLight>(l.at("position").vec3(), frame, per_candela_spectrum(l, context, " goniometric"),
                                            std::move(table));
}

std::unique_ptr<Light> load_ies_light(const JsonCursor& l, LoadContext& context) {
  l.only_keys({"type", "name", "light_group", "file", "position", "direction", "c0_direction", "spectrum", "luminous_power_lm",
               "candela_scale", "luminous_opening"});
  const JsonCursor file = l.at("file");
  IesPhotometry ies;
  try {
    ies = read_ies_file(context.spectra.scene_directory() / file.string());
  } catch (const InputError& e) {
    file.fail(e.what());  // "downlight.ies:12: ..." under the key that named the file
  }
  const Vec3 axis = l.has("direction") ? l.at("direction").vec3() : Vec3{0, -1, 0};
  if (!(length(axis) > 0.0f)) l.at("direction").fail("a direction cannot be zero");
  const Vec3 n = normalize(axis);
  Vec3 c0 = std::fabs(n.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 0, 1};
  if (const auto c = l.find("c0_direction")) {
    c0 = c->vec3();
    if (!(length(cross(c0, n)) > 1e-6f * length(c0))) c->fail("c0_direction must not be parallel to the direction");
  }

  LightSpectrum per_candela = per_candela_spectrum(l, context, "n ies");
  double table_scale = 1.0;
  if (l.has("luminous_power_lm") && l.has("candela_scale"))
    l.at("candela_scale").fail("give either luminous_power_lm or candela_scale, not both");
  if (const auto s = l.find("candela_scale")) table_scale = s->number(1e-30, 1e30);
  std::shared_ptr<const CandelaDistribution> table = candela_distribution(ies, table_scale);
  if (!(table->integral_sr() > 0.0)) file.fail("the IES file's candela table is all zero");
  // The lamp's flux bounds what reaches the film; the scene's amounts stop at 1e30 lm, and so does this one (beyond,
  // single-precision radiance overflows and every sample of the lamp would be discarded).
  const JsonCursor amount_key = l.has("candela_scale") ? l.at("candela_scale") : file;
  if (!l.has("luminous_power_lm") && !(table->integral_sr() <= 1e30))
    amount_key.fail("the IES table gives " + format_number(table->integral_sr()) +
                    " lm; a lamp may give at most 1e30 lm");
  if (const auto lm = l.find("luminous_power_lm")) {
    const double scale = lm->number(1e-30, 1e30) / table->integral_sr();
    if (!std::isfinite(scale) || !(scale > 0.0))
      lm->fail("scaling the IES table (" + format_number(table->integral_sr()) + " lm) to this flux gives a "
               "factor of " + format_number(scale));
    table = candela_distribution(ies, scale);
  }

  auto light = std::make_unique<GoniometricLight>(l.at("position").vec3(), n, c0, std::move(per_candela), std::move(table));
  // "luminous_opening": true: the light leaves from the file's luminous opening (width, length, height) instead of
  // its photometric centre (transport/lights/luminous_opening.h).
  if (const auto opening_key = l.find("luminous_opening"); opening_key && opening_key->boolean()) {
    constexpr double kMetresPerFoot = 0.3048;
    const auto opening = luminous_opening_from_lm63(ies.width, ies.length, ies.height,
                                                    ies.units_type == 1 ? kMetresPerFoot : 1.0);
    if (!opening.opening) opening_key->fail("the IES file's luminous opening (" + opening.error + ")");
    if (opening.opening->is_point())
      opening_key->fail("the IES file gives no luminous opening (width, length and height are 0): it is a point");
    light->set_opening(*opening.opening);
  }
  return light;
}

}  // namespace rimu::scene_loading
