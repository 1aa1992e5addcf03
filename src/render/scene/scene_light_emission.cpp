#include "render/scene/scene_light_emission.h"

#include <array>
#include <cmath>

#include "render/scene/light_amount_key.h"

namespace rimu::scene_loading {
namespace {

constexpr std::array kFormKeys{"spectrum", "keep", "reference_spectrum", "power_convention"};

// The shape's integrals, with the key path added to the "no visible power" error.
ShapeIntegrals integrals_at(const JsonCursor& where, const Spectrum& shape, LoadContext& context) {
  try {
    return shape_integrals(shape, context.spectra.library().photopic_v());
  } catch (const InputError& e) {
    where.fail(e.explanation());
  }
}

}  // namespace

bool has_light_amount(const JsonCursor& object) {
  if (!object.is_object()) return false;
  for (const LightAmountKey& a : kLightAmountKeys)
    if (object.has(a.key)) return true;
  return false;
}

void only_light_keys(const JsonCursor& object, std::initializer_list<const char*> own) {
  if (!object.is_object()) object.fail("expected an object");
  for (const auto& [key, unused] : object.value().items()) {
    bool known = false;
    for (const char* k : own) known = known || key == k;
    for (const char* k : kFormKeys) known = known || key == k;
    for (const LightAmountKey& a : kLightAmountKeys) known = known || key == a.key;
    if (known) continue;
    std::string list;
    for (const char* k : own) list += std::string(list.empty() ? "" : ", ") + k;
    for (const char* k : kFormKeys) list += std::string(", ") + k;
    for (const LightAmountKey& a : kLightAmountKeys) list += std::string(", ") + a.key;
    object.at(key).fail("unknown key '" + key + "'; expected one of: " + list);
  }
}

SpotPowerConvention spot_power_convention(const JsonCursor& light) {
  if (!light.has("power_convention")) return SpotPowerConvention::cone;
  return light.at("power_convention").choice({"cone", "point"}) == "cone" ? SpotPowerConvention::cone
                                                                           : SpotPowerConvention::point;
}

LightSpectrum parse_light_emission(const JsonCursor& object, const char* legacy_key, const EmitterGeometry& geometry,
                                   LoadContext& context) {
  if (!has_light_amount(object)) {
    for (const char* k : kFormKeys)
      if (object.has(k) && !(std::string(k) == "power_convention" && geometry.kind == EmitterKind::spot))
        object.at(k).fail(std::string("'") + k + "' needs an amount: one of luminous_power_lm, luminous_intensity_cd, "
                          "illuminance_lx, luminance_nt, ev100 or their radiometric twins");
    return LightSpectrum(context.spectra.parse(object.at(legacy_key), SpectrumRole::emission), 1.0);
  }
  if (object.has(legacy_key))
    object.at(legacy_key).fail(std::string("give either '") + legacy_key +
                               "' (an absolute spectrum) or 'spectrum' and an amount, not both");
  const KeyedLightAmount given = *read_light_amount(object);  // has_light_amount: there is one
  const LightAmount amount = given.amount;
  const JsonCursor amount_key = object.at(given.key->key);
  if (!object.has("spectrum"))
    object.fail(std::string("'") + given.key->key + "' needs 'spectrum': the light's spectral shape, e.g. {\"blackbody\": 2700}");
  const JsonCursor spectrum_key = object.at("spectrum");
  SpectrumPtr shape = context.spectra.parse(spectrum_key, SpectrumRole::emission);
  const ShapeIntegrals integrals = integrals_at(spectrum_key, *shape, context);

  KeepConstant keep = KeepConstant::photometric;
  std::optional<ShapeIntegrals> reference;
  if (object.has("keep"))
    keep = object.at("keep").choice({"photometric", "radiometric"}) == "radiometric" ? KeepConstant::radiometric
                                                                                      : KeepConstant::photometric;
  if (object.has("reference_spectrum")) {
    const JsonCursor r = object.at("reference_spectrum");
    if (keep != KeepConstant::radiometric) r.fail("reference_spectrum applies with \"keep\": \"radiometric\" only");
    reference = integrals_at(r, *context.spectra.parse(r, SpectrumRole::emission), context);
  } else if (keep == KeepConstant::radiometric && is_photometric(amount.unit)) {
    object.at("keep").fail("\"keep\": \"radiometric\" with a photometric amount needs 'reference_spectrum': the shape "
                           "the amount was authored for (its watts are kept)");
  }
  const double scale = shape_scale(amount, geometry, integrals, amount_key.where(), keep, reference ? &*reference : nullptr);
  if (!std::isfinite(scale) || !(scale > 0.0)) amount_key.fail("the amount gives a scale of " + std::to_string(scale));
  return LightSpectrum(std::move(shape), scale);
}

LightSpectrum area_light_emission(const JsonCursor& emission, const TriangleMesh& mesh, bool two_sided,
                                  LoadContext& context) {
  // The area only matters to an amount (lumens spread over it): no sum over the triangles otherwise.
  const double area_m2 = has_light_amount(emission) ? mesh_area_m2(mesh.positions, mesh.indices) : 0.0;
  return area_light_emission(emission, area_m2, two_sided, context);
}

LightSpectrum area_light_emission(const JsonCursor& emission, double area_m2, bool two_sided, LoadContext& context) {
  if (!has_light_amount(emission)) return LightSpectrum(context.spectra.parse(emission, SpectrumRole::emission), 1.0);
  only_light_keys(emission, {});
  if (emission.has("power_convention")) emission.at("power_convention").fail("power_convention applies to spot lights");
  EmitterGeometry geometry{EmitterKind::area};
  geometry.area_m2 = area_m2;
  geometry.two_sided = two_sided;
  return parse_light_emission(emission, "radiance", geometry, context);
}

LightSpectrum medium_emission_radiance(const JsonCursor& emission, LoadContext& context) {
  if (!has_light_amount(emission)) return LightSpectrum(context.spectra.parse(emission, SpectrumRole::emission), 1.0);
  only_light_keys(emission, {});
  if (emission.has("power_convention")) emission.at("power_convention").fail("power_convention applies to spot lights");
  return parse_light_emission(emission, "radiance", EmitterGeometry{EmitterKind::medium}, context);
}

bool is_emission_image(const JsonCursor& emission) { return emission.is_object() && emission.has("image"); }

EmissionImage area_emission_image(const JsonCursor& emission, LoadContext& context) {
  if (has_light_amount(emission) || emission.has("spectrum"))
    emission.fail("an emission image is scaled by 'scale' (film units: a pixel of luminance Y renders as film Y), "
                  "not by a photometric amount or a spectrum");
  emission.only_keys({"image", "colour_space", "encoding", "scale", "white_luminance_nt"});
  if (emission.has("white_luminance_nt") && emission.has("scale"))
    emission.at("scale").fail("give either scale (film units) or white_luminance_nt, not both");
  // A pixel of luminance Y (Y = 1: white) renders as film Y · scale, and one film unit of Y is
  // emission_rgb_scale() ≈ 72 983 cd/m² (K_m ∫ȳ dλ): a white of L nt is the scale L / that.
  const double scale = emission.has("white_luminance_nt")
                           ? emission.at("white_luminance_nt").number(1e-30, 1e30) / context.spectra.emission_rgb_scale()
                           : emission.number_or("scale", 1.0, 0.0, 1e30);
  return load_emission_image(emission, scale, context);
}

nlohmann::json included_light(const JsonCursor& light, const std::filesystem::path& scene_directory) {
  const JsonCursor include = light.at("include");
  const std::filesystem::path path = scene_directory / include.string();
  nlohmann::json merged;
  try {
    merged = parse_json_file(path);
  } catch (const InputError& e) {
    include.fail(e.what());
  }
  if (!merged.is_object()) include.fail("'" + path.string() + "' does not hold a JSON object (a light definition)");
  if (merged.contains("include")) include.fail("'" + path.string() + "' includes another file; one level only");
  for (const auto& [key, value] : light.value().items())
    if (key != "include") merged[key] = value;
  return merged;
}

double mesh_area_m2(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices) {
  // The same double-precision cross product as AreaLight, so the luminance set here and the power it reports agree.
  double area = 0.0;
  for (size_t k = 0; k + 2 < indices.size(); k += 3) {
    const Vec3 v0 = positions[indices[k]], v1 = positions[indices[k + 1]], v2 = positions[indices[k + 2]];
    const double e1[3] = {double(v1.x) - v0.x, double(v1.y) - v0.y, double(v1.z) - v0.z};
    const double e2[3] = {double(v2.x) - v0.x, double(v2.y) - v0.y, double(v2.z) - v0.z};
    const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double twice = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (twice > 0.0 && std::isfinite(twice)) area += 0.5 * twice;
  }
  return area;
}

}  // namespace rimu::scene_loading
