#include "render/scene_ies_light.h"

#include <cmath>

#include "render/ies_file.h"
#include "spectral/light_units.h"
#include "transport/goniometric_light.h"

namespace rimu::scene_loading {

std::unique_ptr<Light> load_ies_light(const JsonCursor& l, LoadContext& context) {
  l.only_keys({"type", "name", "file", "position", "direction", "c0_direction", "spectrum", "luminous_power_lm",
               "candela_scale"});
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

  if (!l.has("spectrum")) l.fail("an ies light needs 'spectrum': its spectral shape, e.g. {\"blackbody\": 3000}");
  const JsonCursor spectrum_key = l.at("spectrum");
  SpectrumPtr shape = context.spectra.parse(spectrum_key, SpectrumRole::emission);
  ShapeIntegrals integrals;
  try {
    integrals = shape_integrals(*shape, context.spectra.library().photopic_v());
  } catch (const InputError& e) {
    spectrum_key.fail(e.explanation());
  }

  double table_scale = 1.0;
  if (l.has("luminous_power_lm") && l.has("candela_scale"))
    l.at("candela_scale").fail("give either luminous_power_lm or candela_scale, not both");
  if (const auto s = l.find("candela_scale")) table_scale = s->number(1e-30, 1e30);
  std::shared_ptr<const CandelaDistribution> table = candela_distribution(ies, table_scale);
  if (!(table->integral_sr() > 0.0)) file.fail("the IES file's candela table is all zero");
  if (const auto lm = l.find("luminous_power_lm"))
    table = candela_distribution(ies, lm->number(1e-30, 1e30) / table->integral_sr());

  // One table unit = 1 cd: the shape scaled so that K_m Σ S V Δλ = 1 (lm/sr per W/sr of the scaled shape).
  LightSpectrum per_candela(std::move(shape), 1.0 / integrals.luminous);
  return std::make_unique<GoniometricLight>(l.at("position").vec3(), n, c0, std::move(per_candela), std::move(table));
}

}  // namespace rimu::scene_loading
