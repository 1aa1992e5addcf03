// Texture values of the JSON scene format: numbers and spectra that vary over a surface.
#include "render/scene/scene_textures.h"

#include "render/alpha_mask.h"
#include "render/float_image_texture.h"
#include "render/image_texture.h"
#include "render/rgb_transport_inputs.h"
#include "transport/spectral_texture_ops.h"

namespace rimu::scene_loading {
namespace {

// The combinator keys; an object has at most one of them.
constexpr std::initializer_list<const char*> kCombinators = {"product", "power", "mix", "direction_mix", "checkerboard"};

std::optional<std::string> combinator_of(const JsonCursor& value) {
  if (!value.is_object()) return std::nullopt;
  std::optional<std::string> found;
  for (const char* key : kCombinators)
    if (value.has(key)) {
      if (found) value.fail("give one of product, power, mix, direction_mix, checkerboard, not both " + *found + " and " + key);
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
    value.only_keys({"texture", "encoding", "invert", "scale"});
    const JsonCursor file = value.at("texture");
    const std::filesystem::path path = context.spectra.scene_directory() / file.string();
    return file.blame([&]() -> FloatTexturePtr {
      // The first channel, with the sRGB curve removed from 8/16-bit files unless told otherwise (pbrt-v4's default).
      bool srgb = default_encoding_for(path).srgb_transfer;
      if (value.has("encoding")) srgb = value.at("encoding").choice({"srgb", "linear"}) == "srgb";
      // Values as read, not clamped: roughness clamps at use, a mix's amount decides by a ≤ 0 / ≥ 1 test.
      auto values = std::make_shared<const AlphaMask>(AlphaMask::read(path, 0, srgb, false, false));
      return std::make_shared<ImageFloatTexture>(std::move(values), float(value.number_or("scale", 1.0, -1e30, 1e30)),
                                                 value.boolean_or("invert", false));
    });
  }
  const auto kind = combinator_of(value);
  if (!kind) value.fail("expected a number or an object with texture, product, mix, direction_mix or checkerboard");
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
  value.only_keys({"checkerboard", "uv_scale", "uv_offset"});
  return std::make_shared<CheckerboardFloatTexture>(std::move(a), std::move(b), uv_mapping(value));
}

SpectralTexturePtr load_spectral_texture(const JsonCursor& value, LoadContext& context) {
  if (value.is_object() && value.has("texture")) {
    value.only_keys({"texture", "colour_space", "encoding", "scale"});
    const std::filesystem::path path = context.spectra.scene_directory() / value.at("texture").string();
    const std::shared_ptr<const RgbImage> image = load_rgb_image(value, path);
    const std::string space = value.string_or("colour_space", "srgb-linear");
    if (context.spectra.rgb_transport())
      return std::make_shared<RgbLaneImageTexture>(image, RgbColourSpace::named(space),
                                                   float(value.number_or("scale", 1.0, 0.0, 1.0)));
    const auto upsampler = context.spectra.upsampler(space, value.has("colour_space") ? value.at("colour_space") : value);
    return std::make_shared<ImageTexture>(image, upsampler, float(value.number_or("scale", 1.0, 0.0, 1.0)));
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
  value.only_keys({"checkerboard", "uv_scale", "uv_offset"});
  return std::make_shared<CheckerboardSpectralTexture>(std::move(a), std::move(b), uv_mapping(value));
}

}  // namespace rimu::scene_loading
