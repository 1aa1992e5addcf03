// pbrt-v4 textures → Rimu's texture values (docs/scene-format.md "Textures", docs/pbrt-import.md): float textures
// (constant, scale, mix, directionmix, checkerboard, dots, fbm, wrinkled, windy, imagemap) and the spectrum ones
// (scale, mix, directionmix, checkerboard, dots, marble) with every 2D mapping and the 3D one. Default operands
// are pbrt-v4's: scale tex 1 × scale 1; mix tex1 0, tex2 1, amount 0.5; directionmix tex1 0, tex2 1, dir (0, 1, 0);
// checkerboard tex1 1, tex2 0.
#include <algorithm>
#include <cmath>
#include <functional>

#include "render/scene/pbrt/pbrt_converter.h"

namespace rimu {
namespace {

// pbrt-v4's 2D texture mapping parameters as Rimu's mapping keys (docs/scene-format.md "Textures"). `placement` is
// the texture's CTM as transform steps (null for the identity), asked for only by the mappings that use it; an unknown mapping is listed and uv is used.
void texture_mapping(PbrtParams& tp, json& value, PbrtConverter& converter, const SourceLocation& where,
                     const std::function<json()>& placement) {
  const std::string mapping = tp.string("mapping", "uv");
  if (mapping == "spherical" || mapping == "cylindrical" || mapping == "planar") {
    value["mapping"] = mapping;
    if (json steps = placement(); !steps.is_null()) value["transform"] = steps;
    if (mapping == "planar") {
      const auto axis = [&](const char* name, std::vector<double> fallback) {
        std::vector<double> v = tp.numbers(name, {PbrtParamType::vector3});
        if (v.empty()) v = std::move(fallback);
        if (v.size() != 3) throw InputError(where, std::string("texture mapping \"planar\": \"") + name + "\" must be one vector3");
        return v;
      };
      value["planar_axes"] = {axis("v1", {1, 0, 0}), axis("v2", {0, 1, 0})};
      value["uv_offset"] = {tp.real("udelta", 0.0), tp.real("vdelta", 0.0)};
    }
    return;
  }
  if (mapping != "uv") converter.ignore("texture mapping \"" + mapping + "\" (uv is used)", where);
  value["uv_scale"] = {tp.real("uscale", 1.0), tp.real("vscale", 1.0)};
  value["uv_offset"] = {tp.real("udelta", 0.0), tp.real("vdelta", 0.0)};
}

// pbrt-v4's TextureMapping3D: the texture's CTM.
void solid_mapping(json& value, const json& placement) {
  value["mapping"] = "solid";
  if (!placement.is_null()) value["transform"] = placement;
}

// The roughness (ω) of a noise texture: within ±10, so that ω^octaves stays a float.
double noise_roughness(PbrtParams& tp, const std::string& texture_name, const SourceLocation& where) {
  const double omega = tp.real("roughness", 0.5);
  if (!(std::abs(omega) <= 10.0))
    throw InputError(where, "Texture \"" + texture_name + "\": \"roughness\" must be within ±10 (the weight ratio of successive octaves)");
  return omega;
}

// The octave count of a noise texture: pbrt-v4 loops over none for 0; a negative count has no meaning.
int octaves(PbrtParams& tp, const std::string& texture_name, const SourceLocation& where) {
  const int n = tp.integer("octaves", 8);
  if (n < 0 || n > 30)
    throw InputError(where, "Texture \"" + texture_name + "\": \"octaves\" must be 0-30 (each doubles the frequency), not " + std::to_string(n));
  return n;
}

// Texture lookups allowed for one parameter: far more than a hand-made or exported texture graph uses, and few
// enough that a graph unfolding exponentially is refused in milliseconds instead of running for ever.
constexpr int kMaxTextureLookups = 4096;

}  // namespace

void PbrtConverter::image_mapping(PbrtParams& tp, json& value, const PbrtTexture& texture) {
  const PbrtStatement& ts = texture.statement;
  json mapping = json::object();
  texture_mapping(tp, mapping, *this, ts.where, [&] { return transform_steps(texture.world_from_texture, ts.where); });
  // Plain uv (pbrt's default) writes no keys, so that the document stays as short as the file.
  if (mapping.contains("mapping") || mapping["uv_scale"] != json{1.0, 1.0} || mapping["uv_offset"] != json{0.0, 0.0})
    value.update(mapping);
  // pbrt-v4's MIP-map filter (default bilinear, Rimu's too: written only when another is asked for).
  const std::string filter = tp.string("filter", "bilinear");
  if (filter == "point" || filter == "trilinear" || filter == "ewa")
    value["filter"] = filter;
  else if (filter != "bilinear")
    ignore("imagemap \"filter\" \"" + filter + "\" (not point, bilinear, trilinear or ewa: bilinear is used)", ts.where);
  if (const double anisotropy = tp.real("maxanisotropy", 8.0); anisotropy != 8.0) {
    if (anisotropy >= 1.0 && anisotropy <= 1e6)
      value["max_anisotropy"] = anisotropy;
    else
      ignore("imagemap \"maxanisotropy\" outside [1, 1e6] (8 is used)", ts.where);
  }
  if (const std::string wrap = tp.string("wrap", "repeat"); wrap != "repeat")
    ignore("imagemap \"wrap\" \"" + wrap + "\" (Rimu's image textures repeat)", ts.where);
}

void PbrtConverter::count_texture_lookup(const std::string& name, int depth, const SourceLocation& where) {
  if (depth == 0) texture_lookups_ = 0;
  if (++texture_lookups_ > kMaxTextureLookups)
    throw InputError(where, "Texture \"" + name + "\": the parameter's textures unfold into more than " +
                                std::to_string(kMaxTextureLookups) +
                                " texture lookups (textures that use the same texture in several operands, nested)");
}

json PbrtConverter::float_value(PbrtParams& p, const std::string& name, double fallback, int depth) {
  const PbrtParam* q = p.get(name, {PbrtParamType::real, PbrtParamType::texture});
  if (!q) return fallback;
  if (q->type == PbrtParamType::real) return q->numbers.at(0);
  if (auto v = float_texture_value(q->strings.at(0), q->where, depth)) return *v;
  return fallback;
}

std::optional<json> PbrtConverter::float_texture_value(const std::string& texture_name, const SourceLocation& where, int depth) {
  // Constant everywhere (constant, scale/mix of constants): a number. This also checks the name and kind.
  if (const auto constant = constant_float_texture(texture_name, where, depth)) return json(*constant);
  if (depth > 64) throw InputError(where, "Texture \"" + texture_name + "\": textures nested more than 64 deep");
  const PbrtTexture& texture = textures_.at(texture_name);
  const PbrtStatement& ts = texture.statement;
  const std::string& cls = texture.texture_class;
  PbrtParams tp(*this, ts, "Texture \"" + texture_name + "\"");
  const auto placement = [&] { return transform_steps(texture.world_from_texture, ts.where); };
  if (cls == "scale") return json{{"product", {float_value(tp, "tex", 1.0, depth + 1), float_value(tp, "scale", 1.0, depth + 1)}}};
  if (cls == "mix")
    return json{{"mix", {float_value(tp, "tex1", 0.0, depth + 1), float_value(tp, "tex2", 1.0, depth + 1)}},
                {"amount", float_value(tp, "amount", 0.5, depth + 1)}};
  if (cls == "directionmix") {
    std::vector<double> dir = tp.numbers("dir", {PbrtParamType::vector3});
    if (dir.empty()) dir = {0.0, 1.0, 0.0};
    if (dir.size() != 3) throw InputError(ts.where, "Texture \"" + texture_name + "\": \"dir\" must be one vector3");
    const auto world = texture.world_from_texture.vector({dir[0], dir[1], dir[2]});
    return json{{"direction_mix", {float_value(tp, "tex1", 0.0, depth + 1), float_value(tp, "tex2", 1.0, depth + 1)}},
                {"direction", {world[0], world[1], world[2]}}};
  }
  if (cls == "checkerboard") {
    const int dimension = tp.integer("dimension", 2);
    if (dimension != 2 && dimension != 3)
      throw InputError(ts.where, "Texture \"" + texture_name + "\": \"dimension\" must be 2 or 3, not " + std::to_string(dimension));
    json value = {{"checkerboard", {float_value(tp, "tex1", 1.0, depth + 1), float_value(tp, "tex2", 0.0, depth + 1)}}};
    if (dimension == 3)
      solid_mapping(value, placement());
    else
      texture_mapping(tp, value, *this, ts.where, placement);
    return value;
  }
  if (cls == "dots") {
    // pbrt-v4 hands its "inside" texture to the dots texture's outside slot and "outside" to the inside one (its
    // Create passes them in the constructor's other order): imported as pbrt renders it.
    json value = {{"dots", {float_value(tp, "outside", 0.0, depth + 1), float_value(tp, "inside", 1.0, depth + 1)}}};
    texture_mapping(tp, value, *this, ts.where, placement);
    return value;
  }
  if (cls == "fbm" || cls == "wrinkled" || cls == "windy") {
    json value = {{"noise", cls}};
    if (cls != "windy") {
      value["octaves"] = octaves(tp, texture_name, ts.where);
      value["roughness"] = noise_roughness(tp, texture_name, ts.where);
    }
    if (json steps = placement(); !steps.is_null()) value["transform"] = steps;
    return value;
  }
  if (cls == "imagemap") {
    const std::string filename = tp.string("filename", "");
    if (filename.empty()) throw InputError(ts.where, "Texture \"" + texture_name + "\": needs \"string filename\"");
    const std::filesystem::path path = std::filesystem::absolute(ts.directory / filename);
    if (!std::filesystem::is_regular_file(path))
      throw InputError(ts.where, "Texture \"" + texture_name + "\": cannot find the image '" + path.string() + "'");
    // The first channel (pbrt-v4's MIPMap texel for Float).
    json value = {{"texture", path_for_document(path)}, {"encoding", image_encoding(tp, path, ts.where)}};
    if (tp.boolean("invert", false)) value["invert"] = true;
    if (const double scale = tp.real("scale", 1.0); scale != 1.0) value["scale"] = scale;
    image_mapping(tp, value, texture);
    return value;
  }
  ignore("float Texture class \"" + cls + "\" (the parameter's default is used)", ts.where);
  return std::nullopt;
}

bool PbrtConverter::read_as_srgb_regardless(const std::filesystem::path& image) {
  std::string extension = image.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return extension != ".exr" && extension != ".pfm" && extension != ".hdr" && extension != ".png" && extension != ".qoi";
}

std::string PbrtConverter::image_encoding(PbrtParams& tp, const std::filesystem::path& image, const SourceLocation& where) {
  std::string extension = image.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  // pbrt-v4's Image::Read decides, not the texture: a float image (EXR, PFM, HDR) is linear; a PNG takes the
  // texture's "encoding" (its default is sRGB for a .png name); every other file (TGA, JPEG, PPM, BMP, ...) is read
  // by stb_image as 8-bit sRGB whatever "encoding" says (the texture's default, "linear", never reaches it).
  const std::string encoding = tp.string("encoding", "sRGB");  // read (and so not listed) for every format
  if (extension == ".exr" || extension == ".pfm" || extension == ".hdr") return "linear";
  if (read_as_srgb_regardless(image)) {
    if (encoding != "sRGB")
      ignore("imagemap encoding \"" + encoding + "\" of a " + extension + " image (pbrt-v4 reads it as sRGB too)", where);
    return "srgb";
  }
  if (encoding == "linear") return "linear";
  if (encoding != "sRGB") ignore("imagemap encoding \"" + encoding + "\" (sRGB is used)", where);
  return "srgb";
}

std::optional<json> PbrtConverter::spectrum_combinator(const PbrtTexture& texture, int depth) {
  const PbrtStatement& ts = texture.statement;
  const std::string& cls = texture.texture_class;
  if (cls != "scale" && cls != "mix" && cls != "directionmix" && cls != "checkerboard" && cls != "dots" && cls != "marble")
    return std::nullopt;
  PbrtParams tp(*this, ts, "Texture \"" + ts.strings[0] + "\"");
  const auto placement = [&] { return transform_steps(texture.world_from_texture, ts.where); };
  const auto spectral = [&](const char* key, double fallback) { return reflectance(tp, key, fallback, depth).value_or(json(fallback)); };
  if (cls == "scale") return json{{"product", {spectral("tex", 1.0), float_value(tp, "scale", 1.0, depth)}}};
  if (cls == "mix")
    return json{{"mix", {spectral("tex1", 0.0), spectral("tex2", 1.0)}},
                {"amount", float_value(tp, "amount", 0.5, depth)}};
  if (cls == "directionmix") {
    std::vector<double> dir = tp.numbers("dir", {PbrtParamType::vector3});
    if (dir.empty()) dir = {0.0, 1.0, 0.0};
    if (dir.size() != 3) throw InputError(ts.where, "Texture \"" + ts.strings[0] + "\": \"dir\" must be one vector3");
    const auto world = texture.world_from_texture.vector({dir[0], dir[1], dir[2]});
    return json{{"direction_mix", {spectral("tex1", 0.0), spectral("tex2", 1.0)}},
                {"direction", {world[0], world[1], world[2]}}};
  }
  if (cls == "marble") {
    json value = {{"noise", "marble"}, {"octaves", octaves(tp, ts.strings[0], ts.where)}, {"roughness", noise_roughness(tp, ts.strings[0], ts.where)},
                  {"scale", tp.real("scale", 1.0)}, {"variation", tp.real("variation", 0.2)}};
    if (json steps = placement(); !steps.is_null()) value["transform"] = steps;
    return value;
  }
  if (cls == "dots") {
    json value = {{"dots", {spectral("outside", 0.0), spectral("inside", 1.0)}}};  // swapped as pbrt-v4 does (above)
    texture_mapping(tp, value, *this, ts.where, placement);
    return value;
  }
  const int dimension = tp.integer("dimension", 2);
  if (dimension != 2 && dimension != 3)
    throw InputError(ts.where, "Texture \"" + ts.strings[0] + "\": \"dimension\" must be 2 or 3, not " + std::to_string(dimension));
  json value = {{"checkerboard", {spectral("tex1", 1.0), spectral("tex2", 0.0)}}};
  if (dimension == 3)
    solid_mapping(value, placement());
  else
    texture_mapping(tp, value, *this, ts.where, placement);
  return value;
}

json PbrtConverter::roughness_value(const json& pbrt_roughness, bool remap) const {
  if (pbrt_roughness.is_number()) {
    const double r = pbrt_roughness.get<double>();
    const double alpha = remap ? std::sqrt(std::max(0.0, r)) : std::max(0.0, r);
    return std::min(1.0, std::sqrt(alpha));
  }
  return json{{"power", {pbrt_roughness, remap ? 0.25 : 0.5}}};
}

}  // namespace rimu
