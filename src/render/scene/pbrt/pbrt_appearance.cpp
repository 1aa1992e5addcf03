// pbrt-v4 materials, textures and lights → Rimu's. The light units follow pbrt-v4: every light's spectrum is first
// normalised to a luminance of 1 (SpectrumToPhotometric), so `scale` (and `power`, `illuminance`) set the pixel value
// a pbrt film records, with a pixel Y of 1 standing for 1 nit. Rimu's XYZ film records Y = 1 at nits_per_unit_y_
// (≈ 72 983 nt), so pbrt's amount A becomes A · nits_per_unit_y_ in Rimu's photometric keys: the same image.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "render/scene/pbrt/pbrt_converter.h"
#include "render/image/image_file.h"
#include "render/scene/pbrt/pbrt_v3_hint.h"
#include "render/image/rgb_image.h"
#include "transport/lights/environment_portal.h"
#include "transport/sampling/equal_area_square.h"
#include "spectral/io/input_file.h"
#include "spectral/colour_spaces/rgb_colour_space.h"

namespace rimu {

namespace {

// pbrt-v4's roughness → Rimu's perceptual roughness r (GGX α = r²). pbrt's α is √roughness when remaproughness is
// true (TrowbridgeReitzDistribution::RoughnessToAlpha), the roughness itself otherwise.
double rimu_roughness(double pbrt_roughness, bool remap) {
  const double alpha = remap ? std::sqrt(std::max(0.0, pbrt_roughness)) : std::max(0.0, pbrt_roughness);
  return std::min(1.0, std::sqrt(alpha));
}

// pbrt-v4's named metal spectra → Rimu's copies of pbrt's own tables (src/spectral/library/optical_constants.cpp), so that
// an imported scene reflects as in pbrt; Rimu's "gold" etc. are other measurements (docs/pbrt-import.md).
std::optional<std::string> metal_of(const std::string& named, const std::string& suffix) {
  static const std::pair<const char*, const char*> metals[] = {{"Au", "pbrt-au"}, {"Ag", "pbrt-ag"},     {"Cu", "pbrt-cu"},
                                                               {"Al", "pbrt-al"}, {"CuZn", "pbrt-cuzn"}, {"MgO", "pbrt-mgo"},
                                                               {"TiO2", "pbrt-tio2"}};
  for (const auto& [symbol, name] : metals)
    if (named == std::string("metal-") + symbol + suffix) return std::string(name);
  return std::nullopt;
}

// pbrt-v4's named glasses → Rimu's copies of pbrt's tables (glass-F5/F10/F11 are SCHOTT SF5/SF10/SF11).
std::optional<std::string> glass_of(const std::string& named) {
  static const std::pair<const char*, const char*> glasses[] = {{"glass-BK7", "pbrt-bk7"},     {"glass-BAF10", "pbrt-baf10"},
                                                                {"glass-FK51A", "pbrt-fk51a"}, {"glass-LASF9", "pbrt-lasf9"},
                                                                {"glass-F5", "pbrt-sf5"},      {"glass-F10", "pbrt-sf10"},
                                                                {"glass-F11", "pbrt-sf11"}};
  for (const auto& [pbrt_name, name] : glasses)
    if (named == pbrt_name) return std::string(name);
  return std::nullopt;
}

std::optional<std::string> illuminant_of(const std::string& named) {
  if (named.rfind("stdillum-", 0) != 0) return std::nullopt;
  const std::string tail = named.substr(9);
  static const char* known[] = {"A", "D50", "D65", "F1", "F2", "F3", "F4", "F5", "F6", "F7", "F8", "F9", "F10", "F11", "F12"};
  for (const char* k : known)
    if (tail == k) return tail;
  return std::nullopt;
}

// pbrt-v4's wavelength-value pairs (PiecewiseLinearSpectrum::FromInterleaved): strictly increasing wavelengths,
// and the end values carried out to 360 and 830 nm, so that beyond its table the spectrum keeps its end values
// (pbrt is 0 only outside 360-830 nm, which Rimu does not transport). The overall scale pbrt applies to a light's
// spectrum does not matter: light amounts are set photometrically (see the top of this file).
json tabulated_spectrum(const std::vector<double>& pairs, const PbrtParam& param) {
  if (pairs.size() < 4 || pairs.size() % 2 != 0)
    throw InputError(param.where, "spectrum of \"" + param.name + "\": expected at least two wavelength-value pairs, got " +
                                      std::to_string(pairs.size()) + " numbers");
  std::vector<double> lambda_nm, values;
  for (size_t i = 0; i < pairs.size(); i += 2) {
    if (i > 0 && !(pairs[i] > pairs[i - 2]))
      throw InputError(param.where, "spectrum of \"" + param.name + "\": wavelengths must increase; " + std::to_string(pairs[i]) +
                                        " nm follows " + std::to_string(pairs[i - 2]) + " nm");
    if (pairs[i + 1] < 0) throw InputError(param.where, "spectrum of \"" + param.name + "\": negative value at " + std::to_string(pairs[i]) + " nm");
    lambda_nm.push_back(pairs[i]);
    values.push_back(pairs[i + 1]);
  }
  if (lambda_nm.front() > 360.0) {
    lambda_nm.insert(lambda_nm.begin(), 360.0);
    values.insert(values.begin(), values.front());
  }
  if (lambda_nm.back() < 830.0) {
    lambda_nm.push_back(830.0);
    values.push_back(values.back());
  }
  return {{"wavelengths_nm", lambda_nm}, {"values", values}};
}

// A pbrt spectrum file: numbers separated by white space (or commas), '#' to the end of a line a comment; the
// numbers are wavelength-value pairs. Errors name the file and line.
std::vector<double> read_spectrum_file(const std::filesystem::path& path, const PbrtParam& param) {
  std::istringstream in;
  try {
    in.str(read_input_file(path, kMaxTableFileBytes));  // the reader every input goes through (input_file.h)
  } catch (const InputError& e) {
    throw InputError(param.where, "cannot read the spectrum file '" + path.string() + "': " + e.explanation());
  }
  std::vector<double> numbers;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream words(line);
    for (std::string word; words >> word;) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end != word.c_str() + word.size() || !std::isfinite(v))
        throw InputError({path.string(), line_number, ""}, "expected a number, not '" + word + "'");
      numbers.push_back(v);
    }
  }
  if (numbers.size() % 2 != 0) throw InputError({path.string(), 0, ""}, "an odd count of numbers: expected wavelength-value pairs");
  return numbers;
}

}  // namespace

std::string PbrtConverter::default_material() {
  const std::string name = "pbrt default diffuse";
  if (!materials_.contains(name)) materials_[name] = {{"type", "diffuse"}, {"reflectance", 0.5}};
  return name;
}

double PbrtConverter::rgb_luminance(const PbrtParam& rgb) const {
  const RgbColourSpace& space = RgbColourSpace::named(state_.colour_space);
  return space.to_xyz({rgb.numbers[0], rgb.numbers[1], rgb.numbers[2]}).y;
}

std::optional<json> PbrtConverter::spectrum_value(const PbrtParam& param, bool illuminant, const std::filesystem::path& directory) {
  switch (param.type) {
    case PbrtParamType::rgb: return json{{"rgb", param.numbers}, {"space", state_.colour_space}};
    case PbrtParamType::blackbody: return json{{"blackbody", param.numbers[0]}};
    case PbrtParamType::real: return json(param.numbers.at(0));
    case PbrtParamType::spectrum:
      if (!param.strings.empty()) {
        const std::string& named = param.strings[0];
        if (illuminant)
          if (const auto name = illuminant_of(named)) return json{{"illuminant", *name}};
        const std::filesystem::path file = directory / named;
        const bool looks_like_file = named.find('.') != std::string::npos || named.find('/') != std::string::npos;
        if (!std::filesystem::is_regular_file(file)) {
          if (looks_like_file) throw InputError(param.where, "cannot find the spectrum file '" + file.string() + "' of \"" + param.name + "\"");
          ignore("spectrum \"" + named + "\" of \"" + param.name + "\" (named spectra are imported as a conductor's metal-*-eta/-k pair, a dielectric's glass-* and a light's stdillum-*)", param.where);
          return std::nullopt;
        }
        return tabulated_spectrum(read_spectrum_file(file, param), param);
      } else {
        bool constant = true;
        for (size_t i = 3; i < param.numbers.size(); i += 2) constant = constant && param.numbers[i] == param.numbers[1];
        if (constant) return json(param.numbers[1]);
        return tabulated_spectrum(param.numbers, param);
      }
    default: return std::nullopt;
  }
}

std::optional<json> PbrtConverter::optical_constant(const PbrtParam& param, PbrtParams& p, bool conductor_index) {
  if (param.type != PbrtParamType::rgb) return spectrum_value(param, false, p.directory());
  // pbrt-v4 reads an RGB eta or k as an unbounded spectrum (RGBUnboundedSpectrum), not as a colour.
  // The parser has checked three finite numbers >= 0 (as for every RGB).
  const bool index = param.name.ends_with("eta");
  const bool black = !(std::max({param.numbers[0], param.numbers[1], param.numbers[2]}) > 0);
  if (index && black && conductor_index) return json(1e-3);  // pbrt-v3-scenes' dragon/f14-3: "rgb eta" [0 0 0]
  if (index && black)
    throw InputError(param.where, p.context() + ": \"" + param.name + "\" must not be black (an index of refraction is > 0)");
  json value = unbounded_rgb({param.numbers[0], param.numbers[1], param.numbers[2]}, state_.colour_space, param.where);
  // pbrt's sigmoid spectra never reach 0, Rimu's smoothest spectra of saturated colours can; an index must stay > 0,
  // so it is floored at 1e-3 (below every metal's n in pbrt's tables: silver's lowest is 0.04).
  if (index && value.is_object())
    for (json& v : value["values"]) v = std::max(v.get<double>(), 1e-3);
  return value;
}

std::optional<json> PbrtConverter::reflectance(PbrtParams& p, const std::string& name, double fallback, int depth) {
  const PbrtParam* param = p.get(name, {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::texture, PbrtParamType::real});
  if (!param) return json(fallback);
  if (param->type == PbrtParamType::rgb) return rgb_reflectance(*param);
  if (param->type != PbrtParamType::texture) {
    if (auto v = spectrum_value(*param, false, p.directory())) return v;
    return json(fallback);
  }
  count_texture_lookup(param->strings.at(0), depth, param->where);
  const auto found = textures_.find(param->strings.at(0));
  if (found == textures_.end()) throw InputError(param->where, p.context() + ": no texture named \"" + param->strings[0] + "\"");
  const PbrtTexture& texture = found->second;
  const PbrtStatement& ts = texture.statement;
  if (texture.kind != "spectrum") throw InputError(param->where, p.context() + ": \"" + name + "\" needs a spectrum texture, \"" + param->strings[0] + "\" is a float texture");
  if (depth > 64) throw InputError(ts.where, "Texture \"" + ts.strings[0] + "\": textures nested more than 64 deep");
  if (texture.texture_class == "constant") {
    PbrtParams tp(*this, ts, "Texture \"" + ts.strings[0] + "\"");
    return reflectance(tp, "value", 1.0, depth + 1);
  }
  if (texture.texture_class != "imagemap")
    if (auto combined = spectrum_combinator(texture, depth + 1)) return combined;
  if (texture.texture_class == "imagemap") {
    PbrtParams tp(*this, ts, "Texture \"" + ts.strings[0] + "\"");
    const std::string filename = tp.string("filename", "");
    if (filename.empty()) throw InputError(ts.where, "Texture \"" + ts.strings[0] + "\": needs \"string filename\"");
    const std::filesystem::path path = std::filesystem::absolute(ts.directory / filename);
    if (!std::filesystem::is_regular_file(path)) throw InputError(ts.where, "Texture \"" + ts.strings[0] + "\": cannot find the image '" + path.string() + "'");
    json value = {{"texture", path_for_document(path)}, {"encoding", image_encoding(tp, path, ts.where)}};
    // Scale and invert act on the texel RGB before upsampling, as in pbrt-v4; a negative scale makes every texel 0
    // (or 1 inverted) there, and so here.
    const double scale = tp.real("scale", 1.0);
    if (scale != 1.0) value["scale"] = std::max(0.0, scale);
    if (tp.boolean("invert", false)) value["invert"] = true;
    image_mapping(tp, value, texture);
    return value;
  }
  ignore("Texture class \"" + texture.texture_class + "\" (the material's default is used)", ts.where);
  return json(fallback);
}

std::optional<double> PbrtConverter::constant_float_texture(const std::string& name, const SourceLocation& where, int depth) {
  count_texture_lookup(name, depth, where);
  const auto found = textures_.find(name);
  if (found == textures_.end()) throw InputError(where, "no texture named \"" + name + "\"");
  const PbrtTexture& texture = found->second;
  const PbrtStatement& ts = texture.statement;
  if (texture.kind != "float") throw InputError(where, "\"" + name + "\" is a spectrum texture where a float texture is needed");
  if (depth > 64) throw InputError(ts.where, "Texture \"" + name + "\": textures nested more than 64 deep");
  const std::string& cls = texture.texture_class;
  if (cls != "constant" && cls != "scale" && cls != "mix") return std::nullopt;
  // Textures that are constant everywhere are numbers: "constant", and "scale"/"mix" of constants (pbrt-v4's
  // FloatScaledTexture: tex·scale; FloatMixTexture: (1 − amount)·tex1 + amount·tex2).
  PbrtParams tp(*this, ts, "Texture \"" + name + "\"");
  if (cls == "constant") return tp.real("value", 1.0);
  // Every operand is looked up first (so none is listed as unused), then followed only until one is not constant:
  // following all of them at every level made a texture graph unfold quadratically more than it needs to.
  const auto param = [&](const std::string& key) { return tp.get(key, {PbrtParamType::real, PbrtParamType::texture}); };
  const auto value = [&](const PbrtParam* q, double fallback) -> std::optional<double> {
    if (!q) return fallback;
    if (q->type == PbrtParamType::real) return q->numbers.at(0);
    return constant_float_texture(q->strings.at(0), q->where, depth + 1);
  };
  if (cls == "scale") {
    const PbrtParam* tex = param("tex");
    const PbrtParam* scale = param("scale");
    const auto t = value(tex, 1.0);
    if (!t) return std::nullopt;
    const auto k = value(scale, 1.0);
    if (!k) return std::nullopt;
    return *t * *k;
  }
  const PbrtParam* tex1 = param("tex1");
  const PbrtParam* tex2 = param("tex2");
  const PbrtParam* amount_param = param("amount");
  const auto a = value(tex1, 0.0);
  if (!a) return std::nullopt;
  const auto b = value(tex2, 1.0);
  if (!b) return std::nullopt;
  const auto amount = value(amount_param, 0.5);
  if (!amount) return std::nullopt;
  return (1.0 - *amount) * *a + *amount * *b;
}

void PbrtConverter::texture(const PbrtStatement& s) {
  const std::string& kind = s.strings[1];
  if (kind == "color")
    throw InputError(s.where, "Texture \"" + s.strings[0] + "\": the type \"color\" is pbrt-v3's (pbrt-v4 says "
                                                          "\"spectrum\"); " + pbrt_v3_hint());
  if (kind != "spectrum" && kind != "float")
    throw InputError(s.where, "Texture \"" + s.strings[0] + "\": the type must be \"spectrum\" or \"float\", not \"" + kind + "\"");
  textures_[s.strings[0]] = {kind, s.strings[2], s, world_from_object()};
}

std::string PbrtConverter::mix_material(const PbrtStatement& s, const std::string& name, const std::string& context,
                                        const std::vector<PbrtParam>* material_defaults) {
  // pbrt-v4's MixMaterial picks materials[1] with probability `amount` per hit (a hash of the hit): Rimu's "mix".
  PbrtParams p(*this, s, context + " (mix)", material_defaults);
  if (s.keyword == "MakeNamedMaterial") p.string("type", "");
  const PbrtParam* names = p.get("materials", {PbrtParamType::string});
  if (!names || names->strings.size() != 2)
    throw InputError(s.where, p.context() + ": \"string materials\" must name two materials");
  for (const std::string& n : names->strings)
    if (!named_materials_.count(n) || !materials_.contains(n))
      throw InputError(names->where, p.context() + ": no material named \"" + n + "\"");
  json amount = float_value(p, "amount", 0.5);
  // pbrt-v4 treats ≤ 0 and ≥ 1 as certain choices; Rimu's mix clamps a textured amount per hit.
  if (amount.is_number()) amount = std::clamp(amount.get<double>(), 0.0, 1.0);
  const bool first_interface = interface_materials_.count(names->strings[0]) > 0;
  const bool second_interface = interface_materials_.count(names->strings[1]) > 0;
  if (first_interface || second_interface) {
    // A mix with pbrt's "no surface" would need a per-hit choice of whether the shape exists (an alpha): the
    // material of the larger share stands in for the whole surface.
    const std::string& chosen = names->strings[!amount.is_number() || amount.get<double>() >= 0.5 ? 1 : 0];
    ignore("Material \"mix\" with an \"interface\" material (the material of the larger share stands in)", s.where);
    materials_[name] = materials_.at(chosen);
    if (interface_materials_.count(chosen)) interface_materials_.insert(name);
    return name;
  }
  materials_[name] = {{"type", "mix"}, {"materials", names->strings}, {"amount", amount}};
  return name;
}

json PbrtConverter::hair_material(PbrtParams& p, const PbrtStatement& s) {
  json m = {{"type", "hair"}};
  // pbrt-v4's HairMaterial::Create takes the first of sigma_a, reflectance, eumelanin/pheomelanin that is given
  // (warning about the rest), and brown hair, eumelanin 1.3, when none is; Rimu's material wants exactly one.
  const PbrtParam* sigma_a = p.get("sigma_a", {PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::texture});
  const PbrtParam* colour = p.get("reflectance", {PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::texture, PbrtParamType::real});
  const PbrtParam* eumelanin = p.get("eumelanin", {PbrtParamType::real, PbrtParamType::texture});
  const PbrtParam* pheomelanin = p.get("pheomelanin", {PbrtParamType::real, PbrtParamType::texture});
  const auto constant = [&](const PbrtParam* q) -> std::optional<double> {
    if (q->type == PbrtParamType::real) return q->numbers.at(0);
    if (const auto c = constant_float_texture(q->strings.at(0), q->where, 0)) return *c;
    ignore("texture for hair \"" + q->name + "\" (pbrt-v4's brown hair, eumelanin 1.3, is used)", q->where);
    return std::nullopt;
  };
  if (sigma_a) {
    if (colour || eumelanin || pheomelanin)
      ignore("hair reflectance or melanin given with sigma_a (sigma_a is used, as in pbrt-v4)", s.where);
    // pbrt reads an RGB sigma_a as an unbounded spectrum (RGBUnboundedSpectrum), per unit fibre radius.
    if (sigma_a->type == PbrtParamType::rgb)
      m["sigma_a"] = unbounded_rgb({sigma_a->numbers[0], sigma_a->numbers[1], sigma_a->numbers[2]}, state_.colour_space, sigma_a->where);
    else if (sigma_a->type == PbrtParamType::spectrum)
      if (const auto v = spectrum_value(*sigma_a, false, p.directory())) m["sigma_a"] = *v;
    if (sigma_a->type == PbrtParamType::texture)
      ignore("texture for hair \"sigma_a\" (pbrt-v4's brown hair, eumelanin 1.3, is used)", sigma_a->where);
  } else if (colour) {
    if (eumelanin || pheomelanin) ignore("hair melanin given with reflectance (the reflectance is used, as in pbrt-v4)", s.where);
    if (colour->type == PbrtParamType::rgb)
      m["reflectance"] = rgb_reflectance(*colour);
    else if (colour->type == PbrtParamType::real)
      m["reflectance"] = colour->numbers.at(0);
    else if (colour->type == PbrtParamType::spectrum) {
      if (const auto v = spectrum_value(*colour, false, p.directory())) m["reflectance"] = *v;
    } else {
      ignore("texture for hair \"reflectance\" (pbrt-v4's brown hair, eumelanin 1.3, is used)", colour->where);
    }
  } else if (eumelanin || pheomelanin) {
    const auto e = eumelanin ? constant(eumelanin) : std::optional<double>(0.0);
    const auto h = pheomelanin ? constant(pheomelanin) : std::optional<double>(0.0);
    if (e && h) {
      m["eumelanin"] = std::max(0.0, *e);
      m["pheomelanin"] = std::max(0.0, *h);
    }
  }
  // Neither: the JSON material's own default is pbrt-v4's eumelanin 1.3.
  const auto scalar = [&](const std::string& key, double fallback) {
    const PbrtParam* q = p.get(key, {PbrtParamType::real, PbrtParamType::texture});
    if (!q) return fallback;
    if (q->type == PbrtParamType::real) return q->numbers.at(0);
    if (const auto c = constant_float_texture(q->strings.at(0), q->where, 0)) return *c;
    ignore("texture for hair \"" + key + "\" (" + std::to_string(fallback) + " is used)", q->where);
    return fallback;
  };
  // pbrt-v4 takes any value; Rimu's material refuses what its model cannot represent (β = 0 is a delta lobe), so
  // values are brought into its ranges here, and listed when that changes them.
  const auto ranged = [&](const char* key, double fallback, double low, double high) {
    const double value = scalar(key, fallback), kept = std::clamp(value, low, high);
    if (kept != value) ignore(std::string("hair \"") + key + "\" " + std::to_string(value) + " (" + std::to_string(kept) + " is used)", s.where);
    if (kept != fallback) m[key] = kept;
  };
  ranged("eta", 1.55, 1.0, 10.0);
  ranged("beta_m", 0.3, 1e-3, 1.0);
  ranged("beta_n", 0.3, 1e-3, 1.0);
  ranged("alpha", 2.0, -45.0, 45.0);
  return m;
}

std::string PbrtConverter::material(const PbrtStatement& s, const std::string& type, const std::string& context) {
  const bool named = s.keyword == "MakeNamedMaterial";
  std::string name = named ? s.strings[0]
                           : "pbrt " + type + " material at " + std::filesystem::path(s.where.file).filename().string() + ":" +
                                 std::to_string(s.where.line);
  // Files of one name in two folders (or one file included twice) would repeat a name: number the repeats.
  if (!named && materials_.contains(name)) name += " #" + std::to_string(++anonymous_materials_);
  origin("/materials/" + name, s.where, context);
  const auto defaults = state_.attributes.find("material");
  const std::vector<PbrtParam>* material_defaults = defaults == state_.attributes.end() ? nullptr : &defaults->second;
  json m;
  // pbrt-v4 reads "" and "none" as "interface" (deprecated spellings it warns about; clouds.pbrt uses "").
  if (type == "interface" || type.empty() || type == "none") {
    // pbrt's "no surface" (a medium's boundary). Without media its shapes have nothing to show: they are left out.
    materials_[name] = {{"type", "diffuse"}, {"reflectance", 0.5}};
    interface_materials_.insert(name);
    return name;
  }
  if (type == "mix") return mix_material(s, name, context, material_defaults);
  if (const auto v4 = pbrt_v4_name_of_v3_material(type))
    throw InputError(s.where, context + ": material \"" + type + "\" is pbrt-v3's (pbrt-v4's upgrader makes it \"" +
                                  *v4 + "\"); " + pbrt_v3_hint());
  if (type != "diffuse" && type != "coateddiffuse" && type != "coatedconductor" && type != "conductor" &&
      type != "dielectric" && type != "thindielectric" && type != "diffusetransmission" && type != "hair" &&
      type != "subsurface" && type != "measured") {
    ignore("Material \"" + type + "\" (" +
               (type == "fourier" ? "pbrt-v3's tabulated BSDF, which pbrt-v4 no longer reads; " : "") +
               "a grey diffuse of reflectance 0.5 stands in)",
           s.where);
    materials_[name] = {{"type", "diffuse"}, {"reflectance", 0.5}};
    return name;
  }
  PbrtParams p(*this, s, context + " (" + type + ")", material_defaults);
  if (named) p.string("type", "");
  const auto scalar = [&](const std::string& key, double fallback) {
    const PbrtParam* q = p.get(key, {PbrtParamType::real, PbrtParamType::texture});
    if (!q) return fallback;
    if (q->type == PbrtParamType::real) return q->numbers.at(0);
    if (const auto constant = constant_float_texture(q->strings.at(0), q->where, 0)) return *constant;
    ignore("texture for \"" + key + "\" of " + p.context() + " (" + std::to_string(fallback) + " is used)", q->where);
    return fallback;
  };
  const bool remap = p.boolean("remaproughness", true);
  // pbrt's "roughness" is the default of "uroughness" and "vroughness" (with a prefix for the coated conductor's
  // "interface." and "conductor." parameters).
  // Each is a number or a float texture (JSON, for roughness_value).
  const auto roughness_pair = [&](const std::string& prefix) {
    const json r = float_value(p, prefix + "roughness", 0.0);
    const auto one = [&](const std::string& key) {
      return p.get(key, {PbrtParamType::real, PbrtParamType::texture}) ? float_value(p, key, 0.0) : r;
    };
    return std::pair{one(prefix + "uroughness"), one(prefix + "vroughness")};
  };
  // The coat and slab of coateddiffuse / coatedconductor, with pbrt-v4's defaults (thickness 0.01, albedo 0,
  // g 0, maxdepth 10, nsamples 1). Rimu's coat is isotropic: anisotropic roughness becomes the mean (of numbers;
  // of textures, uroughness stands in).
  const auto coat_layer = [&](const std::string& prefix, json& out) {
    const auto [u, v] = roughness_pair(prefix);
    if (u.is_number() && v.is_number()) {
      const double mean = 0.5 * (u.get<double>() + v.get<double>());
      if (u != v) ignore("anisotropic coat roughness of " + type + " (the mean is used)", s.where);
      if (mean > 0) out["roughness"] = rimu_roughness(mean, remap);
    } else {
      if (u != v) ignore("anisotropic textured coat roughness of " + type + " (uroughness is used)", s.where);
      out["roughness"] = roughness_value(u, remap);
    }
    out["thickness"] = std::max(0.0, scalar("thickness", 0.01));
    if (const PbrtParam* albedo = p.get("albedo", {PbrtParamType::real, PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::texture})) {
      if (!(albedo->type == PbrtParamType::real && albedo->numbers[0] == 0.0)) out["albedo"] = *reflectance(p, "albedo", 0.0);
    }
    const double g = scalar("g", 0.0);
    if (g != 0.0) out["g"] = std::clamp(g, -0.99, 0.99);
    const int max_depth = p.integer("maxdepth", 10), samples = p.integer("nsamples", 1);
    if (max_depth != 10) out["max_depth"] = std::clamp(max_depth, 1, 1000);
    if (samples != 1) out["samples"] = std::clamp(samples, 1, 1000);
  };
  // A conductor's n and k from "<prefix>eta" / "<prefix>k" (named metal spectra, floats, tabulated), or copper.
  const auto conductor_ior = [&](const std::string& prefix, json& out) {
    const PbrtParam* eta = p.get(prefix + "eta", {PbrtParamType::real, PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::texture});
    const PbrtParam* k = p.get(prefix + "k", {PbrtParamType::real, PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::texture});
    if (const PbrtParam* r = p.get("reflectance", {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::texture})) {
      ignore(type + " \"reflectance\" (pbrt's copper is used)", r->where);
      out["metal"] = "pbrt-cu";
    } else if (!eta && !k) {
      out["metal"] = "pbrt-cu";  // pbrt's default: metal-Cu-eta / metal-Cu-k
    } else if (eta && k && eta->type == PbrtParamType::spectrum && k->type == PbrtParamType::spectrum && !eta->strings.empty() &&
               !k->strings.empty() && metal_of(eta->strings[0], "-eta") && metal_of(eta->strings[0], "-eta") == metal_of(k->strings[0], "-k")) {
      out["metal"] = *metal_of(eta->strings[0], "-eta");
    } else if (eta && k && eta->type != PbrtParamType::texture && k->type != PbrtParamType::texture) {
      // Floats, inline pairs, spectrum files or RGB (pbrt's unbounded RGB); a named spectrum Rimu lacks is listed
      // by spectrum_value.
      const auto n_value = optical_constant(*eta, p, true);
      const auto k_value = optical_constant(*k, p);
      if (n_value && k_value) {
        out["n"] = *n_value;
        out["k"] = *k_value;
      } else {
        out["metal"] = "pbrt-cu";
      }
    } else {
      ignore(type + " " + prefix + "eta/" + prefix + "k other than a metal-*-eta/-k pair of one metal, floats, RGB or tabulated spectra (pbrt's copper is used)", s.where);
      out["metal"] = "pbrt-cu";
    }
  };
  if (type == "hair") {
    m = hair_material(p, s);
  } else if (type == "measured") {
    // A measured BRDF of the RGL database: the file is read by the scene loader (MeasuredBrdf), as pbrt-v4 reads it.
    const std::string filename = p.string("filename", "");
    if (filename.empty()) throw InputError(s.where, context + " (measured): needs \"string filename\" (a .bsdf file)");
    const std::filesystem::path path = std::filesystem::absolute(p.directory() / filename);
    if (!std::filesystem::is_regular_file(path))
      throw InputError(s.where, context + " (measured): cannot find the BRDF file '" + path.string() + "'");
    m = {{"type", "measured"}, {"file", path.string()}};
  } else if (type == "diffuse") {
    m = {{"type", "diffuse"}, {"reflectance", *reflectance(p, "reflectance", 0.5)}};
  } else if (type == "diffusetransmission") {
    m = {{"type", "diffuse_transmission"}, {"reflectance", *reflectance(p, "reflectance", 0.25)},
         {"transmittance", *reflectance(p, "transmittance", 0.25)}};
    const double scale = p.real("scale", 1.0);
    if (scale != 1.0) m["scale"] = std::max(0.0, scale);
  } else if (type == "coateddiffuse") {
    m = {{"type", "coated_diffuse"}, {"reflectance", *reflectance(p, "reflectance", 0.5)}};
    if (const PbrtParam* eta = p.get("eta", {PbrtParamType::real, PbrtParamType::spectrum, PbrtParamType::rgb})) {
      if (const auto v = optical_constant(*eta, p)) m["coat_ior"] = *v;
    }
    coat_layer("", m);
  } else if (type == "coatedconductor") {
    m = {{"type", "coated_conductor"}};
    if (const PbrtParam* eta = p.get("interface.eta", {PbrtParamType::real, PbrtParamType::spectrum, PbrtParamType::rgb})) {
      if (const auto v = optical_constant(*eta, p)) m["coat_ior"] = *v;
    }
    coat_layer("interface.", m);
    if (p.get("reflectance", {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::texture, PbrtParamType::real})) {
      // pbrt-v4's artist metal under the coat (pbrt refuses it next to conductor.eta/k): Rimu's "reflectance".
      const std::initializer_list<PbrtParamType> ior_types = {PbrtParamType::real, PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::texture};
      if (p.get("conductor.eta", ior_types) || p.get("conductor.k", ior_types))
        throw InputError(s.where, "coatedconductor: give either \"reflectance\" or \"conductor.eta\"/\"conductor.k\", not both (as pbrt-v4)");
      m["reflectance"] = *reflectance(p, "reflectance", 0.0);
    } else {
      conductor_ior("conductor.", m);
    }
    const auto [u, v] = roughness_pair("conductor.");
    if (u == v) {
      if (u != json(0.0)) m["conductor_roughness"] = roughness_value(u, remap);
    } else {
      m["conductor_roughness_u"] = roughness_value(u, remap);
      m["conductor_roughness_v"] = roughness_value(v, remap);
    }
  } else if (type == "conductor") {
    m = {{"type", "conductor"}};
    if (p.get("reflectance", {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::texture, PbrtParamType::real})) {
      // pbrt-v4's artist-friendly conductor (n = 1, k from the reflectance): Rimu's conductor "reflectance".
      const std::initializer_list<PbrtParamType> ior_types = {PbrtParamType::real, PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::texture};
      if (p.get("eta", ior_types) || p.get("k", ior_types))
        ignore("conductor eta/k given with \"reflectance\" (the reflectance is used)", s.where);
      m["reflectance"] = *reflectance(p, "reflectance", 0.0);
    } else {
      conductor_ior("", m);
    }
    const json r = float_value(p, "roughness", 0.0);
    const json u = p.get("uroughness", {PbrtParamType::real, PbrtParamType::texture}) ? float_value(p, "uroughness", 0.0) : r;
    const json v = p.get("vroughness", {PbrtParamType::real, PbrtParamType::texture}) ? float_value(p, "vroughness", 0.0) : r;
    if (u == v) {
      if (u != json(0.0)) m["roughness"] = roughness_value(u, remap);
    } else {
      m["roughness_u"] = roughness_value(u, remap);
      m["roughness_v"] = roughness_value(v, remap);
    }
  } else {  // dielectric, thindielectric: the same eta; subsurface: a dielectric around its medium (subsurface_medium)
    const bool thin = type == "thindielectric";
    m = {{"type", thin ? "thin_dielectric" : "dielectric"}};
    // A spectrally varying eta (RGB, a table, a named glass) disperses, in pbrt-v4 as in Rimu.
    if (type == "subsurface") {
      const double ior = p.real("eta", 1.33);  // pbrt-v4 reads one float here
      if (!(ior > 0) || !(ior < 1e3)) throw InputError(s.where, context + " (subsurface): \"eta\" must be in (0, 1000)");
      m["ior"] = ior;
      // pbrt-v4's BSSRDF lets light in through its exit lobe S_ω, a Fresnel-weighted diffuse one: so does this
      // boundary, and point, spot and distant lights reach the walk beneath it through next-event estimation.
      m["diffuse_entry"] = true;
    } else if (const PbrtParam* eta = p.get("eta", {PbrtParamType::real, PbrtParamType::spectrum, PbrtParamType::rgb}); !eta) {
      m["ior"] = 1.5;
    } else if (eta->type == PbrtParamType::spectrum && !eta->strings.empty() && glass_of(eta->strings[0])) {
      m["glass"] = *glass_of(eta->strings[0]);
    } else if (const auto v = optical_constant(*eta, p)) {
      m["ior"] = *v;
    } else {
      m["ior"] = 1.5;  // spectrum_value reported it
    }
    // pbrt-v4's ThinDielectricMaterial reads no roughness: left unread, a given one is listed as unused.
    if (!thin) {
      const json r = float_value(p, "roughness", 0.0);
      const json u = p.get("uroughness", {PbrtParamType::real, PbrtParamType::texture}) ? float_value(p, "uroughness", 0.0) : r;
      const json v = p.get("vroughness", {PbrtParamType::real, PbrtParamType::texture}) ? float_value(p, "vroughness", 0.0) : r;
      if (u.is_number() && v.is_number()) {
        const double mean = 0.5 * (u.get<double>() + v.get<double>());
        if (u != v) ignore("anisotropic dielectric roughness (the mean is used)", s.where);
        if (mean > 0) m["roughness"] = roughness_value(mean, remap);
      } else {
        if (u != v) ignore("anisotropic textured dielectric roughness (uroughness is used)", s.where);
        m["roughness"] = roughness_value(u, remap);
      }
    }
  }
  // pbrt-v4's "normalmap" (an RGB image in tangent space) and bump map ("displacement", a float texture). pbrt's
  // GetBSDF uses the normal map when both are given.
  const std::string normal_map = p.string("normalmap", "");
  const bool displaced = p.get("displacement", {PbrtParamType::real, PbrtParamType::texture}) != nullptr;
  if (!normal_map.empty()) {
    const std::filesystem::path path = std::filesystem::absolute(p.directory() / normal_map);
    if (!std::filesystem::is_regular_file(path))
      throw InputError(s.where, p.context() + ": cannot find the normal map '" + path.string() + "'");
    // pbrt-v4 asks its Image::Read for linear values, but only its PNG reader takes the request: a TGA, PPM, JPEG or
    // BMP file comes out sRGB-decoded before n = 2·rgb − 1. Rimu's "normal_map" is linear unless told otherwise.
    m["normal_map"] = read_as_srgb_regardless(path)
                          ? json{{"image", path_for_document(path)}, {"encoding", "srgb"}}
                          : json(path_for_document(path));
    if (displaced) ignore("\"displacement\" given with \"normalmap\" (the normal map is used, as in pbrt-v4)", s.where);
  } else if (displaced) {
    m["displacement"] = float_value(p, "displacement", 0.0);
  }
  materials_[name] = m;
  if (type == "subsurface") subsurface_medium(p, name);
  return name;
}

json PbrtConverter::light_amount(PbrtParams& p, const char* spectrum_key, const char* radiometric_key,
                                 const char* photometric_key, std::optional<double> photometric_amount,
                                 const char* scale_key) {
  const PbrtParam* sp = p.get(spectrum_key, {PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::blackbody});
  const double scale = p.real(scale_key, 1.0);
  json value;
  double rgb_y = 1.0;  // pbrt normalises only the illuminant of an RGB light: the RGB's own luminance stays
  bool is_rgb = true;
  if (!sp) {
    value = {{"rgb", {1.0, 1.0, 1.0}}, {"space", state_.colour_space}};  // pbrt's default: the colour space's white
  } else if (sp->type == PbrtParamType::rgb) {
    rgb_y = rgb_luminance(*sp);
    if (auto shape = rgb_illuminant_shape(*sp)) {
      // pbrt's spectrum for the RGB, whose luminance the photometric key sets to the RGB's own Y (as the scene
      // format's RGB emission renders): the same film Y as before, with pbrt's spectral shape.
      value = std::move(*shape);
      if (!photometric_amount) photometric_amount = 1.0;
    } else {
      value = *spectrum_value(*sp, true, p.directory());
    }
  } else if (const auto v = spectrum_value(*sp, true, p.directory())) {
    value = *v;
    is_rgb = false;
  } else {
    value = {{"rgb", {1.0, 1.0, 1.0}}, {"space", state_.colour_space}};
  }
  if (is_rgb && !photometric_amount) {
    value["scale"] = std::max(0.0, scale);
    return {{radiometric_key, value}};
  }
  const double amount = nits_per_unit_y_ * scale * photometric_amount.value_or(1.0) * rgb_y;
  if (!(amount > 0)) return {{radiometric_key, 0.0}};
  return {{"spectrum", value}, {photometric_key, amount}};
}

json PbrtConverter::area_emission(const PbrtStatement& area_light, double area_m2, double power_multiple, bool& two_sided,
                                  bool image_capable) {
  const auto defaults = state_.attributes.find("light");
  PbrtParams p(*this, area_light, "AreaLightSource \"diffuse\"", defaults == state_.attributes.end() ? nullptr : &defaults->second);
  two_sided = p.boolean("twosided", false);
  const std::string filename = p.string("filename", "");
  // pbrt gives "power" to every shape it makes: a mesh's triangles each emit it, at the radiance power/(π A_triangle).
  // With triangles of equal area that is a uniform radiance of shape_count · power over the whole mesh.
  const double power = p.real("power", -1.0);
  if (!filename.empty() && image_capable) return image_area_emission(p, area_light, filename, area_m2, power * power_multiple, two_sided);
  if (!filename.empty())
    ignore("AreaLightSource \"filename\" on a sphere (Rimu's emissive spheres emit uniformly: \"L\" is used)", area_light.where);
  std::optional<double> lumens;
  if (power > 0 && area_m2 > 0) lumens = power * power_multiple;
  const json fields = light_amount(p, "L", "emission", lumens ? "luminous_power_lm" : "luminance_nt", lumens);
  return fields.contains("emission") ? fields["emission"] : fields;
}

json PbrtConverter::image_area_emission(PbrtParams& p, const PbrtStatement& s, const std::string& filename, double area_m2,
                                        double power, bool two_sided) {
  const std::string context = "AreaLightSource \"diffuse\"";
  if (p.get("L", {PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::blackbody}))
    throw InputError(s.where, context + ": give either \"L\" or \"filename\", not both");
  const std::filesystem::path path = std::filesystem::absolute(s.directory / filename);
  if (!std::filesystem::is_regular_file(path)) throw InputError(s.where, context + ": cannot find the image '" + path.string() + "'");
  // pbrt-v4 (DiffuseAreaLight) reads the image's RGB at the hit's (u, 1 − v), bilinearly, clamped at the edges, as an
  // RGB illuminant spectrum divided by the colour space white's luminance: a pixel of luminance Y is Y nits, Rimu's
  // film units, so its scale carries over (as for an environment image).
  double scale = p.real("scale", 1.0);
  if (power > 0 && area_m2 > 0) {
    // pbrt-v4 scales to the given power by k_e = π A (2 if two-sided) times the mean over the pixels of their
    // luminance (the file's colour space; sRGB here, as Rimu reads it): the image's mean, "assuming no distortion in
    // the mapping", not its mean over the surface.
    const RgbImage image = RgbImage::read(path, default_encoding_for(path));
    const RgbColourSpace& srgb = RgbColourSpace::named("srgb-linear");
    double mean_y = 0.0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) mean_y += srgb.to_xyz(image.pixel(x, y)).y;
    mean_y /= double(image.width()) * image.height();
    const double k_e = mean_y * (two_sided ? 2.0 : 1.0) * area_m2 * M_PI;
    if (!(k_e > 0)) throw InputError(s.where, context + ": \"power\" given for a black image '" + path.string() + "'");
    scale *= power / k_e;
  }
  return {{"image", path_for_document(path)}, {"scale", std::max(0.0, scale)}};
}

std::array<Vec3d, 3> PbrtConverter::light_axes(const PbrtMatrix& world, const std::string& context,
                                                const SourceLocation& where) {
  // A light transform may mirror (a Frame of either handedness works); a shear or non-uniform scale, which bends
  // pbrt's mapping, cannot be represented and is made rigid.
  std::array<Vec3d, 3> axes;
  for (int i = 0; i < 3; ++i) axes[i] = world.vector({i == 0 ? 1.0 : 0.0, i == 1 ? 1.0 : 0.0, i == 2 ? 1.0 : 0.0});
  const auto dot3 = [](const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const double scale0 = std::sqrt(dot3(axes[0], axes[0]));
  bool rigid = scale0 > 0;
  for (int i = 0; i < 3 && rigid; ++i)
    for (int j = 0; j < 3; ++j)
      rigid = rigid && std::abs(dot3(axes[i], axes[j]) - (i == j ? scale0 * scale0 : 0.0)) <= 1e-6 * scale0 * scale0;
  if (!rigid) ignore(context + " under a shear or non-uniform scale (its axes are made perpendicular)", where);
  for (int i = 0; i < 3; ++i) {  // Gram-Schmidt (for a rigid transform only the normalisation does anything)
    if (!rigid)
      for (int j = 0; j < i; ++j) {
        const double d = dot3(axes[i], axes[j]);
        for (int c = 0; c < 3; ++c) axes[i][c] -= d * axes[j][c];
      }
    const double len = std::sqrt(dot3(axes[i], axes[i]));
    if (!(len > 0)) throw InputError(where, context + ": the current transform is singular");
    for (int c = 0; c < 3; ++c) axes[i][c] /= len;
  }
  return axes;
}

json PbrtConverter::image_environment(PbrtParams& p, const PbrtStatement& s, const std::string& filename, const PbrtMatrix& world) {
  const std::string context = "LightSource \"infinite\"";
  if (p.get("L", {PbrtParamType::spectrum, PbrtParamType::rgb, PbrtParamType::blackbody}))
    throw InputError(s.where, context + ": give either \"L\" or \"filename\", not both");
  const std::filesystem::path path = std::filesystem::absolute(s.directory / filename);
  if (!std::filesystem::is_regular_file(path)) throw InputError(s.where, context + ": cannot find the image '" + path.string() + "'");
  // pbrt looks a world direction up at EqualAreaSphereToSquare(light_from_world · d): the image's axes s, t, n are
  // the world images of light-space x, y, z.
  const std::array<Vec3d, 3> axes = light_axes(world, context, s.where);
  double scale = p.real("scale", 1.0);
  const double illuminance = p.real("illuminance", -1.0);
  const ImageSize size = read_image_size(path);
  if (size.width != size.height) {
    // pbrt-v4 refuses a map that is not square ("unlikely to be an equal-area environment map"). Such maps come
    // from pbrt-v3 scenes, whose infinite light read them in the equirectangular mapping: light-space direction w
    // at u = φ/2π, v = θ/π with φ = atan2(w.y, w.x) ∈ [0, 2π), θ = acos(w.z), v = 0 the top row (pbrt-v3,
    // InfiniteAreaLight::Le). Rimu's equirectangular map has φ = atan2(−t·d, s·d), θ = acos(n·d): so s, t, n are
    // the world images of light-space x, −y, z. The upgrader keeps the file as it is, so this reads the scene as
    // pbrt-v3 rendered it.
    ignore(context + " with a map that is not square (pbrt-v4 refuses it; read in pbrt-v3's equirectangular "
                     "mapping)",
           s.where);
    if (illuminance > 0) {
      // No pbrt-v4 definition to follow: the true illuminance of the upper hemisphere (light-space z > 0),
      // Σ Y(pixel) cos θ Ω(pixel) with Ω = (2π/w)(π/h) sin θ at the pixel centre.
      const RgbImage image = RgbImage::read(path, default_encoding_for(path));
      const RgbColourSpace& srgb = RgbColourSpace::named("srgb-linear");
      double e = 0.0;
      for (int y = 0; y < image.height(); ++y) {
        const double theta = M_PI * (y + 0.5) / image.height();
        if (std::cos(theta) <= 0) continue;
        const double weight = std::cos(theta) * std::sin(theta) * (2.0 * M_PI / image.width()) * (M_PI / image.height());
        for (int x = 0; x < image.width(); ++x) e += srgb.to_xyz(image.pixel(x, y)).y * weight;
      }
      if (!(e > 0)) throw InputError(s.where, context + ": \"illuminance\" given for a map whose upper hemisphere is black");
      scale *= illuminance / e;
    }
    const Vec3d minus_y{-axes[1][0], -axes[1][1], -axes[1][2]};
    return {{"type", "environment"}, {"image", path_for_document(path)}, {"mapping", "equirectangular"},
            {"frame", {axes[0], minus_y, axes[2]}}, {"scale", std::max(0.0, scale)}};
  }
  if (illuminance > 0) {
    // pbrt-v4 (lights.cpp, ImageInfiniteLight) scales the map so that k_e = (2π/N) Σ Y(pixel) cos θ over the N
    // pixels whose centre has light-space z > 0 becomes the given illuminance. Each pixel subtends 4π/N sr, so the
    // upper hemisphere's true illuminance is twice pbrt's k_e: following pbrt (the same image) means twice the
    // stated illuminance. Y uses the linear sRGB luminance weights (pbrt: the file's colour space, sRGB by default).
    const RgbImage image = RgbImage::read(path, default_encoding_for(path));
    const RgbColourSpace& srgb = RgbColourSpace::named("srgb-linear");
    double k_e = 0.0;
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) {
        const Vec3 w = equal_area_square_to_sphere({(x + 0.5f) / float(image.width()), (y + 0.5f) / float(image.height())});
        if (w.z <= 0) continue;
        const Rgb rgb = image.pixel(x, y);
        k_e += srgb.to_xyz(rgb).y * w.z;
      }
    k_e *= 2.0 * M_PI / (double(image.width()) * image.height());
    if (!(k_e > 0)) throw InputError(s.where, context + ": \"illuminance\" given for a map whose upper hemisphere is black");
    scale *= illuminance / k_e;
  }
  // A pixel of luminance Y is Y nits in pbrt (its spectrum divided by the colour space white's luminance), the
  // film's Y = 1 per nit: Rimu's film units, so pbrt's scale carries over unchanged.
  return {{"type", "environment"}, {"image", path_for_document(path)}, {"mapping", "equal_area_octahedral"},
          {"frame", {axes[0], axes[1], axes[2]}}, {"scale", std::max(0.0, scale)}};
}

json PbrtConverter::goniometric_light(PbrtParams& p, const PbrtStatement& s, const PbrtMatrix& world) {
  // pbrt-v4 (GoniometricLight): I(λ, ω) = scale · I_spectrum(λ)/Y(I_spectrum) · image(EqualAreaSphereToSquare(w))
  // with w the light-space direction after swapping y and z, and image the pixel's "Y" or mean of R, G, B (nearest
  // pixel). So the image's local x, y, z are the world images of light-space x, z, y. "power" P replaces the image's
  // own scale: k_e = 4π · mean(image), scale · P / k_e.
  const std::string context = "LightSource \"goniometric\"";
  const std::string filename = p.string("filename", "");
  if (filename.empty()) {
    ignore(context + " without \"filename\" (pbrt renders it dark)", s.where);
    return nullptr;
  }
  const std::filesystem::path path = std::filesystem::absolute(s.directory / filename);
  if (!std::filesystem::is_regular_file(path)) throw InputError(s.where, context + ": cannot find the image '" + path.string() + "'");
  const std::array<Vec3d, 3> axes = light_axes(world, context, s.where);
  json light = {{"type", "goniometric"}, {"image", path_for_document(path)}, {"position", world.point({0, 0, 0})},
                {"frame", {axes[0], axes[2], axes[1]}}};
  // The file is decoded as the environment's image is (float images linear, 8-bit ones sRGB), as pbrt reads files
  // without colour-space metadata; pbrt's goniometric light takes no "encoding".
  const double power = p.real("power", -1.0);
  // Rimu's candela per pixel unit: pbrt's scale · Y_rgb in film units (nits_per_unit_y_), as for a point light.
  const json amount = light_amount(p, "I", "intensity", power > 0 ? "luminous_power_lm" : "candela_scale",
                                   power > 0 ? std::optional<double>(power) : std::optional<double>(1.0));
  if (!amount.contains("spectrum")) {
    ignore(context + " with a scale of 0 (it emits nothing)", s.where);
    return nullptr;
  }
  light.update(amount);
  return light;
}

json PbrtConverter::projection_light(PbrtParams& p, const PbrtStatement& s, const PbrtMatrix& world) {
  const std::string context = "LightSource \"projection\"";
  const std::string filename = p.string("filename", "");
  if (filename.empty()) throw InputError(s.where, context + ": \"filename\" is required (as in pbrt-v4)");
  const std::filesystem::path path = std::filesystem::absolute(s.directory / filename);
  if (!std::filesystem::is_regular_file(path)) throw InputError(s.where, context + ": cannot find the image '" + path.string() + "'");
  // pbrt-v4 projects along light-space +z through its Perspective(fov) screen, with the light's y flipped so that
  // light-space +y is the image's top row and +x its right: Rimu's frame [right, up, axis] is the world images of
  // light-space x, y, z.
  const std::array<Vec3d, 3> axes = light_axes(world, context, s.where);
  const double fov = p.real("fov", 90.0);
  if (!(fov > 0.0 && fov < 179.0)) throw InputError(s.where, context + ": \"fov\" must be in (0, 179) degrees");
  json light = {{"type", "projection"}, {"image", path_for_document(path)}, {"position", world.point({0, 0, 0})},
                {"frame", {axes[0], axes[1], axes[2]}}, {"fov_deg", fov}};
  // A pixel of luminance Y is pbrt's scale · Y "nits" of intensity (its spectrum over the colour space white's
  // luminance), Rimu's scale · Y · nits_per_unit_y_ candela. pbrt's "power" scales to power / Σ Y·Ω over the
  // pixels, which Rimu's luminous_power_lm does with the same sum (ProjectionLight), in the same film units.
  const double scale = p.real("scale", 1.0), power = p.real("power", -1.0);
  if (!(scale > 0.0)) {
    ignore(context + " with a scale of 0 (it emits nothing)", s.where);
    return nullptr;
  }
  if (power > 0) light["luminous_power_lm"] = nits_per_unit_y_ * scale * power;
  else light["white_intensity_cd"] = nits_per_unit_y_ * scale;
  return light;
}

void PbrtConverter::light_source(const PbrtStatement& s) {
  const std::string& type = s.strings[0];
  const std::string context = "LightSource \"" + type + "\"";
  if (type != "point" && type != "spot" && type != "distant" && type != "infinite" && type != "goniometric" &&
      type != "projection") {
    ignore(context, s.where);
    return;
  }
  if (object_) {
    ignore("LightSource inside ObjectBegin", s.where);
    return;
  }
  const auto defaults = state_.attributes.find("light");
  PbrtParams p(*this, s, context, defaults == state_.attributes.end() ? nullptr : &defaults->second);
  const PbrtMatrix world = world_from_object();
  if (!world.is_finite() || !world.is_affine()) throw InputError(s.where, context + ": the current transform is not finite and affine");
  if (ctm_moves()) ignore(context + " that moves (ActiveTransform: lights stay at their start placement)", s.where);
  const auto point = [&](const char* name, Vec3d fallback) {
    const std::vector<double> v = p.numbers(name, {PbrtParamType::point3});
    if (!v.empty() && v.size() != 3) throw InputError(s.where, context + ": \"" + name + "\" takes one point");
    return v.empty() ? fallback : Vec3d{v[0], v[1], v[2]};
  };
  json light = {{"type", type}};
  if (type == "projection") {
    json projection = projection_light(p, s, world);
    if (projection.is_null()) return;
    origin("/lights/" + std::to_string(lights_.size()), s.where, context);
    lights_.push_back(std::move(projection));
    return;
  }
  if (type == "goniometric") {
    json goniometric = goniometric_light(p, s, world);
    if (goniometric.is_null()) return;
    origin("/lights/" + std::to_string(lights_.size()), s.where, context);
    lights_.push_back(std::move(goniometric));
    return;
  }
  if (type == "point") {
    light["position"] = world.point(point("from", {0, 0, 0}));
    const double power = p.real("power", -1.0);
    json amount = light_amount(p, "I", "intensity", power > 0 ? "luminous_power_lm" : "luminous_intensity_cd",
                               power > 0 ? std::optional<double>(power) : std::nullopt);
    light.update(amount);
  } else if (type == "spot") {
    const Vec3d from = point("from", {0, 0, 0}), to = point("to", {0, 0, 1});
    light["position"] = world.point(from);
    const Vec3d direction = world.vector({to[0] - from[0], to[1] - from[1], to[2] - from[2]});
    if (direction == Vec3d{0, 0, 0}) throw InputError(s.where, context + ": \"from\" and \"to\" coincide");
    light["direction"] = direction;
    const double cone = p.real("coneangle", 30.0), delta = p.real("conedeltaangle", 5.0);
    // pbrt's angles are half-angles; Rimu's are full opening angles. Both fall off by a smoothstep in cos θ.
    const double full = std::clamp(2.0 * cone, 0.01, 179.9);
    if (full != 2.0 * cone) ignore("spot \"coneangle\" outside 0.005-89.95 degrees (clamped)", s.where);
    light["cone_angle_deg"] = full;
    light["falloff_start_deg"] = std::clamp(2.0 * (cone - delta), 0.0, full);
    const double power = p.real("power", -1.0);
    light.update(light_amount(p, "I", "intensity", power > 0 ? "luminous_power_lm" : "luminous_intensity_cd",
                              power > 0 ? std::optional<double>(power) : std::nullopt));
  } else if (type == "distant") {
    const Vec3d from = point("from", {0, 0, 0}), to = point("to", {0, 0, 1});
    // pbrt's light travels from "from" to "to"; Rimu's direction points from the scene towards the light.
    const Vec3d towards_light = world.vector({from[0] - to[0], from[1] - to[1], from[2] - to[2]});
    if (towards_light == Vec3d{0, 0, 0}) throw InputError(s.where, context + ": \"from\" and \"to\" coincide");
    light["direction"] = towards_light;
    const double illuminance = p.real("illuminance", -1.0);
    light.update(light_amount(p, "L", "irradiance", "illuminance_lx",
                              illuminance > 0 ? std::optional<double>(illuminance) : std::nullopt));
  } else {  // infinite
    light["type"] = "environment";
    // pbrt-v4's "portal": four points in world space (not under the current transform), a rectangle.
    json portals;
    if (const std::vector<double> v = p.numbers("portal", {PbrtParamType::point3}); !v.empty()) {
      if (v.size() != 12) throw InputError(s.where, context + ": \"portal\" takes four points, not " + std::to_string(v.size() / 3));
      const auto corner = [&](int i) { return Vec3{float(v[3 * i]), float(v[3 * i + 1]), float(v[3 * i + 2])}; };
      if (!PortalRectangle::from_corners(corner(0), corner(1), corner(2), corner(3)))
        throw InputError(s.where, context + ": the four \"portal\" points must form a rectangle, in order");
      portals = json::array({json::array({Vec3d{v[0], v[1], v[2]}, Vec3d{v[3], v[4], v[5]}, Vec3d{v[6], v[7], v[8]},
                                          Vec3d{v[9], v[10], v[11]}})});
    }
    if (const std::string filename = p.string("filename", ""); !filename.empty()) {
      origin("/lights/" + std::to_string(lights_.size()), s.where, "LightSource \"" + s.strings[0] + "\"");
      json image = image_environment(p, s, filename, world);
      if (!portals.is_null()) image["portals"] = portals;
      lights_.push_back(std::move(image));
      return;
    }
    if (!portals.is_null()) light["portals"] = portals;
    // "illuminance": what a surface facing up receives from the uniform sphere, π L.
    const double illuminance = p.real("illuminance", -1.0);
    light.update(light_amount(p, "L", "radiance", "luminance_nt",
                              illuminance > 0 ? std::optional<double>(illuminance / M_PI) : std::nullopt));
  }
  origin("/lights/" + std::to_string(lights_.size()), s.where, "LightSource \"" + s.strings[0] + "\"");
  lights_.push_back(std::move(light));
}

}  // namespace rimu
