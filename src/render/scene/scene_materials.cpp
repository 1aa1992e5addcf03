// The "materials" section of the JSON scene format.
#include <cmath>

#include "render/image_texture.h"
#include "render/rgb_transport_inputs.h"
#include "render/scene/scene_load_context.h"
#include "spectral/optical_constants.h"
#include "transport/spectral_texture.h"

namespace rimu::scene_loading {
namespace {

// A reflectance: any spectral input, or {"texture": "file.png", "colour_space": ..., "encoding": ..., "scale": k}.
SpectralTexturePtr reflectance_texture(const JsonCursor& value, LoadContext& context) {
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
  return std::make_shared<ConstantSpectralTexture>(context.spectra.parse(value, SpectrumRole::reflectance));
}

// Roughness in [0, 1] (perceptual: alpha = roughness²; see transport/microfacet.h).
float roughness_of(const JsonCursor& m) { return float(m.number_or("roughness", 0.0, 0.0, 1.0)); }

template <typename F>
auto with_key(const JsonCursor& where, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    if (!e.where().key.empty()) throw;
    where.fail(e.explanation());
  }
}

// A conductor's complex index: "metal" (a named metal) or "n" and "k".
ComplexIorSpectra conductor_ior_of(const JsonCursor& m, LoadContext& context) {
  ComplexIorSpectra ior;
  if (m.has("metal")) {
    for (const char* key : {"n", "k"})
      if (m.has(key)) m.at(key).fail("give either metal or n and k, not both");
    const JsonCursor metal = m.at("metal");
    ior = with_key(metal, [&] { return conductor_ior(context.spectra.library(), metal.string()); });
  } else {
    // Rgb transport point-samples n and k at its lanes' nominal wavelengths (render/rgb_transport_inputs.h).
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

Material load_material(const JsonCursor& m, LoadContext& context) {
  const std::string type = m.at("type").choice({"diffuse", "conductor", "dielectric", "thin_dielectric", "coated_diffuse",
                                                    "diffuse_transmission", "coated_conductor"});
  SpectralLibrary& library = context.spectra.library();
  if (type == "diffuse") {
    m.only_keys({"type", "reflectance"});
    return DiffuseMaterial(reflectance_texture(m.at("reflectance"), context));
  }
  if (type == "conductor") {
    m.only_keys({"type", "metal", "n", "k", "roughness", "roughness_u", "roughness_v"});
    const ComplexIorSpectra ior = conductor_ior_of(m, context);
    const float r = roughness_of(m);
    const float ru = float(m.number_or("roughness_u", r, 0.0, 1.0)), rv = float(m.number_or("roughness_v", r, 0.0, 1.0));
    return with_key(m, [&] { return Material(ConductorMaterial(ior, ru, rv)); });
  }
  if (type == "dielectric" || type == "thin_dielectric") {
    const bool thin = type == "thin_dielectric";
    if (thin)
      m.only_keys({"type", "ior", "glass"});  // a thin sheet is smooth (pbrt-v4 has no rough one either)
    else
      m.only_keys({"type", "ior", "glass", "roughness"});
    SpectrumPtr ior;
    if (m.has("glass")) {
      if (m.has("ior")) m.at("ior").fail("give either glass or ior, not both");
      const JsonCursor glass = m.at("glass");
      ior = context.spectra.transport_form(with_key(glass, [&] { return dielectric_ior(library, glass.string()); }),
                                           SpectrumRole::ior);
    } else {
      ior = context.spectra.parse(m.at("ior"), SpectrumRole::ior);
    }
    if (thin) return with_key(m, [&] { return Material(ThinDielectricMaterial(ior)); });
    const float roughness = roughness_of(m);
    return with_key(m, [&] { return Material(DielectricMaterial(ior, roughness)); });
  }
  if (type == "diffuse_transmission") {
    m.only_keys({"type", "reflectance", "transmittance", "scale"});
    // pbrt-v4's defaults: 0.25 each.
    SpectralTexturePtr reflectance = m.has("reflectance") ? reflectance_texture(m.at("reflectance"), context)
                                                          : std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(0.25));
    SpectralTexturePtr transmittance = m.has("transmittance") ? reflectance_texture(m.at("transmittance"), context)
                                                              : std::make_shared<ConstantSpectralTexture>(std::make_shared<ConstantSpectrum>(0.25));
    const float scale = float(m.number_or("scale", 1.0, 0.0));
    return with_key(m, [&] { return Material(DiffuseTransmissionMaterial(std::move(reflectance), std::move(transmittance), scale)); });
  }
  if (type == "coated_conductor") {
    m.only_keys({"type", "coat_ior", "roughness", "thickness", "albedo", "g", "max_depth", "samples", "metal", "n", "k",
                 "conductor_roughness", "conductor_roughness_u", "conductor_roughness_v"});
    const SpectrumPtr coat = coat_ior_of(m, context);
    const ComplexIorSpectra ior = conductor_ior_of(m, context);
    const float r = float(m.number_or("conductor_roughness", 0.0, 0.0, 1.0));
    const float ru = float(m.number_or("conductor_roughness_u", r, 0.0, 1.0));
    const float rv = float(m.number_or("conductor_roughness_v", r, 0.0, 1.0));
    const CoatLayer layer = coat_layer_of(m, context);
    return with_key(m.has("coat_ior") ? m.at("coat_ior") : m,
                    [&] { return Material(CoatedConductorMaterial(coat, ior, ru, rv, layer)); });
  }
  m.only_keys({"type", "reflectance", "coat_ior", "roughness", "thickness", "albedo", "g", "max_depth", "samples"});
  const SpectrumPtr coat = coat_ior_of(m, context);
  SpectralTexturePtr reflectance = reflectance_texture(m.at("reflectance"), context);
  const CoatLayer layer = coat_layer_of(m, context);
  // The material checks that the coat index is ≥ 1 everywhere; its error is reported at coat_ior.
  return with_key(m.has("coat_ior") ? m.at("coat_ior") : m,
                  [&] { return Material(CoatedDiffuseMaterial(std::move(reflectance), coat, layer)); });
}

}  // namespace

void load_materials(const JsonCursor& section, LoadContext& context) {
  if (!section.is_object()) section.fail("expected an object of material name → material");
  for (const auto& [name, unused] : section.value().items()) {
    context.scene.materials.push_back(load_material(section.at(name), context));
    context.scene.material_names.push_back(name);
    context.material_index[name] = int(context.scene.materials.size()) - 1;
  }
}

}  // namespace rimu::scene_loading
