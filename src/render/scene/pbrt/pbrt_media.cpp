// pbrt-v4 participating media (MakeNamedMedium, MediumInterface, the "interface" material) → Rimu's "media"
// section. pbrt gives every shape an inside and an outside medium; Rimu fills the closed shapes of one material
// with one medium and finds the outside from the shapes around (docs/pbrt-import.md, "Media"). A shape whose
// inside medium differs from its outside one therefore gets a copy of its material that bounds that medium.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "render/scene/pbrt/pbrt_converter.h"
#include "render/scene/spectrum_input.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "spectral/io/csv_table.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "transport/media/nanovdb_grid.h"

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

json PbrtConverter::unbounded_rgb(const Vec3d& c, const std::string& colour_space, const SourceLocation& where) {
  if (c[0] == c[1] && c[1] == c[2]) return c[0];
  if (rgb_upsampler_ == PbrtRgbUpsampler::sigmoid) return sigmoid_table(sigmoid_fit({c[0], c[1], c[2]}, true, colour_space, where));
  // pbrt's unbounded RGB (RGBUnboundedSpectrum): the reflectance-like spectrum of rgb / (2·max), times 2·max.
  // Rimu's scene format refuses RGB for coefficients (a coefficient is not a colour), so the importer writes
  // that spectrum as a table: pbrt's own sigmoid fit (pbrt_rgb_spectra.cpp), or, with Rimu's upsampler, its
  // reflectance upsampler of the colour space at 5 nm.
  const std::shared_ptr<const RgbUpsampler> upsampler = shared_upsampler(library_, colour_space);
  const double scale = 2.0 * std::max({c[0], c[1], c[2]});
  const ReflectanceSpectrum shape = upsampler->reflectance_spectrum({c[0] / scale, c[1] / scale, c[2] / scale}, where);
  json nm = json::array(), values = json::array();
  for (int wavelength_nm = 360; wavelength_nm <= 830; wavelength_nm += 5) {
    nm.push_back(wavelength_nm);
    values.push_back(scale * shape.value(wavelength_nm));
  }
  return json{{"wavelengths_nm", nm}, {"values", values}};
}

std::optional<std::pair<json, json>> PbrtConverter::scattering_preset(const std::string& name, const SourceLocation& where) {
  // data/media/scattering_presets.csv: pbrt-v4's table of Jensen et al. 2001 and Narasimhan et al. 2006, per mm,
  // which pbrt uses per scene unit as sRGB unbounded RGB: σ_a, and σ'_s as σ_s.
  const CsvTable& table = library_.table("media/scattering_presets.csv");
  const size_t name_column = table.column_index("name");
  for (size_t row = 0; row < table.row_count(); ++row) {
    if (table.cell(row, name_column) != name) continue;
    const auto rgb = [&](const char* prefix) {
      Vec3d c{};
      const char* channels[3] = {"_r", "_g", "_b"};
      for (size_t k = 0; k < 3; ++k) {
        const size_t column = table.column_index(std::string(prefix) + channels[k]);
        if (!parse_finite_number(table.cell(row, column), c[k]) || c[k] < 0)
          throw InputError({table.name(), table.line_of_row(row), ""}, "expected a finite number >= 0");
      }
      return c;
    };
    return std::pair{unbounded_rgb(rgb("sigma_a"), "srgb-linear", where), unbounded_rgb(rgb("sigma_prime_s"), "srgb-linear", where)};
  }
  return std::nullopt;
}

json PbrtConverter::coefficient_value(PbrtParams& p, const std::string& name, double fallback) {
  const PbrtParam* param = p.get(name, {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::blackbody});
  if (!param) return fallback;
  if (param->type == PbrtParamType::rgb) {
    const std::vector<double>& c = param->numbers;
    if (c.size() != 3) throw InputError(param->where, p.context() + ": \"" + name + "\" takes 3 numbers");
    for (double v : c)
      if (!(v >= 0)) throw InputError(param->where, p.context() + ": \"" + name + "\" must be >= 0 (a coefficient per unit length)");
    return unbounded_rgb({c[0], c[1], c[2]}, state_.colour_space, param->where);
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
  // pbrt-v3's density grid. pbrt-v4's upgrader means to rename it "uniformgrid" (same parameters: density, nx, ny,
  // nz, p0, p1, sigma_a, sigma_s, g, scale) but tests the medium's name instead of its type, so upgraded files
  // keep "heterogeneous", which pbrt-v4 then refuses: read it as the upgrader intends.
  if (type == "heterogeneous") type = "uniformgrid";
  media_where_[name] = s.where;
  if (type == "cloud") {
    PbrtParams p(*this, s, context);
    p.string("type", "");
    media_defined_[name] = noise_cloud_medium(p);
    return;
  }
  if (type == "rgbgrid") {
    ignore("MakeNamedMedium \"" + type + "\" (not imported: shapes it fills render without a medium)", s.where);
    media_defined_[name] = nullptr;
    return;
  }
  if (type != "homogeneous" && type != "uniformgrid" && type != "nanovdb") throw InputError(s.where, context + ": unknown medium type; pbrt-v4 has homogeneous, uniformgrid, rgbgrid, nanovdb and cloud");
  PbrtParams p(*this, s, context);
  p.string("type", "");
  json sigma_a = coefficient_value(p, "sigma_a", 1.0);
  json sigma_s = coefficient_value(p, "sigma_s", 1.0);
  if (type == "homogeneous") {
    // pbrt-v4 reads "preset" for homogeneous media only; a preset it knows replaces sigma_a and sigma_s.
    const std::string preset = p.string("preset", "");
    if (!preset.empty()) {
      if (const auto coefficients = scattering_preset(preset, s.where)) {
        std::tie(sigma_a, sigma_s) = *coefficients;
        for (const char* overridden : {"sigma_a", "sigma_s"})
          if (p.get(overridden, {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::blackbody}))
            ignore("MakeNamedMedium \"" + std::string(overridden) + "\" beside a \"preset\" (the preset's values are used, as in pbrt-v4)", s.where);
      } else {
        ignore("MakeNamedMedium \"preset\" \"" + preset + "\" (not one of pbrt-v4's names: sigma_a and sigma_s, or their default 1, stand in, as in pbrt-v4)", s.where);
      }
    }
  }
  const double scale = p.real("scale", 1.0);
  if (!(scale >= 0)) throw InputError(s.where, context + ": \"scale\" must be >= 0");
  const double g = medium_g(p);
  // "Le" × "Lescale" (homogeneous, uniformgrid): pbrt-v4 normalises the spectrum as a light's "L"
  // (SpectrumToPhotometric), so it imports as an area light's emission does: a shape and a luminance.
  std::optional<json> emission;
  if (const PbrtParam* le = p.get("Le", {PbrtParamType::rgb, PbrtParamType::spectrum, PbrtParamType::blackbody})) {
    const bool dark = le->type != PbrtParamType::blackbody && le->strings.empty() &&
                      std::all_of(le->numbers.begin(), le->numbers.end(), [](double v) { return v == 0; });
    const PbrtParam* le_scale = p.get("Lescale", {PbrtParamType::real});
    if (dark) {
    } else if (type == "nanovdb") {
      ignore("MakeNamedMedium \"nanovdb\" \"Le\" (pbrt-v4's NanoVDB medium emits from its \"temperature\" grid only)",
             le->where);
    } else if (le_scale && le_scale->numbers.size() > 1) {
      ignore("MakeNamedMedium \"uniformgrid\" per-voxel \"Lescale\" (Rimu's grid media emit one spectrum everywhere: "
             "imported without its emission)", le_scale->where);
    } else if (json fields = light_amount(p, "Le", "radiance", "luminance_nt", 1.0, "Lescale"); fields.contains("spectrum")) {
      emission = std::move(fields);
    }
  }
  if (type == "homogeneous") p.real("Lescale", 1.0);  // only meaningful with Le
  json medium = {{"type", "homogeneous"}, {"sigma_a", scaled(sigma_a, scale)}, {"sigma_s", scaled(sigma_s, scale)}, {"g", g}};
  if (emission) medium["emission"] = std::move(*emission);
  if (type == "uniformgrid") add_density_grid(p, medium);
  if (type == "nanovdb") add_nanovdb_grid(p, medium);
  media_defined_[name] = std::move(medium);
}

// pbrt-v4's subsurface material is a dielectric surface over a BSSRDF: photon beam diffusion tables (d'Eon & Irving
// 2011) standing in for light that scatters beneath the surface. Rimu renders what that model approximates: the
// same dielectric around a homogeneous medium, traced by a random walk (a walk is exact where diffusion is not:
// thin parts, edges, low albedo). Its scattering events are one bounce for the path's depth, as pbrt's BSSRDF is.
void PbrtConverter::subsurface_medium(PbrtParams& p, const std::string& material) {
  const SourceLocation& where = p.where();
  const std::string& context = p.context();
  double g = p.real("g", 0.0);
  const double scale = p.real("scale", 1.0);
  if (!(scale >= 0)) throw InputError(where, context + ": \"scale\" must be >= 0");
  json medium = {{"type", "homogeneous"}};
  // pbrt-v4's defaults when nothing (or a texture) is given: unbounded sRGB, per scene unit.
  const auto default_sigma_a = [&] { return unbounded_rgb({.0011, .0024, .014}, "srgb-linear", where); };
  const auto default_sigma_s = [&] { return unbounded_rgb({2.55, 3.21, 3.77}, "srgb-linear", where); };
  const std::initializer_list<PbrtParamType> spectral = {PbrtParamType::rgb, PbrtParamType::spectrum,
                                                         PbrtParamType::blackbody, PbrtParamType::texture};
  // pbrt evaluates these as textures per hit; a homogeneous medium takes one value: a texture is listed and pbrt's
  // default for the input stands in.
  const auto textured = [&](const char* key) {
    const PbrtParam* q = p.get(key, spectral);
    if (!q || q->type != PbrtParamType::texture) return false;
    ignore(context + ": texture for \"" + std::string(key) + "\" (a homogeneous medium takes one value: pbrt-v4's default is used)", q->where);
    return true;
  };
  // pbrt-v4's four ways, in its order: a named measured medium, σ_a and σ_s, reflectance and mean free path, defaults.
  const std::string name = p.string("name", "");
  const bool has_sigma_a = p.get("sigma_a", spectral) != nullptr, has_sigma_s = p.get("sigma_s", spectral) != nullptr;
  const bool has_reflectance = p.get("reflectance", spectral) != nullptr;
  if (!name.empty()) {
    const auto coefficients = scattering_preset(name, where);
    if (!coefficients) throw InputError(where, context + ": \"name\" \"" + name + "\" is not one of pbrt-v4's named media (data/media/scattering_presets.csv)");
    if (g != 0.0) ignore(context + ": \"g\" beside \"name\" (the table holds reduced scattering coefficients: g = 0, as in pbrt-v4)", where);
    g = 0.0;
    medium["sigma_a"] = scaled(coefficients->first, scale);
    medium["sigma_s"] = scaled(coefficients->second, scale);
  } else if (has_sigma_a || has_sigma_s) {
    if (!has_sigma_a || !has_sigma_s)
      throw InputError(where, context + ": give \"sigma_a\" and \"sigma_s\" together (pbrt-v4 refuses one without the other)");
    const bool textures = int(textured("sigma_a")) + int(textured("sigma_s")) > 0;
    medium["sigma_a"] = scaled(textures ? default_sigma_a() : coefficient_value(p, "sigma_a", 1.0), scale);
    medium["sigma_s"] = scaled(textures ? default_sigma_s() : coefficient_value(p, "sigma_s", 1.0), scale);
  } else if (has_reflectance) {
    // Reflectance = the surface albedo A (the total diffuse reflectance of a thick slab) and pbrt's mean free path ×
    // scale: Rimu's Chiang, Kutz & Burley 2016 parameterisation of a medium (docs/media.md). pbrt inverts A with
    // its own diffusion tables; Chiang's fit of random walks gives a somewhat different single-scattering albedo.
    // A textured reflectance stays a texture: the medium scales σ_s by it where a path enters (TexturedAlbedo).
    medium["albedo"] = reflectance(p, "reflectance", 0.5).value_or(json(0.5));
    double mfp_scale = scale;
    json mfp_shape = 1.0;
    if (const PbrtParam* mfp = p.get("mfp", spectral); mfp && !textured("mfp")) {
      if (mfp->type == PbrtParamType::rgb && mfp->numbers.size() == 3) {
        // The colour's shape (≤ 1) and its largest component as the length.
        const double largest = std::max({mfp->numbers[0], mfp->numbers[1], mfp->numbers[2]});
        if (!(largest > 0) || !(std::min({mfp->numbers[0], mfp->numbers[1], mfp->numbers[2]}) >= 0))
          throw InputError(mfp->where, context + ": \"mfp\" must be > 0 (a length)");
        PbrtParam shape = *mfp;
        for (double& v : shape.numbers) v /= largest;
        mfp_shape = rgb_reflectance(shape);
        mfp_scale *= largest;
      } else {
        ignore(context + ": \"mfp\" other than an RGB colour (a mean free path of 1 is used)", mfp->where);
      }
    }
    if (!(mfp_scale > 0)) throw InputError(where, context + ": the mean free path (\"mfp\" × \"scale\") must be > 0");
    medium["mean_free_path"] = mfp_shape;
    medium["mean_free_path_scale_m"] = std::clamp(mfp_scale, 1e-9, 1e9);
  } else {
    if (p.get("mfp", spectral)) ignore(context + ": \"mfp\" without \"reflectance\" (unused, as in pbrt-v4)", where);
    medium["sigma_a"] = scaled(default_sigma_a(), scale);
    medium["sigma_s"] = scaled(default_sigma_s(), scale);
  }
  if (!(g > -1 && g < 1)) throw InputError(where, context + ": \"g\" must be in (-1, 1)");
  if (std::abs(g) > 0.99) ignore(context + ": \"g\" beyond ±0.99 (clamped to Rimu's range)", where);
  medium["g"] = std::clamp(g, -0.99, 0.99);
  medium["boundary_material"] = material;
  medium["counts_towards_max_depth"] = false;
  std::string rimu_name = "subsurface of " + material;
  for (int n = 2; media_.contains(rimu_name); ++n) rimu_name = "subsurface of " + material + " #" + std::to_string(n);
  media_[rimu_name] = std::move(medium);
  origin("/media/" + rimu_name, where, context);
  subsurface_materials_.insert(material);
}

void PbrtConverter::add_medium_placement(const SourceLocation& where, json& medium) {
  if (ctm_moves()) ignore("a medium that moves (ActiveTransform: media stay at their start placement)", where);
  const json steps = transform_steps(world_from_object(), where);
  if (!steps.is_null()) medium["transform"] = steps;
}

double PbrtConverter::medium_g(PbrtParams& p) {
  double g = p.real("g", 0.0);
  if (!(g > -1 && g < 1)) throw InputError(p.where(), p.context() + ": \"g\" must be in (-1, 1)");
  if (std::abs(g) > 0.99) {
    ignore("MakeNamedMedium \"g\" beyond ±0.99 (clamped to Rimu's range)", p.where());
    g = std::clamp(g, -0.99, 0.99);
  }
  return g;
}

std::pair<Vec3d, Vec3d> PbrtConverter::medium_box(PbrtParams& p) {
  const auto point = [&](const char* name, Vec3d fallback) {
    const std::vector<double> v = p.numbers(name, {PbrtParamType::point3});
    if (v.empty()) return fallback;
    if (v.size() != 3) throw InputError(p.where(), p.context() + ": \"" + name + "\" takes 3 numbers");
    return Vec3d{v[0], v[1], v[2]};
  };
  const Vec3d p0 = point("p0", {0, 0, 0}), p1 = point("p1", {1, 1, 1});
  // pbrt's Bounds3f(p0, p1) takes the componentwise min and max.
  Vec3d lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[size_t(a)] = std::min(p0[size_t(a)], p1[size_t(a)]);
    hi[size_t(a)] = std::max(p0[size_t(a)], p1[size_t(a)]);
    if (!(hi[size_t(a)] > lo[size_t(a)])) throw InputError(p.where(), p.context() + ": the box \"p0\"–\"p1\" is empty");
  }
  return {lo, hi};
}

json PbrtConverter::noise_cloud_medium(PbrtParams& p) {
  json medium = {{"type", "noise_cloud"}};
  // pbrt-v4's CloudMedium::Create: unbounded spectra (default 1), "density" 1, "wispiness" 1, "frequency" 5, "g" 0.
  medium["sigma_a"] = coefficient_value(p, "sigma_a", 1.0);
  medium["sigma_s"] = coefficient_value(p, "sigma_s", 1.0);
  medium["g"] = medium_g(p);
  const std::pair<const char*, double> shape[] = {{"density", 1.0}, {"wispiness", 1.0}, {"frequency", 5.0}};
  for (const auto& [key, fallback] : shape) {
    const double v = p.real(key, fallback);
    // pbrt takes any number; a negative one clamps the density to 0 everywhere (density) or mirrors the noise
    // (frequency): refused here, as a scene error rather than a cloud that is not there.
    if (!(v >= 0) || !(v <= 1e6)) throw InputError(p.where(), p.context() + ": \"" + key + "\" must be in [0, 1e6]");
    medium[std::string(key) == "density" ? "density_scale" : key] = v;
  }
  const auto [lo, hi] = medium_box(p);
  medium["bounds_min"] = lo;
  medium["bounds_max"] = hi;
  add_medium_placement(p.where(), medium);
  return medium;
}

void PbrtConverter::add_nanovdb_grid(PbrtParams& p, json& medium) {
  const SourceLocation& where = p.where();
  const std::string filename = p.string("filename", "");
  if (filename.empty()) throw InputError(where, p.context() + ": needs \"string filename\"");
  const std::filesystem::path path = std::filesystem::absolute(p.directory() / filename);
  if (!std::filesystem::is_regular_file(path))
    throw InputError(where, p.context() + ": cannot find the NanoVDB file '" + path.string() + "'");
  // pbrt-v4 emits from the file's "temperature" grid, if it has one: Lescale × the peak-normalised black body at
  // T = (value − temperatureoffset) × temperaturescale ("temperaturecutoff" is the offset's older name), a raw
  // spectral radiance (no photometric normalisation, unlike "Le"). pbrt's radiance L renders as Rimu's L × ∫ȳ dλ
  // (its lights' spectra are normalised to ∫ȳ L = 1 per unit of scale, Rimu's area lights to ∫ȳ L = ∫ȳ dλ): the
  // scale carries that factor.
  const double le_scale = p.real("Lescale", 1.0);
  const double offset_k = p.real("temperatureoffset", p.real("temperaturecutoff", 0.0));
  const double temperature_scale = p.real("temperaturescale", 1.0);
  if (NanoVdbGrid::has_grid(path, "temperature")) {
    if (!(le_scale >= 0) || !(temperature_scale >= 0))
      throw InputError(where, p.context() + ": \"Lescale\" and \"temperaturescale\" must be >= 0");
    if (le_scale > 0)
      medium["emission"] = {{"temperature_grid", "temperature"},
                            {"temperature_offset_k", offset_k},
                            {"temperature_scale", temperature_scale},
                            {"scale", le_scale * nits_per_unit_y_ / kMaxLuminousEfficacy_lm_W}};
  } else if (p.get("Lescale", {PbrtParamType::real}) || p.get("temperatureoffset", {PbrtParamType::real}) ||
             p.get("temperaturescale", {PbrtParamType::real})) {
    ignore("MakeNamedMedium \"nanovdb\" \"Lescale\", \"temperatureoffset\", \"temperaturescale\" (the file has no "
           "\"temperature\" grid, so nothing emits, as in pbrt-v4)", where);
  }
  medium["type"] = "grid";
  // pbrt-v4 reads the grid named "density", the JSON loader's default.
  medium["file"] = path_for_document(path);
  // pbrt-v4's NanoVDBMedium samples the grid trilinearly (SampleFromVoxels of order 1).
  medium["interpolation"] = "trilinear";
  // The medium's space is the CTM at MakeNamedMedium (pbrt's renderFromMedium), after the file's own map.
  add_medium_placement(where, medium);
}

void PbrtConverter::add_density_grid(PbrtParams& p, json& medium) {
  const SourceLocation& where = p.where();
  const std::string& context = p.context();
  const int nx = p.integer("nx", 1), ny = p.integer("ny", 1), nz = p.integer("nz", 1);
  for (int n : {nx, ny, nz})
    if (n < 1 || n > 4096) throw InputError(where, context + ": \"nx\", \"ny\" and \"nz\" must be 1..4096 (they are " + std::to_string(nx) + ", " + std::to_string(ny) + ", " + std::to_string(nz) + ")");
  const PbrtParam* density = p.get("density", {PbrtParamType::real});
  if (!density) throw InputError(where, context + ": needs \"float density\" (nx·ny·nz values)");
  const uint64_t count = uint64_t(nx) * uint64_t(ny) * uint64_t(nz);
  if (density->numbers.size() != count)
    throw InputError(density->where, context + ": \"density\" has " + std::to_string(density->numbers.size()) +
                                         " values; expected nx·ny·nz = " + std::to_string(nx) + "·" + std::to_string(ny) + "·" +
                                         std::to_string(nz) + " = " + std::to_string(count));
  json values = json::array();
  for (size_t i = 0; i < density->numbers.size(); ++i) {
    const double d = density->numbers[i];
    if (!(d >= 0) || !(d <= 3.4e38))
      throw InputError(density->where, context + ": \"density\" value " + std::to_string(i) + " is " +
                                           json(d).dump() + "; densities must be finite and >= 0");
    values.push_back(d);
  }
  const auto [lo, hi] = medium_box(p);
  if (!p.numbers("temperature", {PbrtParamType::real}).empty())
    ignore("MakeNamedMedium \"uniformgrid\" \"temperature\" (Rimu reads temperatures from .nvdb grids only: "
           "imported without its emission)", where);
  for (const char* unused : {"temperaturescale", "temperatureoffset", "temperaturecutoff"}) p.real(unused, 0.0);
  medium["type"] = "grid";
  medium["voxels"] = {nx, ny, nz};
  medium["density"] = std::move(values);
  medium["bounds_min"] = lo;
  medium["bounds_max"] = hi;
  // pbrt-v4 interpolates its SampledGrid trilinearly between voxel centres (0 beyond the grid).
  medium["interpolation"] = "trilinear";
  // The medium's space is the CTM at MakeNamedMedium (pbrt's renderFromMedium).
  add_medium_placement(where, medium);
}

namespace {

// Materials through which paths cross a shape (and so change medium there) other than pbrt's "interface".
bool transmits(const json& material) {
  const json type = material.value("type", json());
  return type == "dielectric" || type == "thin_dielectric" || type == "diffuse_transmission" || type == "mix";
}

// Whether a triangle mesh is closed: every edge, with vertices welded by position, is shared by exactly two triangles
// (the seams and poles of the sphere and cylinder meshes repeat vertices at equal positions).
bool is_closed(const std::vector<Vec3d>& positions, const std::vector<uint32_t>& indices) {
  std::map<std::pair<Vec3d, Vec3d>, int> edges;
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    for (size_t k = 0; k < 3; ++k) {
      const Vec3d& a = positions[indices[t + k]];
      const Vec3d& b = positions[indices[t + (k + 1) % 3]];
      if (a == b) continue;  // a degenerate triangle's collapsed edge
      ++edges[a < b ? std::pair{a, b} : std::pair{b, a}];
    }
  if (edges.empty()) return false;
  for (const auto& [edge, count] : edges)
    if (count != 2) return false;
  return true;
}

}  // namespace

// pbrt-v4 puts a MediumInterface's interior behind the surface normal and its exterior in front; a ray takes the
// medium of the side it leaves a surface into. Rimu's media lie behind their boundary's front (a path crossing against
// the geometric normal enters the medium, crossing along it leaves). The importer makes Rimu's front pbrt's normal
// side (emit_mesh), so "inside" medium = Rimu's interior. A shape with a medium only in front
// (`MediumInterface "" "fog"`) is turned inside out (winding and normals) and bounds that medium from behind, which
// keeps pbrt's answer for every path that crosses it:
//   - an "interface" shape, open or closed (a box whose faces point inward is filled; a plane with fog in front has
//     fog on that side for paths crossing it);
//   - an opaque closed shape (a room whose walls face inward holds its fog; paths do not cross it, so it matters for
//     the camera's medium, which then starts inside it).
// Not representable, and listed: an opaque open shape with a medium in front (pbrt gives only the rays leaving that
// surface the medium; Rimu changes media where paths cross boundaries), and a transmitting material with vacuum
// behind (turning it would turn its index of refraction around too; listed in boundary_material).
bool PbrtConverter::medium_in_front_only(const std::string& material) const {
  if (!state_.inside_medium.empty() || state_.outside_medium.empty() || state_.area_light) return false;
  const auto medium = media_defined_.find(state_.outside_medium);
  return medium != media_defined_.end() && !medium->second.is_null() && materials_.contains(material);
}

bool PbrtConverter::turn_for_front_medium(const std::vector<Vec3d>& positions, const std::vector<uint32_t>& indices,
                                          const SourceLocation& where, const std::string& context) {
  const std::string material = current_material();
  if (!medium_in_front_only(material)) return false;
  if (interface_materials_.count(material)) return true;
  if (transmits(materials_.at(material))) return false;  // listed by boundary_material
  if (is_closed(positions, indices)) return true;
  ignore(context + ": an open opaque shape with a medium only in front of it (MediumInterface \"\" \"" +
             state_.outside_medium + "\"; pbrt-v4 gives the rays leaving it that medium, Rimu's media change where paths "
             "cross a closed boundary): not represented",
         where);
  return false;
}

std::optional<std::string> PbrtConverter::boundary_material(const std::string& material, const SourceLocation& where,
                                                             const std::string& context) {
  // A shape turned inside out bounds its front medium (turn_for_front_medium): that medium is now behind it.
  const bool turned = std::exchange(shape_turned_for_medium_, false);
  const std::string inside = turned ? state_.outside_medium : state_.inside_medium;
  const std::string outside = turned ? std::string() : state_.outside_medium;
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
  if (inside.empty() && !outside.empty() && !media_defined_.at(outside).is_null() && materials_.contains(material)) {
    // pbrt: vacuum inside a shape in a medium. Rimu's stack keeps the medium around inside a shape that bounds no
    // medium: the same for opaque surfaces, not for surfaces that transmit.
    if (transmits(materials_.at(material)) && !subsurface_materials_.count(material))
      ignore(context + ": vacuum inside a transmitting shape that has a medium outside (in Rimu the outside medium "
                       "continues inside it)", where);
  }
  if (inside.empty() || inside == outside) return left_out();  // no medium begins at this surface
  if (!materials_.contains(material))
    throw InputError(where, context + ": its material \"" + material + "\" is defined after this shape, which begins the "
                                      "medium \"" + inside + "\"; Rimu needs the MakeNamedMaterial of a medium's boundary "
                                      "before the shape");
  const json& medium = media_defined_.at(inside);
  if (medium.is_null()) return left_out();
  if (subsurface_materials_.count(material))
    ignore(context + ": a \"subsurface\" material around the medium \"" + inside + "\" (that medium fills the shape "
                     "instead of the material's own scattering)", where);  // a medium type Rimu does not import (listed at MakeNamedMedium)
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
  if (!camera_medium_.empty()) {
    const auto defined = media_defined_.find(camera_medium_);
    if (defined == media_defined_.end())
      throw InputError(camera_medium_where_, "Camera: the MediumInterface in effect names the medium \"" + camera_medium_ +
                                                 "\", which no MakeNamedMedium defines");
    if (defined->second.is_null()) {
      ignore("the camera's medium \"" + camera_medium_ + "\" (its type is not imported: the camera sees as if from vacuum)", camera_medium_where_);
    } else if (interior_media_.count(camera_medium_)) {
      // Some shapes bound it: the camera starts in the first Rimu medium made of it (the others are copies with
      // other boundary materials; a path leaving any of their shapes leaves it).
      media_[camera_medium_]["contains_camera"] = true;
    } else {
      // No shape has it inside: a medium around everything, with no boundary.
      json entry = defined->second;
      entry["contains_camera"] = true;
      std::string rimu_name = camera_medium_;
      for (int n = 2; media_.contains(rimu_name); ++n) rimu_name = camera_medium_ + " #" + std::to_string(n);
      media_[rimu_name] = std::move(entry);
      origin("/media/" + rimu_name, media_where_.at(camera_medium_), "MakeNamedMedium \"" + camera_medium_ + "\"");
    }
  }
  for (const auto& [name, where] : exterior_media_)
    if (name != camera_medium_ && !interior_media_.count(name) && !media_defined_.at(name).is_null())
      ignore("medium \"" + name + "\" outside shapes (MediumInterface exterior) with no shape that has it inside: Rimu's media fill "
             "closed shapes, so a medium around everything is not imported",
             where);
}

}  // namespace rimu
