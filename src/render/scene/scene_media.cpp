// The "media" section of the JSON scene format: homogeneous, voxel-grid and noise-cloud media, and the material whose
// shapes enclose each of them (docs/media.md).
#include <cctype>
#include <filesystem>

#include "render/scene/rgb_transport_inputs.h"
#include "render/scene/scene_light_emission.h"
#include "render/scene/scene_light_groups.h"
#include "render/scene/scene_load_context.h"
#include "render/scene/scene_textures.h"
#include "transport/sampling/wavelength_modes.h"
#include "transport/media/medium.h"
#include "transport/media/nanovdb_grid.h"

namespace rimu::scene_loading {
namespace {

// A spectrum scaled by a number: mean free paths given as a colour shape (≤ 1) times a length in metres.
class ScaledSpectrum final : public Spectrum {
 public:
  ScaledSpectrum(SpectrumPtr shape, double scale) : shape_(std::move(shape)), scale_(scale) {}
  double value(double nm) const override { return scale_ * shape_->value(nm); }
  double max_value() const override { return scale_ * shape_->max_value(); }
  std::string describe() const override { return std::to_string(scale_) + " × " + shape_->describe(); }

 private:
  SpectrumPtr shape_;
  double scale_;
};

// A coefficient in 1/m: any non-RGB spectral input (≥ 0, unbounded), like a conductor's k.
SpectrumPtr coefficient(const JsonCursor& c, LoadContext& context) {
  return context.spectra.parse(c, SpectrumRole::coefficient);
}

// The linear sRGB that a spectral input carries in rgb transport (lanes 0-2 of its rgb-transport form, whatever
// wraps it, e.g. a scale).
Rgb rgb_lanes(const Spectrum& rgb_transport_form) {
  const SampledSpectrum lanes = rgb_transport_form.sample(rgb_transport_lanes());
  return {lanes[0], lanes[1], lanes[2]};
}

// "voxels": [nx, ny, nz] and "density": nx·ny·nz numbers (x fastest, then y, then z), each finite and ≥ 0: the
// inline form of an .rvol file (what the pbrt importer writes).
void load_inline_density(const JsonCursor& m, int& nx, int& ny, int& nz, std::vector<float>& density) {
  const JsonCursor voxels = m.at("voxels");
  if (!voxels.is_array() || voxels.size() != 3) voxels.fail("expected [nx, ny, nz]");
  nx = voxels.at(0).integer(1, 4096);
  ny = voxels.at(1).integer(1, 4096);
  nz = voxels.at(2).integer(1, 4096);
  const JsonCursor values = m.at("density");
  const uint64_t count = uint64_t(nx) * uint64_t(ny) * uint64_t(nz);
  if (!values.is_array() || values.size() != count)
    values.fail("expected nx·ny·nz = " + std::to_string(count) + " numbers (x fastest, then y, then z)" +
                (values.is_array() ? ", found " + std::to_string(values.size()) : std::string()));
  density.resize(size_t(count));
  for (size_t i = 0; i < size_t(count); ++i) {
    const nlohmann::json& v = values.value()[i];
    const double d = v.is_number() ? v.get<double>() : -1.0;
    // Checked here, not only in GridMedium, so that the error names the value's index.
    if (!(d >= 0.0) || !(d <= 3.4e38)) values.at(i).fail("a density must be a finite number >= 0");
    density[i] = float(d);
  }
}

// A "file" ending in .nvdb (any case) is read by NanoVDB; any other is an .rvol file.
bool is_nanovdb_file(const std::string& file) {
  std::string extension = std::filesystem::path(file).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".nvdb";
}

Medium load_absorbing_medium(const JsonCursor& m, LoadContext& context) {
  const std::string type = m.at("type").choice({"homogeneous", "grid", "noise_cloud"});
  const float g = float(m.number_or("g", 0.0, -0.99, 0.99));
  const int priority = m.integer_or("priority", 0, -1000, 1000);
  // false: a subsurface walk, whose scattering events are no path vertices for max_depth (medium.h says why).
  const bool counts_towards_max_depth = m.boolean_or("counts_towards_max_depth", true);
  SpectrumPtr sigma_a, sigma_s;
  std::shared_ptr<const TexturedAlbedo> textured_albedo;
  SpectralTexturePtr surface_albedo;  // the authored albedo A, reported as the albedo feature (path_features.h)
  if (m.has("albedo")) {
    // Chiang et al. 2016: surface albedo colour (a reflectance) and mean free path colour × scale in metres.
    for (const char* key : {"sigma_a", "sigma_s"})
      if (m.has(key)) m.at(key).fail("give either albedo + mean_free_path or sigma_a + sigma_s");
    // A texture (an image, a combinator): the medium is built for a uniform grey A₀ and the texture scales its σ_s
    // per path where the path enters (TexturedAlbedo; σ_t depends on the mean free path alone).
    SpectrumPtr albedo;
    const SpectralTexturePtr albedo_texture = load_spectral_texture(m.at("albedo"), context);
    surface_albedo = albedo_texture;
    if (const auto* constant = dynamic_cast<const ConstantSpectralTexture*>(albedo_texture.get())) {
      albedo = constant->spectrum();
    } else {
      if (type != "homogeneous") m.at("albedo").fail("a textured albedo needs a homogeneous medium");
      constexpr double kBaseAlbedo = 0.5;
      albedo = std::make_shared<ConstantSpectrum>(kBaseAlbedo);
      textured_albedo = m.at("albedo").blame([&] { return std::make_shared<const TexturedAlbedo>(albedo_texture, kBaseAlbedo); });
    }
    const SpectrumPtr mfp_shape = context.spectra.parse(m.at("mean_free_path"), SpectrumRole::reflectance);
    const double scale = m.number_or("mean_free_path_scale_m", 1.0, 1e-9, 1e9);
    // value() of an rgb-transport form is the original spectrum's, so this is the spectral medium in every mode.
    const HomogeneousMedium h = chiang2016_medium(*albedo, ScaledSpectrum(mfp_shape, scale), g);
    sigma_a = h.sigma_a();
    sigma_s = h.sigma_s();
    if (context.spectra.rgb_transport()) {
      // An RGB renderer applies the parameterisation per channel to the RGB albedo and mean free path.
      const Rgb mfp = rgb_lanes(*mfp_shape);
      const RgbMediumCoefficients c =
          chiang2016_rgb_coefficients(h, rgb_lanes(*albedo), {mfp.r * scale, mfp.g * scale, mfp.b * scale});
      sigma_a = c.sigma_a;
      sigma_s = c.sigma_s;
    }
  } else {
    sigma_a = coefficient(m.at("sigma_a"), context);
    sigma_s = coefficient(m.at("sigma_s"), context);
  }
  if (type == "homogeneous") {
    m.only_keys({"type", "g", "priority", "albedo", "mean_free_path", "mean_free_path_scale_m", "sigma_a", "sigma_s",
                 "boundary_material", "index_matched", "contains_camera", "counts_towards_max_depth", "emission",
                 "light_group"});
    Medium medium(HomogeneousMedium(sigma_a, sigma_s, g), priority, counts_towards_max_depth);
    medium.set_textured_albedo(std::move(textured_albedo));
    medium.set_surface_albedo(std::move(surface_albedo));
    return medium;
  }
  if (type == "noise_cloud") {
    m.only_keys({"type", "g", "priority", "albedo", "mean_free_path", "mean_free_path_scale_m", "sigma_a", "sigma_s",
                 "boundary_material", "index_matched", "contains_camera", "counts_towards_max_depth", "emission",
                 "light_group", "density_scale", "wispiness", "frequency", "bounds_min", "bounds_max", "transform"});
    NoiseCloudShape shape;
    shape.density = float(m.number_or("density_scale", 1.0, 0.0, 1e6));
    shape.wispiness = float(m.number_or("wispiness", 1.0, 0.0, 1e3));
    shape.frequency = float(m.number_or("frequency", 5.0, 0.0, 1e6));
    const Vec3 lo = m.has("bounds_min") ? m.at("bounds_min").vec3() : Vec3{0.0f, 0.0f, 0.0f};
    const Vec3 hi = m.has("bounds_max") ? m.at("bounds_max").vec3() : Vec3{1.0f, 1.0f, 1.0f};
    std::optional<Transform> world_from_medium;
    if (m.has("transform")) world_from_medium = parse_transform(m);
    try {
      Medium medium(NoiseCloudMedium(sigma_a, sigma_s, g, shape, lo, hi, world_from_medium), priority,
                    counts_towards_max_depth);
      medium.set_surface_albedo(std::move(surface_albedo));
      return medium;
    } catch (const InputError& e) {
      m.fail(e.explanation());
    }
  }
  m.only_keys({"type", "g", "priority", "albedo", "mean_free_path", "mean_free_path_scale_m", "sigma_a", "sigma_s",
               "boundary_material", "index_matched", "file", "procedural", "resolution", "bounds_min", "bounds_max",
               "seed", "voxels", "density", "interpolation", "transform", "contains_camera", "grid",
               "counts_towards_max_depth", "emission", "light_group"});
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> density;
  const int sources = int(m.has("file")) + int(m.has("procedural")) + int(m.has("density"));
  if (sources != 1) m.fail("a grid medium takes exactly one of \"file\", \"procedural\" or \"voxels\" + \"density\"");
  const GridInterpolation interpolation = m.has("interpolation") && m.at("interpolation").choice({"voxel", "trilinear"}) == "trilinear"
                                              ? GridInterpolation::trilinear
                                              : GridInterpolation::voxel;
  std::optional<Transform> world_from_grid;
  if (m.has("transform")) world_from_grid = parse_transform(m);
  const bool nanovdb = m.has("file") && is_nanovdb_file(m.at("file").string());
  if (m.has("grid") && !nanovdb) m.at("grid").fail("\"grid\" names a grid of a .nvdb file; \"file\" names none");
  if (nanovdb) {
    // The file's active voxels and index-to-world map place the grid; a box from the scene would contradict them.
    for (const char* key : {"bounds_min", "bounds_max"})
      if (m.has(key)) m.at(key).fail("a .nvdb grid's box comes from the file; place it with \"transform\"");
    const JsonCursor file = m.at("file");
    std::shared_ptr<const NanoVdbGrid> sparse;
    try {
      sparse = NanoVdbGrid::load(context.spectra.scene_directory() / file.string(), m.string_or("grid", "density"));
    } catch (const InputError& e) {
      file.fail(e.what());  // "cloud.nvdb: ..." under the key that named the file
    }
    try {
      Medium medium(GridMedium(std::move(sparse), sigma_a, sigma_s, g, interpolation, world_from_grid), priority,
                    counts_towards_max_depth);
      medium.set_surface_albedo(std::move(surface_albedo));
      return medium;
    } catch (const InputError& e) {
      m.fail(e.explanation());
    }
  }
  if (m.has("file")) {
    const JsonCursor file = m.at("file");
    try {
      read_grid_file(context.spectra.scene_directory() / file.string(), nx, ny, nz, density);
    } catch (const InputError& e) {
      file.fail(e.what());  // "cloud.rvol: ..." under the key that named the file
    }
  } else if (m.has("density")) {
    load_inline_density(m, nx, ny, nz, density);
  } else {
    m.at("procedural").choice({"cloud"});
    nx = ny = nz = m.integer_or("resolution", 64, 1, 512);
    density = procedural_cloud_density(nx, uint32_t(m.integer_or("seed", 1, 0, 1 << 30)));
  }
  try {
    Medium medium(GridMedium(nx, ny, nz, std::move(density), m.at("bounds_min").vec3(), m.at("bounds_max").vec3(),
                             sigma_a, sigma_s, g, interpolation, world_from_grid),
                  priority, counts_towards_max_depth);
    medium.set_surface_albedo(std::move(surface_albedo));
    return medium;
  } catch (const InputError& e) {
    m.fail(e.explanation());
  }
}

// A medium's "emission": L_e as a spectrum (absolute, film units) or a spectral shape and a luminance (the
// luminance of an optically thick body of the medium), or a black body at the temperatures of a grid of the
// medium's .nvdb file.
std::shared_ptr<const MediumEmission> load_medium_emission(const JsonCursor& m, const Medium& medium,
                                                           LoadContext& context) {
  const JsonCursor e = m.at("emission");
  const SpectrumPtr& sigma_a = medium.sigma_a();
  if (!(sigma_a->max_value() > 0.0))
    e.fail("a medium emits sigma_a × its radiance: with sigma_a = 0 at every wavelength it cannot emit");
  if (!(e.is_object() && e.has("temperature_grid"))) {
    const LightSpectrum radiance = medium_emission_radiance(e, context);
    return std::make_shared<const MediumEmission>(radiance.shape(), radiance.scale());
  }
  e.only_keys({"temperature_grid", "temperature_offset_k", "temperature_scale", "scale"});
  const JsonCursor name = e.at("temperature_grid");
  if (!medium.grid() || !m.has("file") || !is_nanovdb_file(m.at("file").string()))
    name.fail("a temperature grid is read from the medium's .nvdb file: it needs a grid medium with a .nvdb \"file\"");
  if (context.spectra.rgb_transport())
    name.fail("a temperature grid's black body needs spectral transport, not --wavelengths rgb");
  std::shared_ptr<const NanoVdbGrid> temperatures;
  try {
    temperatures = NanoVdbGrid::load(context.spectra.scene_directory() / m.at("file").string(), name.string());
  } catch (const InputError& error) {
    name.fail(error.what());
  }
  std::optional<Transform> world_from_grid;
  if (m.has("transform")) world_from_grid = parse_transform(m);
  const SpectrumPtr none = std::make_shared<ConstantSpectrum>(0.0);
  // A GridMedium only for the lookup: its "density" is the temperature, placed exactly as the density grid.
  auto field = std::make_shared<const GridMedium>(std::move(temperatures), none, none, 0.0f,
                                                  medium.grid()->interpolation(), world_from_grid);
  return std::make_shared<const MediumEmission>(std::move(field), e.number_or("temperature_offset_k", 0.0, -1e6, 1e6),
                                                e.number_or("temperature_scale", 1.0, 0.0, 1e6),
                                                e.number_or("scale", 1.0, 0.0, 1e30));
}

Medium load_medium(const JsonCursor& m, LoadContext& context) {
  Medium medium = load_absorbing_medium(m, context);
  if (m.has("emission")) {
    medium.set_emission(load_medium_emission(m, medium, context), read_medium_light_group(m, context.scene));
  } else if (m.has("light_group")) {
    m.at("light_group").fail("a light group holds light: only a medium with \"emission\" has one");
  }
  return medium;
}

}  // namespace

void load_media(const JsonCursor& section, LoadContext& context) {
  if (!section.is_object()) section.fail("expected an object of medium name → medium");
  Scene& scene = context.scene;
  scene.medium_boundaries.assign(scene.materials.size(), MediumBoundary{});
  for (const auto& [name, unused] : section.value().items()) {
    const JsonCursor m = section.at(name);
    scene.media.push_back(load_medium(m, context));
    // "contains_camera": camera paths start in this medium. Without a boundary material it surrounds everything
    // (nothing ever leaves it: a scene-wide fog).
    const bool contains_camera = m.boolean_or("contains_camera", false);
    if (contains_camera) {
      if (scene.camera_medium >= 0) m.at("contains_camera").fail("only one medium can contain the camera");
      scene.camera_medium = int(scene.media.size()) - 1;
      if (!m.has("boundary_material")) {
        if (m.has("index_matched")) m.at("index_matched").fail("a medium without a boundary_material has no boundary to match");
        continue;
      }
    }
    // The shapes of the boundary material enclose this medium (closed meshes, normals pointing out).
    const JsonCursor b = m.at("boundary_material");
    const auto it = context.material_index.find(b.string());
    if (it == context.material_index.end()) b.fail("unknown material '" + b.string() + "'");
    MediumBoundary& boundary = scene.medium_boundaries[size_t(it->second)];
    if (boundary.interior_medium >= 0) b.fail("material '" + b.string() + "' already bounds another medium");
    boundary.interior_medium = int(scene.media.size()) - 1;
    boundary.index_matched = m.boolean_or("index_matched", false);
  }
}

}  // namespace rimu::scene_loading
