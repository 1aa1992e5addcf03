// pbrt-v4 participating media (MakeNamedMedium, MediumInterface, the "interface" material) → Rimu's "media"
// section. pbrt gives every shape an inside and an outside medium; Rimu fills the closed shapes of one material
// with one medium and finds the outside from the shapes around (docs/pbrt-import.md, "Media"). A shape whose
// inside medium differs from its outside one therefore gets a copy of its material that bounds that medium.
#include <algorithm>
#include <cmath>

#include "render/scene/pbrt/pbrt_converter.h"
#include "spectral/rgb_upsampler.h"

namespace rimu {

namespace {

// A spectral value (number or object form) multiplied by k ≥ 0: pbrt's medium "scale".
json scaled(json value, double k) {
  if (k == 1.0) return value;
  if (value.is_number()) return value.get<double>() * k;
  value["scale"] = value.value("scale", 1.0) * k;
  return value;
}

}  // namespace

json PbrtConverter::coefficient_value(PbrtParams& p, const std::string& name, double fallback) {
  const PbrtParam* param = p.get(name, {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::blackbody});
  if (!param) return fallback;
  if (param->type == PbrtParamType::rgb) {
    const std::vector<double>& c = param->numbers;
    if (c.size() != 3) throw InputError(param->where, p.context() + ": \"" + name + "\" takes 3 numbers");
    for (double v : c)
      if (!(v >= 0)) throw InputError(param->where, p.context() + ": \"" + name + "\" must be >= 0 (a coefficient per unit length)");
    if (c[0] == c[1] && c[1] == c[2]) return c[0];
    // pbrt's unbounded RGB (RGBUnboundedSpectrum): the reflectance-like spectrum of rgb / (2·max), times 2·max.
    // Rimu's scene format refuses RGB for coefficients (a coefficient is not a colour), so the importer writes
    // that spectrum as a 5 nm table, through Rimu's reflectance upsampler of the colour space in effect.
    auto& upsampler = upsamplers_[state_.colour_space];
    if (!upsampler) upsampler = std::make_shared<const RgbUpsampler>(library_, RgbColourSpace::named(state_.colour_space));
    const double scale = 2.0 * std::max({c[0], c[1], c[2]});
    const ReflectanceSpectrum shape = upsampler->reflectance_spectrum({c[0] / scale, c[1] / scale, c[2] / scale}, param->where);
    json nm = json::array(), values = json::array();
    for (int wavelength_nm = 360; wavelength_nm <= 830; wavelength_nm += 5) {
      nm.push_back(wavelength_nm);
      values.push_back(scale * shape.value(wavelength_nm));
    }
    return json{{"wavelengths_nm", nm}, {"values", values}};
  }
  const std::optional<json> value = spectrum_value(*param, false, p.directory());
  if (!value) return fallback;  // a named spectrum Rimu lacks: listed by spectrum_value
  return *value;
}

void PbrtConverter::make_named_medium(const PbrtStatement& s) {
  const std::string& name = s.strings[0];
  std::string type;
  if (const PbrtParam* t = s.find("type"); t && t->type == PbrtParamType::string && t->strings.size() == 1) type = t->strings[0];
  if (type.empty()) throw InputError(s.where, "MakeNamedMedium \"" + name + "\": needs \"string type\"");
  if (media_defined_.count(name)) throw InputError(s.where, "MakeNamedMedium: \"" + name + "\" is already defined");
  const std::string context = "MakeNamedMedium \"" + name + "\" (" + type + ")";
  media_where_[name] = s.where;
  if (type == "uniformgrid" || type == "rgbgrid" || type == "nanovdb" || type == "cloud") {
    // Rimu's grid medium reads .rvol files or its procedural cloud; the importer does not write voxel files.
    ignore("MakeNamedMedium \"" + type + "\" (not imported: shapes it fills render without a medium)", s.where);
    media_defined_[name] = nullptr;
    return;
  }
  if (type != "homogeneous") throw InputError(s.where, context + ": unknown medium type; pbrt-v4 has homogeneous, uniformgrid, rgbgrid, nanovdb and cloud");
  PbrtParams p(*this, s, context);
  p.string("type", "");
  const std::string preset = p.string("preset", "");
  if (!preset.empty())
    ignore("MakeNamedMedium \"preset\" (pbrt's measured scattering presets are not imported: sigma_a and sigma_s, or their default 1, stand in)", s.where);
  const json sigma_a = coefficient_value(p, "sigma_a", 1.0);
  const json sigma_s = coefficient_value(p, "sigma_s", 1.0);
  const double scale = p.real("scale", 1.0);
  if (!(scale >= 0)) throw InputError(s.where, context + ": \"scale\" must be >= 0");
  double g = p.real("g", 0.0);
  if (!(g > -1 && g < 1)) throw InputError(s.where, context + ": \"g\" must be in (-1, 1)");
  if (std::abs(g) > 0.99) {
    ignore("MakeNamedMedium \"g\" beyond ±0.99 (clamped to Rimu's range)", s.where);
    g = std::clamp(g, -0.99, 0.99);
  }
  if (const PbrtParam* le = p.get("Le", {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::blackbody})) {
    const bool dark = le->type != PbrtParamType::blackbody && le->strings.empty() &&
                      std::all_of(le->numbers.begin(), le->numbers.end(), [](double v) { return v == 0; });
    if (!dark) ignore("MakeNamedMedium \"Le\" (Rimu's media do not emit: the medium is imported without its emission)", le->where);
  }
  p.real("Lescale", 1.0);  // only meaningful with Le
  media_defined_[name] = {{"type", "homogeneous"}, {"sigma_a", scaled(sigma_a, scale)}, {"sigma_s", scaled(sigma_s, scale)}, {"g", g}};
}

std::optional<std::string> PbrtConverter::boundary_material(const std::string& material, const SourceLocation& where,
                                                             const std::string& context) {
  const std::string& inside = state_.inside_medium;
  const std::string& outside = state_.outside_medium;
  const bool is_interface = interface_materials_.count(material) > 0;
  for (const std::string* medium : {&inside, &outside})
    if (!medium->empty() && !media_defined_.count(*medium))
      throw InputError(where, context + ": the MediumInterface at " + state_.medium_interface_where.file + ":" +
                                  std::to_string(state_.medium_interface_where.line) + " names the medium \"" + *medium +
                                  "\", which no MakeNamedMedium before this shape defines");
  if (!outside.empty() && !exterior_media_.count(outside)) exterior_media_[outside] = where;
  const auto left_out = [&]() -> std::optional<std::string> {
    if (!is_interface) return material;
    ignore(context + " with the \"interface\" material and no medium inside it (left out)", where);
    return std::nullopt;
  };
  if (inside.empty() || inside == outside) return left_out();  // no medium begins at this surface
  const json& medium = media_defined_.at(inside);
  if (medium.is_null()) return left_out();  // a medium type Rimu does not import (listed at MakeNamedMedium)
  interior_media_.insert(inside);
  const std::string key = material + '\n' + inside;
  if (const auto it = boundary_materials_.find(key); it != boundary_materials_.end()) return it->second;
  // One Rimu medium per (material, pbrt medium): a Rimu material bounds at most one medium, and "index_matched"
  // (pbrt's interface: no surface at all) belongs to the medium.
  const std::string boundary = material + " (around medium " + inside + ")";
  materials_[boundary] = materials_.at(material);
  origin("/materials/" + boundary, where, context);
  std::string rimu_name = inside;
  for (int n = 2; media_.contains(rimu_name); ++n) rimu_name = inside + " #" + std::to_string(n);
  json entry = medium;
  entry["boundary_material"] = boundary;
  if (is_interface) entry["index_matched"] = true;
  media_[rimu_name] = std::move(entry);
  origin("/media/" + rimu_name, media_where_.at(inside), "MakeNamedMedium \"" + inside + "\"");
  boundary_materials_[key] = boundary;
  return boundary;
}

void PbrtConverter::finish_media() {
  for (const auto& [name, where] : exterior_media_)
    if (!interior_media_.count(name) && !media_defined_.at(name).is_null())
      ignore("medium \"" + name + "\" outside shapes (MediumInterface exterior) with no shape that has it inside: Rimu's media fill "
             "closed shapes, so a medium around everything is not imported",
             where);
}

}  // namespace rimu
