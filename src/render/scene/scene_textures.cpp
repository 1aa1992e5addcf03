// Texture values of the JSON scene format: numbers and spectra that vary over a surface.
#include "render/scene/scene_textures.h"

#include "render/image/alpha_mask.h"
#include "render/image/float_image_texture.h"
#include "render/image/image_texture.h"
#include "render/scene/rgb_transport_inputs.h"
#include "transport/textures/procedural_texture.h"
#include "transport/textures/spectral_texture_ops.h"

namespace rimu::scene_loading {
namespace {

// The combinator keys; an object has at most one of them.
constexpr std::initializer_list<const char*> kCombinators = {"product", "power", "mix", "direction_mix", "checkerboard", "dots"};

std::optional<std::string> combinator_of(const JsonCursor& value) {
  if (!value.is_object()) return std::nullopt;
  std::optional<std::string> found;
  for (const char* key : kCombinators)
    if (value.has(key)) {
      if (found) value.fail("give one of product, power, mix, direction_mix, checkerboard, dots, not both " + *found + " and " + key);
      found = key;
    }
  return found;
}

// The two inputs of a combinator: an array of two values.
std::pair<JsonCursor, JsonCursor> operands(const JsonCursor& value, const std::string& key) {
  const JsonCursor pair = value.at(key);
  if (!pair.is_array() || pair.size() != 2) pair.fail("expected an array of two values");
  return {pair.at(size_t(0)), pair.at(size_t(1))};
}

UvMapping uv_mapping(const JsonCursor& value) {
  UvMapping m;
  if (value.has("uv_scale")) {
    const Vec2 s = value.at("uv_scale").vec2();
    m.su = s.x;
    m.sv = s.y;
  }
  if (value.has("uv_offset")) {
    const Vec2 d = value.at("uv_offset").vec2();
    m.du = d.x;
    m.dv = d.y;
  }
  return m;
}

// The mapping keys of a checkerboard, dots or image texture (docs/scene-format.md "Textures"): "mapping" uv
// (default: "uv_scale", "uv_offset"), spherical, cylindrical, planar ("planar_axes", "uv_offset") or, where
// `solid_allowed`, solid (3D); all but uv place texture space by "transform". `own_keys` are the texture's other
// keys; keys that neither it nor the chosen mapping reads are refused.
TextureMapping texture_mapping(const JsonCursor& value, std::initializer_list<const char*> own_keys, bool solid_allowed) {
  std::string kind = "uv";
  if (value.has("mapping"))
    kind = solid_allowed ? value.at("mapping").choice({"uv", "spherical", "cylindrical", "planar", "solid"})
                         : value.at("mapping").choice({"uv", "spherical", "cylindrical", "planar"});
  const auto only = [&](std::initializer_list<const char*> mapping_keys) {
    std::vector<const char*> keys(own_keys);
    keys.insert(keys.end(), mapping_keys);
    value.only_keys(keys);
  };
  if (kind == "uv") {
    only({"mapping", "uv_scale", "uv_offset"});
    return uv_mapping(value);
  }
  TextureMapping m;
  m.texture_from_world = parse_transform(value).inverse();
  if (kind == "planar") {
    only({"mapping", "transform", "planar_axes", "uv_offset"});
    m.kind = TextureMapping::Kind::planar;
    if (value.has("planar_axes")) {
      const JsonCursor axes = value.at("planar_axes");
      if (!axes.is_array() || axes.size() != 2) axes.fail("expected two directions [[x, y, z], [x, y, z]] (s and t)");
      m.planar_s = axes.at(size_t(0)).vec3();
      m.planar_t = axes.at(size_t(1)).vec3();
    }
    if (value.has("uv_offset")) m.planar_offset = value.at("uv_offset").vec2();
    return m;
  }
  only({"mapping", "transform"});
  m.kind = kind == "spherical" ? TextureMapping::Kind::spherical
                               : (kind == "cylindrical" ? TextureMapping::Kind::cylindrical : TextureMapping::Kind::solid);
  return m;
}

// "filter" (point, bilinear, trilinear, ewa; default bilinear, as pbrt-v4's) and "max_anisotropy" (EWA's bound on
// the footprint ellipse's eccentricity, default 8) of an image texture. Reading one marks the scene as needing hit
// footprints (ray differentials).
TextureFilterOptions texture_filter(const JsonCursor& value, LoadContext& context) {
  TextureFilterOptions options;
  if (value.has("filter")) {
    const std::string name = value.at("filter").choice({"point", "bilinear", "trilinear", "ewa"});
    options.filter = name == "point"       ? TextureFilter::point
                     : name == "bilinear"  ? TextureFilter::bilinear
                     : name == "trilinear" ? TextureFilter::trilinear
                                           : TextureFilter::ewa;
  }
  options.max_anisotropy = float(value.number_or("max_anisotropy", 8.0, 1.0, 1e6));
  context.scene.texture_footprints = true;
  return options;
}

NoiseOctaves noise_octaves(const JsonCursor& value) {
  return {value.integer_or("octaves", 8, 0, 30), float(value.number_or("roughness", 0.5, -10.0, 10.0))};
}

// Any finite number inside a combinator (a scale may exceed 1, an offset be negative).
FloatTexturePtr operand_float(const JsonCursor& value, LoadContext& context) {
  return load_float_texture(value, context, -1e30, 1e30);
}

}  // namespace

FloatTexturePtr load_float_texture(const JsonCursor& value, LoadContext& context, double min, double max) {
  if (value.is_number()) return std::make_shared<ConstantFloatTexture>(float(value.number(min, max)));
  if (!value.is_object())
    value.fail("expected a number or a float texture ({\"texture\": \"map.png\"}, {\"mix\": [a, b], \"amount\": t}, ...)");
  if (value.has("texture")) {
    const TextureMapping mapping =
        texture_mapping(value, {"texture", "encoding", "invert", "scale", "filter", "max_anisotropy"}, false);
    const TextureFilterOptions filter = texture_filter(value, context);
    const JsonCursor file = value.at("texture");
    const std::filesystem::path path = context.spectra.scene_directory() / file.string();
    return file.blame([&]() -> FloatTexturePtr {
      // The first channel, with the sRGB curve removed from 8/16-bit files unless told otherwise (pbrt-v4's default).
      bool srgb = default_encoding_for(path).srgb_transfer;
      if (value.has("encoding")) srgb = value.at("encoding").choice({"srgb", "linear"}) == "srgb";
      // Values as read, not clamped: roughness clamps at use, a mix's amount decides by a ≤ 0 / ≥ 1 test.
      auto values = std::make_shared<const AlphaMask>(AlphaMask::read(path, 0, srgb, false, false));
      return std::make_shared<ImageFloatTexture>(values, float(value.number_or("scale", 1.0, -1e30, 1e30)),
                                                 value.boolean_or("invert", false), mapping, filter);
    });
  }
  if (value.has("noise")) {
    const std::string noise = value.at("noise").choice({"fbm", "wrinkled", "windy"});
    if (noise == "windy")
      value.only_keys({"noise", "transform"});
    else
      value.only_keys({"noise", "octaves", "roughness", "transform"});
    const auto kind = noise == "fbm" ? NoiseFloatTexture::Kind::fbm
                                     : (noise == "wrinkled" ? NoiseFloatTexture::Kind::wrinkled : NoiseFloatTexture::Kind::windy);
    return std::make_shared<NoiseFloatTexture>(kind, noise_octaves(value), parse_transform(value).inverse());
  }
  const auto kind = combinator_of(value);
  if (!kind) value.fail("expected a number or an object with texture, noise, product, mix, direction_mix, checkerboard or dots");
  const auto [a_value, b_value] = operands(value, *kind);
  if (*kind == "power") {
    value.only_keys({"power"});
    return std::make_shared<PowerFloatTexture>(operand_float(a_value, context), float(b_value.number()));
  }
  FloatTexturePtr a = operand_float(a_value, context), b = operand_float(b_value, context);
  if (*kind == "product") {
    value.only_keys({"product"});
    return std::make_shared<ProductFloatTexture>(std::move(a), std::move(b));
  }
  if (*kind == "mix") {
    value.only_keys({"mix", "amount"});
    FloatTexturePtr amount = value.has("amount") ? operand_float(value.at("amount"), context) : std::make_shared<ConstantFloatTexture>(0.5f);
    return std::make_shared<MixFloatTexture>(std::move(a), std::move(b), std::move(amount));
  }
  if (*kind == "direction_mix") {
    value.only_keys({"direction_mix", "direction"});
    const JsonCursor direction = value.at("direction");
    return direction.blame([&]() -> FloatTexturePtr {
      return std::make_shared<DirectionMixFloatTexture>(std::move(a), std::move(b), direction.vec3());
    });
  }
  if (*kind == "dots") return std::make_shared<DotsFloatTexture>(std::move(a), std::move(b), texture_mapping(value, {"dots"}, false));
  return std::make_shared<CheckerboardFloatTexture>(std::move(a), std::move(b), texture_mapping(value, {"checkerboard"}, true));
}

SpectralTexturePtr load_spectral_texture(const JsonCursor& value, LoadContext& context) {
  if (value.is_object() && value.has("texture")) {
    const TextureMapping mapping = texture_mapping(
        value, {"texture", "colour_space", "encoding", "scale", "invert", "filter", "max_anisotropy"}, false);
    const TextureFilterOptions filter = texture_filter(value, context);
    const std::filesystem::path path = context.spectra.scene_directory() / value.at("texture").string();
    const std::shared_ptr<const RgbImage> image = load_rgb_image(value, path);
    const std::string space = value.string_or("colour_space", "srgb-linear");
    // Scale, then invert, on the texel RGB before it is upsampled (pbrt-v4's order; render/image/image_texture.h).
    const float scale = float(value.number_or("scale", 1.0, 0.0, 1e30));
    const bool invert = value.boolean_or("invert", false);
    SpectralTexturePtr texture;
    if (context.spectra.rgb_transport()) {
      texture = std::make_shared<RgbLaneImageTexture>(image, RgbColourSpace::named(space), scale, invert);
    } else {
      const auto upsampler = context.spectra.upsampler(space, value.has("colour_space") ? value.at("colour_space") : value);
      texture = std::make_shared<ImageTexture>(image, upsampler, scale, invert, filter);
    }
    if (mapping.is_identity_uv()) return texture;
    return std::make_shared<MappedSpectralTexture>(std::move(texture), mapping);
  }
  if (value.is_object() && value.has("noise")) {
    value.at("noise").choice({"marble"});
    value.only_keys({"noise", "octaves", "roughness", "scale", "variation", "transform"});
    MarbleParameters marble{noise_octaves(value), float(value.number_or("scale", 1.0)), float(value.number_or("variation", 0.2))};
    // pbrt-v4's ramp colours are linear sRGB; rgb transport carries them as they are.
    auto upsampler = context.spectra.rgb_transport() ? nullptr : context.spectra.upsampler("srgb-linear", value);
    return std::make_shared<MarbleSpectralTexture>(marble, parse_transform(value).inverse(), std::move(upsampler));
  }
  const auto kind = combinator_of(value);
  if (!kind) return std::make_shared<ConstantSpectralTexture>(context.spectra.parse(value, SpectrumRole::reflectance));
  if (*kind == "power") value.at("power").fail("\"power\" is a float texture; a reflectance cannot be raised to a power");
  const auto [a_value, b_value] = operands(value, *kind);
  SpectralTexturePtr a = load_spectral_texture(a_value, context);
  if (*kind == "product") {
    value.only_keys({"product"});
    return std::make_shared<ProductSpectralTexture>(std::move(a), operand_float(b_value, context));
  }
  SpectralTexturePtr b = load_spectral_texture(b_value, context);
  if (*kind == "mix") {
    value.only_keys({"mix", "amount"});
    FloatTexturePtr amount = value.has("amount") ? operand_float(value.at("amount"), context) : std::make_shared<ConstantFloatTexture>(0.5f);
    return std::make_shared<MixSpectralTexture>(std::move(a), std::move(b), std::move(amount));
  }
  if (*kind == "direction_mix") {
    value.only_keys({"direction_mix", "direction"});
    const JsonCursor direction = value.at("direction");
    return direction.blame([&]() -> SpectralTexturePtr {
      return std::make_shared<DirectionMixSpectralTexture>(std::move(a), std::move(b), direction.vec3());
    });
  }
  if (*kind == "dots") return std::make_shared<DotsSpectralTexture>(std::move(a), std::move(b), texture_mapping(value, {"dots"}, false));
  return std::make_shared<CheckerboardSpectralTexture>(std::move(a), std::move(b), texture_mapping(value, {"checkerboard"}, true));
}

}  // namespace rimu::scene_loading
