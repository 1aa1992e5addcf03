// A loaded scene: geometry in Embree, materials, lights, camera and render settings.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/camera/camera.h"
#include "render/camera/camera_exposure.h"
#include "render/scene/embree_scene.h"
#include "render/film/film_tile.h"
#include "render/output/aov_channels.h"
#include "spectral/library/spectral_library.h"
#include "transport/lights/light.h"
#include "transport/lights/light_sampler.h"
#include "transport/lights/daylight_ray_sampler.h"
#include "transport/bsdfs/material.h"
#include "transport/integrators/path_integrator.h"
#include "transport/integrators/volumetric_path_integrator.h"

namespace rimu {

/// A pixel filter as the scene describes it (render/film/pixel_filter.h builds it).
struct FilterSettings {
  std::string type = "gaussian";  ///< box, triangle, gaussian, blackman-harris
  float radius_px = 1.5f;
  float sigma_px = 0.5f;
};

/// Which density camera paths draw their wavelengths from (the "integrator" section's "wavelength_density").
enum class WavelengthDensityKind {
  visible,  ///< the closed-form visible density, ≈ the sum of the CIE colour-matching functions (the default)
  lights,   ///< the scene's emission through each CIE curve, with a defensive share (transport/lights/emission_wavelength_density.h)
};

/// How to render: what the scene's "film" and "integrator" sections say, before command-line overrides.
struct RenderSettings {
  int width = 256, height = 256;
  int samples_per_pixel = 16;
  bool samples_per_pixel_given = false;  ///< the scene wrote "integrator.spp" (the cap of its time budget)
  /// integrator "time_limit_s": render whole passes until this much render time is spent (render/time_budget.h);
  /// samples_per_pixel is then the maximum if the scene gives it, else there is none.
  std::optional<double> time_limit_s;
  uint64_t seed = 1;
  SamplerKind sampler = SamplerKind::sobol;  ///< the "integrator" section's "sampler"
  PathIntegratorSettings integrator;
  /// integrator "daylit_points": on, off, or (nullopt, "auto", the default) on where daylight enters through portals
  /// (docs/transport.md, "Daylit points"); the loader resolves it into integrator.daylit_points.
  std::optional<bool> daylit_points;
  DistanceSampling distance_sampling = DistanceSampling::spectral_mis;  ///< media only (integrator.distance_sampling)
  /// media only (integrator.max_depth_includes_media): medium scattering events count towards max_depth, as in
  /// pbrt-v4's volpath
  bool max_depth_includes_media = false;
  /// media only (integrator.equiangular): which lights equiangular sampling aims at in homogeneous media
  /// (docs/media.md)
  EquiangularLights equiangular = EquiangularLights::points;
  LightSamplerKind light_sampler = LightSamplerKind::bvh;  ///< integrator.light_sampler (transport/lights/light_sampler.h)
  WavelengthDensityKind wavelength_density = WavelengthDensityKind::visible;
  std::string film_response = "xyz";  ///< xyz, xyz10, camera:<name>, camera-xyz:<name>
  int spectral_bins = 0;              ///< 0 = no spectral framebuffer
  /// film "max_sample_value": the sample clamp (Film::set_max_sample_value; docs/rendering.md, "Sample clamp").
  std::optional<double> max_sample_value;
  FilterSettings filter;
  CameraExposureSettings camera_exposure;  ///< the camera's "exposure" and "white_balance" (film units if absent)
  /// film "crop": render only these pixels of the width × height image (the default of `rimu --crop`).
  std::optional<PixelBounds> crop;
  /// film "crop_window": the same as fractions of the image (pbrt's "cropwindow"), turned into pixels at the
  /// resolution the render uses, so that `rimu --resolution` keeps the same part of the picture. At most one of
  /// crop and crop_window is set.
  std::optional<CropWindow> crop_window;
  /// film "aov": the feature layers every render of the scene writes ("albedo,normal", "all"; `rimu --aov` replaces
  /// them; render/output/aov_channels.h).
  AovSelection aovs;
};

/// Everything the renderer needs, owned in one place. Immutable after loading; shared by all render threads.
struct Scene {
  std::string source;  ///< the scene file, for messages and metadata
  EmbreeScene geometry;
  std::vector<Material> materials;
  std::vector<std::string> material_names;
  std::vector<std::unique_ptr<Light>> lights;
  std::vector<std::string> light_names;  ///< per light: its "name", else where it was defined ("/lights/2")
  /// The light groups' names ("light_group" keys, in order of first use, then "ungrouped" for the lights without
  /// one); Light::light_group() indexes it. Empty when no light names a group: the film then has no group layers.
  std::vector<std::string> light_groups;
  std::unique_ptr<LightSampler> light_sampler;
  /// Rays of the distant lights through the apertures, for daylit points (transport/lights/daylight_ray_sampler.h);
  /// nullptr without a distant light.
  std::unique_ptr<DaylightRaySampler> daylight_rays;
  /// Load-time warnings (render_job prints them): e.g. lights the light sampler starves (render/scene/light_coverage.h).
  std::vector<std::string> warnings;
  std::vector<int> infinite_lights;
  CameraSettings camera;
  RenderSettings settings;
  float scene_scale = 1.0f;              ///< bounding-box diagonal (m)
  size_t degenerate_triangles_removed = 0;
  /// Meshes with shading normals in (or across) the plane of 1 % or more of their area (a warning: see
  /// TriangleMesh::normals_near_plane_area_share)
  size_t meshes_with_normals_near_plane = 0;
  /// Vertices whose normal was zero or not finite in their file (a warning: their triangles are shaded flat)
  size_t vertices_without_normal = 0;
  /// Some light is given in photometric units (render/scene/photometric_units.h), inline or through "include":
  /// `rimu` meters the display image of such a scene.
  bool photometric_lights = false;
  /// Some material reads an image texture or a bump map: its hits need ray differentials and ∂p/∂u, ∂p/∂v
  /// (TransportScene::texture_footprints); false spares every other scene that cost.
  bool texture_footprints = false;
  std::vector<Medium> media;                      ///< the "media" section (empty: the surface integrator is used)
  std::vector<MediumBoundary> medium_boundaries;  ///< per material: the medium its shapes enclose
  int camera_medium = -1;                         ///< the medium marked "contains_camera", −1: none
  bool has_media() const { return !media.empty(); }
  /// Built at load for WavelengthDensityKind::lights (not in rgb mode, whose lanes are fixed); null otherwise.
  std::shared_ptr<const TabulatedWavelengthDensity> wavelength_density;

  /// The non-owning view the integrator works on.
  TransportScene transport_view() const;
};

/// Loads a JSON scene (docs/scene-format.md). Every error is an InputError naming the file and the key path
/// (or line, for malformed JSON). Geometry is built into Embree before this returns.
std::unique_ptr<Scene> load_scene(const std::filesystem::path& path, SpectralLibrary& library);
/// The same from an already parsed document; relative paths resolve against `directory`.
std::unique_ptr<Scene> load_scene(const nlohmann::json& document, const std::string& name,
                                  const std::filesystem::path& directory, SpectralLibrary& library);
/// The embedded default scene: the measured Cornell box (data/scenes/cornell_box/scene.json).
std::filesystem::path default_scene_path(const SpectralLibrary& library);

}  // namespace rimu
