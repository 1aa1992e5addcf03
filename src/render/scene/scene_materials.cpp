// The "materials" section of the JSON scene format.
#include <cmath>
#include <map>
#include <set>

#include "render/image/image_texture.h"
#include "render/image/rgb_normal_map.h"
#include "render/scene/hair_absorption.h"
#include "render/scene/rgb_transport_inputs.h"
#include "render/scene/scene_load_context.h"
#include "render/scene/scene_textures.h"
#include "spectral/library/optical_constants.h"
#include "transport/sampling/bit_mixing.h"
#include "transport/textures/float_texture.h"
#include "transport/textures/shading_normal_map.h"
#include "transport/textures/spectral_texture.h"

namespace rimu::scene_loading {
namespace {

SpectralTexturePtr reflectance_texture(const JsonCursor& value, LoadContext& context) {
  return load_spectral_texture(value, context);
}

// Roughness in [0, 1] (perceptual: alpha = roughness²; see transport/bsdfs/microfacet.h).
float roughness_of(const JsonCursor& m) { return float(m.number_or("roughness", 0.0, 0.0, 1.0)); }

// Whether any of the roughness keys `<prefix>roughness`, `<prefix>roughness_u`, `<prefix>roughness_v` holds a
// texture (an object) rather than a number (prefix "conductor_" for the coated conductor's metal).
bool textured_roughness(const JsonCursor& m, const std::string& prefix = "") {
  for (const char* key : {"roughness", "roughness_u", "roughness_v"})
    if (m.has(prefix + key) && !m.at(prefix + key).is_number()) return true;
  return false;
}

// The roughness along one tangent (`axis` "_u" or "_v") as a texture: `<prefix>roughness<axis>` if given, else
// `<prefix>roughness`, else 0.
FloatTexturePtr roughness_texture(const JsonCursor& m, const std::string& axis, LoadContext& context,
                                  const std::string& prefix = "") {
  for (const std::string& key : {prefix + "roughness" + axis, prefix + "roughness"})
    if (m.has(key)) return load_float_texture(m.at(key), context, 0.0, 1.0);
  return std::make_shared<ConstantFloatTexture>(0.0f);
}

// A conductor's complex index: "metal" (a named metal) or "n" and "k".
ComplexIorSpectra conductor_ior_of(const JsonCursor& m, LoadContext& context) {
  ComplexIorSpectra ior;
  if (m.has("metal")) {
    for (const char* key : {"n", "k"})
      if (m.has(key)) m.at(key).fail("give either metal or n and k, not both");
    const JsonCursor metal = m.at("metal");
    ior = metal.blame([&] { return conductor_ior(context.spectra.library(), metal.string()); });
  } else {
    // Rgb transport point-samples n and k at its lanes' nominal wavelengths (render/scene/rgb_transport_inputs.h).
    ior.n = context.spectra.parse_spectral(m.at("n"), SpectrumRole::ior);
    // k ≥ 0 and unbounded, like an emission; but RGB would be upsampled (and scaled) as light, so refuse it here.
    const JsonCursor k = m.at("k");
    if (k.is_object() && k.has("rgb")) k.at("rgb").fail("an extinction coefficient cannot be given as RGB");
    ior.k = context.spectra.parse_spectral(k, SpectrumRole::emission);
  }
  return ior;
}

// The coat's index (default 1.5, pbrt-v4's and a typical lacquer's).
SpectrumPtr coat_ior_of(const JsonCursor& m, LoadContext& context) {
  return m.has("coat_ior") ? context.spectra.parse(m.at("coat_ior"), SpectrumRole::ior) : std::make_shared<ConstantSpectrum>(1.5);
}

// The coat's roughness and slab: "roughness", "thickness" (mean free paths), "albedo" (a reflectance, textures
// allowed), "g", and the walk's "max_depth" and "samples" (pbrt-v4's defaults 10 and 1).
CoatLayer coat_layer_of(const JsonCursor& m, LoadContext& context) {
  CoatLayer layer;
  if (m.has("roughness") && !m.at("roughness").is_number())
    layer.roughness_texture = load_float_texture(m.at("roughness"), context, 0.0, 1.0);
  else
    layer.roughness = roughness_of(m);
  layer.thickness = float(m.number_or("thickness", 0.0, 0.0, 1e6));
  if (m.has("albedo")) layer.albedo = reflectance_texture(m.at("albedo"), context);
  layer.g = float(m.number_or("g", 0.0, -0.99, 0.99));
  layer.walk.max_depth = int(m.number_or("max_depth", 10, 1, 1000));
  layer.walk.samples = int(m.number_or("samples", 1, 1, 1000));
  for (const char* key : {"max_depth", "samples"})
    if (m.has(key) && m.at(key).number() != std::floor(m.at(key).number())) m.at(key).fail("expected a whole number");
  return layer;
}

// Materials by name, built on first use so that a mix may name materials that come after it in the section.
class MaterialResolver {
 public:
  MaterialResolver(const JsonCursor& section, LoadContext& context) : section_(section), context_(context) {}
  std::shared_ptr<const Material> named(const std::string& name, const JsonCursor& where);
  LoadContext& context() { return context_; }

 private:
  const JsonCursor& section_;
  LoadContext& context_;
  std::map<std::string, std::shared_ptr<const Material>> built_;
  std::set<std::string> in_progress_;
};

Material load_material(const JsonCursor& m, LoadContext& context, MaterialResolver& resolver);

// {"type": "hair"}: the fibre's absorption from one of "sigma_a" (per unit fibre radius), "reflectance" (the
// colour, Chiang et al.'s inversion) or "eumelanin"/"pheomelanin" (concentrations), else eumelanin 1.3 (pbrt-v4's
// brown default); "eta", "beta_m", "beta_n", "alpha" (degrees) with pbrt-v4's defaults 1.55, 0.3, 0.3, 2.
Material load_hair(const JsonCursor& m, LoadContext& context) {
  m.only_keys({"type", "sigma_a", "reflectance", "eumelanin", "pheomelanin", "eta", "beta_m", "beta_n", "alpha"});
  HairParameters parameters;
  parameters.eta = float(m.number_or("eta", 1.55, 1.0));
  parameters.beta_m = float(m.number_or("beta_m", 0.3, 1e-3, 1.0));
  parameters.beta_n = float(m.number_or("beta_n", 0.3, 1e-3, 1.0));
  parameters.alpha_deg = float(m.number_or("alpha", 2.0, -45.0, 45.0));
  const bool melanin = m.has("eumelanin") || m.has("pheomelanin");
  if (int(m.has("sigma_a")) + int(m.has("reflectance")) + int(melanin) > 1)
    (m.has("sigma_a") ? m.at("sigma_a") : m.at("reflectance"))
        .fail("give one of sigma_a, reflectance or eumelanin/pheomelanin, not several");
  if (m.has("reflectance")) {
    SpectrumPtr colour = context.spectra.parse(m.at("reflectance"), SpectrumRole::reflectance);
    return m.blame([&] { return Material(HairMaterial::from_reflectance(std::move(colour), parameters)); });
  }
  SpectrumPtr sigma_a;
  if (m.has("sigma_a")) {
    const JsonCursor value = m.at("sigma_a");
    if (value.is_object() && value.has("rgb"))
      value.at("rgb").fail("give sigma_a as a spectrum; for a colour use reflectance or eumelanin/pheomelanin");
    sigma_a = context.spectra.parse(value, SpectrumRole::coefficient);
  } else {
    const double eumelanin = melanin ? m.number_or("eumelanin", 0.0, 0.0) : 1.3;
    const double pheomelanin = m.number_or("pheomelanin", 0.0, 0.0);
    sigma_a = context.spectra.transport_form(melanin_sigma_a(context.spectra.library(), eumelanin, pheomelanin),
                                             SpectrumRole::coefficient);
  }
  return m.blame([&] { return Material(HairMaterial(std::move(sigma_a), parameters)); });
}

// {"type": "mix", "materials": ["a", "b"], "amount": a}: per hit "b" with probability a, else "a" (MixMaterial).
Material load_mix(const JsonCursor& m, MaterialResolver& resolver, uint32_t salt) {
  m.only_keys({"type", "materials", "amount"});
  const JsonCursor names = m.at("materials");
  if (!names.is_array() || names.size() != 2) names.fail("expected an array of two material names");
  auto first = resolver.named(names.at(size_t(0)).string(), names.at(size_t(0)));
  auto second = resolver.named(names.at(size_t(1)).string(), names.at(size_t(1)));
  FloatTexturePtr amount = m.has("amount") ? load_float_texture(m.at("amount"), resolver.context(), 0.0, 1.0)
                                           : std::make_shared<ConstantFloatTexture>(0.5f);
  return MixMaterial(std::move(first), std::move(second), std::move(amount), salt);
}

std::shared_ptr<const Material> MaterialResolver::named(const std::string& name, const JsonCursor& where) {
  if (const auto found = built_.find(name); found != built_.end()) return found->second;
  if (!section_.has(name)) where.fail("no material named \"" + name + "\" in /materials");
  if (!in_progress_.insert(name).second) where.fail("mix materials refer to each other in a loop through \"" + name + "\"");
  auto material = std::make_shared<const Material>(load_material(section_.at(name), context_, *this));
  in_progress_.erase(name);
  return built_[name] = material;
}

Material load_material_kind(const JsonCursor& m, LoadContext& context, MaterialResolver& resolver) {
  const std::string type = m.at("type").choice({"diffuse", "conductor", "dielectric", "thin_dielectric", "coated_diffuse",
                                                    "diffuse_transmission", "coated_conductor", "mix", "hair", "measured"});
  // Each mix decorrelates its choice from other mixes' by its own salt: its key path, hashed.
  if (type == "mix") {
    uint32_t salt = 0;
    for (const char c : m.path()) salt = hash32(salt ^ uint8_t(c));
    return load_mix(m, resolver, salt);
  }
  SpectralLibrary& library = context.spectra.library();
  if (type == "diffuse") {
    m.only_keys({"type", "normal_map", "displacement", "reflectance"});
    return DiffuseMaterial(reflectance_texture(m.at("reflectance"), context));
  }
  if (type == "conductor") {
    m.only_keys({"type", "normal_map", "displacement", "metal", "n", "k", "reflectance", "roughness", "roughness_u", "roughness_v"});
    const bool textured = textured_roughness(m);
    if (m.has("reflectance")) {
      // pbrt-v4's artist-friendly conductor: the normal-incidence reflectance instead of n and k.
      for (const char* key : {"metal", "n", "k"})
        if (m.has(key)) m.at(key).fail("give either reflectance or metal or n and k, not several");
      SpectralTexturePtr reflectance = load_spectral_texture(m.at("reflectance"), context);
      return m.blame([&] {
        return Material(ConductorMaterial::from_reflectance(std::move(reflectance), roughness_texture(m, "_u", context),
                                                            roughness_texture(m, "_v", context)));
      });
    }
    const ComplexIorSpectra ior = conductor_ior_of(m, context);
    if (textured)
      return m.blame([&] {
        return Material(ConductorMaterial(ior, roughness_texture(m, "_u", context), roughness_texture(m, "_v", context)));
      });
    const float r = roughness_of(m);
    const float ru = float(m.number_or("roughness_u", r, 0.0, 1.0)), rv = float(m.number_or("roughness_v", r, 0.0, 1.0));
    return m.blame([&] { return Material(ConductorMaterial(ior, ru, rv)); });
  }
  if (type == "dielectric" || type == "thin_dielectric") {
    const bool thin = type == "thin_dielectric";
    if (thin)
      m.only_keys({"type", "normal_map", "displacement", "ior", "glass", "transmittance"});  // a thin sheet is smooth (pbrt-v4 has no rough one either)
    else
      m.only_keys({"type", "normal_map", "displacement", "ior", "glass", "roughness", "diffuse_entry"});
    SpectrumPtr ior;
    if (m.has("glass")) {
      if (m.has("ior")) m.at("ior").fail("give either glass or ior, not both");
      const JsonCursor glass = m.at("glass");
      ior = context.spectra.transport_form(glass.blame([&] { return dielectric_ior(library, glass.string()); }),
                                           SpectrumRole::ior);
    } else {
      ior = context.spectra.parse(m.at("ior"), SpectrumRole::ior);
    }
    if (thin) {
      // A tinted pane: the glass's internal transmittance at normal incidence (a reflectance-like 0-1 spectrum).
      SpectrumPtr tint = m.has("transmittance") ? context.spectra.parse(m.at("transmittance"), SpectrumRole::reflectance)
                                                : nullptr;
      return m.blame([&] { return Material(ThinDielectricMaterial(ior, std::move(tint))); });
    }
    // The boundary of a subsurface medium: light enters it diffusely (DielectricBsdf, "Diffuse entry").
    const bool diffuse_entry = m.boolean_or("diffuse_entry", false);
    return m.blame([&] {
      DielectricMaterial dielectric = [&] {
        if (!textured_roughness(m)) return DielectricMaterial(ior, roughness_of(m));
        FloatTexturePtr roughness = roughness_texture(m, "", context);
        return DielectricMaterial(ior, roughness, roughness);
      }();
      if (diffuse_entry) dielectric.use_diffuse_entry();
      return Material(std::move(dielectric));
    });
  }
  if (type == "diffuse_transmission") {
    m.only_keys({"type", "normal_map", "displacement", "reflectance", "transmittance", "scale"});
    // pbrt-v4's defaults: 0.25 each.
    SpectralTexturePtr reflectance = m.has("reflectance") ? reflectance_texture(m.at("reflectance"), context)
                                                          : std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(0.25));
    SpectralTexturePtr transmittance = m.has("transmittance") ? reflectance_texture(m.at("transmittance"), context)
                                                              : std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(0.25));
    const float scale = float(m.number_or("scale", 1.0, 0.0));
    return m.blame([&] { return Material(DiffuseTransmissionMaterial(std::move(reflectance), std::move(transmittance), scale)); });
  }
  if (type == "hair") return load_hair(m, context);
  if (type == "measured") {
    // {"type": "measured", "file": "x.bsdf"}: a measured BRDF of the RGL database (pbrt-v4's `measured`).
    m.only_keys({"type", "normal_map", "displacement", "file"});
    const JsonCursor file = m.at("file");
    const std::filesystem::path path = (context.spectra.scene_directory() / file.string()).lexically_normal();
    MeasuredBrdfPtr& brdf = context.measured_brdfs[path];
    if (!brdf) brdf = file.blame([&] { return std::make_shared<const MeasuredBrdf>(MeasuredBrdf::read(path)); });
    return MeasuredMaterial(brdf);
  }
  if (type == "coated_conductor") {
    m.only_keys({"type", "normal_map", "displacement", "coat_ior", "roughness", "thickness", "albedo", "g", "max_depth", "samples", "metal", "n", "k",
                 "reflectance", "conductor_roughness", "conductor_roughness_u", "conductor_roughness_v"});
    const SpectrumPtr coat = coat_ior_of(m, context);
    // The metal's roughness: numbers, or float textures along either tangent (then all three keys may be either).
    const bool textured_metal = textured_roughness(m, "conductor_");
    float ru = 0.0f, rv = 0.0f;
    FloatTexturePtr ru_texture, rv_texture;
    if (textured_metal) {
      ru_texture = roughness_texture(m, "_u", context, "conductor_");
      rv_texture = roughness_texture(m, "_v", context, "conductor_");
    } else {
      const float r = float(m.number_or("conductor_roughness", 0.0, 0.0, 1.0));
      ru = float(m.number_or("conductor_roughness_u", r, 0.0, 1.0));
      rv = float(m.number_or("conductor_roughness_v", r, 0.0, 1.0));
    }
    const CoatLayer layer = coat_layer_of(m, context);
    const auto textured = [&](CoatedConductorMaterial material) {
      return textured_metal ? std::move(material).with_conductor_roughness(ru_texture, rv_texture) : std::move(material);
    };
    if (m.has("reflectance")) {
      // pbrt-v4's artist metal under the coat, as the conductor's "reflectance".
      for (const char* key : {"metal", "n", "k"})
        if (m.has(key)) m.at(key).fail("give either reflectance or metal or n and k, not several");
      SpectralTexturePtr reflectance = load_spectral_texture(m.at("reflectance"), context);
      return m.blame([&] { return Material(textured(CoatedConductorMaterial(coat, std::move(reflectance), ru, rv, layer))); });
    }
    const ComplexIorSpectra ior = conductor_ior_of(m, context);
    return (m.has("coat_ior") ? m.at("coat_ior") : m).blame([&] {
      return Material(textured(CoatedConductorMaterial(coat, ior, ru, rv, layer)));
    });
  }
  m.only_keys({"type", "normal_map", "displacement", "reflectance", "coat_ior", "roughness", "thickness", "albedo", "g", "max_depth", "samples"});
  const SpectrumPtr coat = coat_ior_of(m, context);
  SpectralTexturePtr reflectance = reflectance_texture(m.at("reflectance"), context);
  const CoatLayer layer = coat_layer_of(m, context);
  // The material checks that the coat index is ≥ 1 everywhere; its error is reported at coat_ior.
  return (m.has("coat_ior") ? m.at("coat_ior") : m).blame([&] {
    return Material(CoatedDiffuseMaterial(std::move(reflectance), coat, layer));
  });
}

// "normal_map": an RGB image in tangent space, a file name or {"image": file, "encoding": "linear"|"srgb"} (read
// linearly unless it says "srgb": pbrt-v4's convention for normal maps, whose values are vectors, not colours; the
// pbrt importer says "srgb" where pbrt-v4's reader decodes the file as sRGB all the same), or "displacement": a
// float texture (a bump map, in scene units along the normal); not both, and not on a mix (its materials' own apply).
std::shared_ptr<const ShadingNormalModifier> normal_modifier_of(const JsonCursor& m, LoadContext& context) {
  if (m.has("normal_map") && m.has("displacement"))
    m.at("displacement").fail("a material takes a \"normal_map\" or a \"displacement\", not both");
  if (m.has("normal_map")) {
    const JsonCursor value = m.at("normal_map");
    bool srgb = false;
    if (value.is_object()) {
      value.only_keys({"image", "encoding"});
      if (value.has("encoding")) srgb = value.at("encoding").choice({"srgb", "linear"}) == "srgb";
    } else if (!value.is_string()) {
      value.fail("expected an image file name or {\"image\": \"normals.png\", \"encoding\": \"linear\"}");
    }
    const JsonCursor file = value.is_object() ? value.at("image") : value;
    const std::filesystem::path path = context.spectra.scene_directory() / file.string();
    return file.blame([&] {
      auto image = std::make_shared<const RgbImage>(RgbImage::read(path, ImageEncoding{"srgb-linear", srgb}));
      return ShadingNormalModifier::normal_map(std::make_shared<const RgbNormalMap>(std::move(image)));
    });
  }
  if (m.has("displacement")) {
    context.scene.texture_footprints = true;  // the bump's differencing step follows the footprint
    return ShadingNormalModifier::bump(load_float_texture(m.at("displacement"), context, -1e30, 1e30));
  }
  return nullptr;
}

Material load_material(const JsonCursor& m, LoadContext& context, MaterialResolver& resolver) {
  Material material = load_material_kind(m, context, resolver);
  material.set_normal_modifier(normal_modifier_of(m, context));
  return material;
}

}  // namespace

void load_materials(const JsonCursor& section, LoadContext& context) {
  if (!section.is_object()) section.fail("expected an object of material name → material");
  MaterialResolver resolver(section, context);
  for (const auto& [name, unused] : section.value().items()) {
    context.scene.materials.push_back(*resolver.named(name, section));
    context.scene.material_names.push_back(name);
    context.material_index[name] = int(context.scene.materials.size()) - 1;
  }
}

}  // namespace rimu::scene_loading
