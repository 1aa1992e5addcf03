#include <algorithm>
#include <cmath>

#include "render/camera/camera_exposure.h"
#include "render/film/film.h"
#include "render/scene/scene_camera.h"
#include "render/scene/light_coverage.h"
#include "render/scene/photometric_units.h"
#include "render/scene/refracted_light_warning.h"
#include "render/scene/scene.h"
#include "render/scene/scene_load_context.h"
#include "render/scene/scene_sensors.h"
#include "render/scene/scene_light_groups.h"
#include "transport/lights/emission_wavelength_density.h"
#include "transport/lights/environment_light.h"
#include "transport/lights/power_light_sampler.h"
#include "transport/sampling/wavelength_modes.h"

namespace rimu {

using scene_loading::LoadContext;

TransportScene Scene::transport_view() const {
  TransportScene view;
  view.geometry = &geometry;
  view.materials = &materials;
  view.lights = &lights;
  view.light_sampler = light_sampler.get();
  view.daylight_rays = daylight_rays.get();
  view.infinite_lights = infinite_lights;
  view.scene_scale = scene_scale;
  view.passable_surfaces = std::any_of(materials.begin(), materials.end(), [](const Material& m) { return m.passes_shadow_rays(); });
  view.wavelength_density = wavelength_density.get();
  view.texture_footprints = texture_footprints;
  view.has_motion = geometry.has_motion() || camera.camera_to_world_end.has_value();
  return view;
}

std::filesystem::path default_scene_path(const SpectralLibrary& library) {
  return library.root() / "scenes" / "cornell_box" / "scene.json";
}

namespace {

void load_camera(const JsonCursor& c, Scene& scene, SpectralLibrary& library) {
  // render_job resolves "keyframes" for the frame being rendered (render/scene/camera_keyframes.h); here there is none.
  if (c.has("keyframes"))
    c.at("keyframes").fail("a camera path keyed by frame needs a frame number: render with --frame N");
  c.only_keys({"type", "from", "to", "up", "from_end", "to_end", "up_end", "vertical_fov_deg", "lens_radius",
               "focus_distance", "height", "mapping", "frame", "exposure", "white_balance"});
  // The physical camera (render/camera/camera_exposure.h): applied when the film is written.
  if (const auto exposure = c.find("exposure")) scene.settings.camera_exposure.exposure = parse_exposure(*exposure);
  if (const auto wb = c.find("white_balance"))
    scene.settings.camera_exposure.white_balance = parse_white_balance(*wb, library);
  const std::string type =
      c.has("type") ? c.at("type").choice({"pinhole", "thin_lens", "orthographic", "spherical"}) : "pinhole";
  const Vec3 from = c.at("from").vec3(), to = c.at("to").vec3();
  const Vec3 up = c.has("up") ? c.at("up").vec3() : Vec3{0, 1, 0};
  check_coordinates(from, c.at("from"), "the camera position");
  check_coordinates(to, c.at("to"), "the point the camera looks at");
  if (length(to - from) == 0.0f) c.at("to").fail("'to' equals 'from': the camera has no viewing direction");
  if (length(cross(up, to - from)) == 0.0f) c.at("up").fail("'up' is parallel to the viewing direction");
  scene.camera.camera_to_world = Transform::look_at(from, to, up);
  if (c.has("from_end") || c.has("to_end") || c.has("up_end")) {
    // A moving camera (motion blur): where it is at shutter close; a key not given keeps its value at open.
    const Vec3 from_end = c.has("from_end") ? c.at("from_end").vec3() : from;
    const Vec3 to_end = c.has("to_end") ? c.at("to_end").vec3() : to;
    const Vec3 up_end = c.has("up_end") ? c.at("up_end").vec3() : up;
    const JsonCursor where = c.has("from_end") ? c.at("from_end") : c.has("to_end") ? c.at("to_end") : c.at("up_end");
    check_coordinates(from_end, where, "the camera position at shutter close");
    check_coordinates(to_end, where, "the point the camera looks at at shutter close");
    if (length(to_end - from_end) == 0.0f)
      where.fail("'to_end' equals 'from_end': the camera has no viewing direction at shutter close");
    if (length(cross(up_end, to_end - from_end)) == 0.0f)
      where.fail("'up_end' is parallel to the viewing direction at shutter close");
    const Transform end = Transform::look_at(from_end, to_end, up_end);
    if (end.rows() != scene.camera.camera_to_world.rows()) scene.camera.camera_to_world_end = end;
  }
  if (type != "spherical")
    for (const char* key : {"mapping", "frame"})
      if (c.has(key)) c.at(key).fail(std::string("'") + key + "' applies to \"type\": \"spherical\" cameras only");
  if (type == "spherical") {
    for (const char* key : {"vertical_fov_deg", "lens_radius", "focus_distance", "height"})
      if (c.has(key)) c.at(key).fail(std::string("a spherical camera sees every direction: it has no '") + key + "'");
    scene.camera.spherical = c.has("mapping") && c.at("mapping").choice({"equirectangular", "equal_area_octahedral"}) ==
                                                     "equal_area_octahedral"
                                 ? SphericalMapping::equal_area_octahedral
                                 : SphericalMapping::equirectangular;
    if (c.has("frame")) scene.camera.spherical_frame = c.at("frame").frame();
    return;
  }
  if (type == "orthographic") {
    if (c.has("vertical_fov_deg")) c.at("vertical_fov_deg").fail("an orthographic camera has no field of view: give its 'height'");
    scene.camera.orthographic_height = float(c.at("height").number(1e-9, 1e9));
    if (c.has("lens_radius") != c.has("focus_distance")) c.fail("a lens needs both lens_radius and focus_distance");
    if (c.has("lens_radius")) {
      scene.camera.lens_radius = float(c.at("lens_radius").number(0.0, 1e6));
      scene.camera.focus_distance = float(c.at("focus_distance").number(1e-6, 1e9));
    }
    return;
  }
  if (c.has("height")) c.at("height").fail("'height' applies to \"type\": \"orthographic\" cameras only");
  scene.camera.vertical_fov_deg = float(c.number_or("vertical_fov_deg", 40.0, 1e-3, 179.0));
  if (type == "pinhole") {
    for (const char* key : {"lens_radius", "focus_distance"})
      if (c.has(key)) c.at(key).fail(std::string(key) + " applies to \"type\": \"thin_lens\" cameras only");
  } else {
    scene.camera.lens_radius = float(c.at("lens_radius").number(0.0, 1e6));
    scene.camera.focus_distance = float(c.at("focus_distance").number(1e-6, 1e9));
  }
}

void load_film(const JsonCursor& c, RenderSettings& s) {
  c.only_keys({"resolution", "response", "spectral_bins", "filter", "crop", "crop_window", "aov", "max_sample_value"});
  if (c.has("resolution")) {
    const JsonCursor r = c.at("resolution");
    if (r.size() != 2) r.fail("expected [width, height]");
    s.width = r.at(size_t(0)).integer(1, 1 << 15);
    s.height = r.at(size_t(1)).integer(1, 1 << 15);
  }
  if (const auto crop = c.find("crop")) {
    if (!crop->is_array() || crop->size() != 4) crop->fail("expected [x0, y0, x1, y1]: pixels x0 <= x < x1, y0 <= y < y1");
    PixelBounds b;
    b.x0 = crop->at(size_t(0)).integer(0, s.width - 1);
    b.y0 = crop->at(size_t(1)).integer(0, s.height - 1);
    b.x1 = crop->at(size_t(2)).integer(b.x0 + 1, s.width);
    b.y1 = crop->at(size_t(3)).integer(b.y0 + 1, s.height);
    s.crop = b;
  }
  if (const auto window = c.find("crop_window")) {
    if (c.has("crop")) window->fail("give either \"crop\" (pixels) or \"crop_window\" (fractions), not both");
    if (!window->is_array() || window->size() != 4)
      window->fail("expected [x0, y0, x1, y1]: fractions of the image, 0 <= x0 < x1 <= 1, 0 <= y0 < y1 <= 1");
    CropWindow w;
    w.x0 = window->at(size_t(0)).number(0.0, 1.0);
    w.y0 = window->at(size_t(1)).number(0.0, 1.0);
    w.x1 = window->at(size_t(2)).number(0.0, 1.0);
    w.y1 = window->at(size_t(3)).number(0.0, 1.0);
    if (!(w.x0 < w.x1 && w.y0 < w.y1)) window->fail("expected x0 < x1 and y0 < y1");
    s.crop_window = w;
  }
  s.film_response = c.string_or("response", s.film_response);
  s.spectral_bins = c.integer_or("spectral_bins", 0, 0, 471);
  if (c.has("max_sample_value")) s.max_sample_value = c.at("max_sample_value").number(Film::kMinSampleClamp, Film::kMaxSampleClamp);
  if (c.has("aov")) {
    const JsonCursor aov = c.at("aov");
    try {
      s.aovs = parse_aov_list(aov.string(), "aov");
    } catch (const InputError& e) {
      aov.fail(e.explanation());
    }
  }
  if (const auto f = c.find("filter")) {
    f->only_keys({"type", "radius", "sigma"});
    s.filter.type = f->at("type").choice({"box", "triangle", "gaussian", "blackman-harris"});
    const double default_radius = s.filter.type == "box" ? 0.5 : s.filter.type == "triangle" ? 2.0 : 1.5;
    s.filter.radius_px = float(f->number_or("radius", default_radius, 0.01, 16.0));
    if (s.filter.type != "gaussian" && f->has("sigma")) f->at("sigma").fail("sigma applies to the gaussian filter only");
    s.filter.sigma_px = float(f->number_or("sigma", 0.5, 0.01, 16.0));
  }
}

void load_integrator(const JsonCursor& c, RenderSettings& s) {
  c.only_keys({"spp", "max_depth", "russian_roulette_depth", "seed", "sampler", "wavelengths", "wavelength_density",
               "direct_lighting", "distance_sampling", "max_depth_includes_media", "equiangular", "caustics", "method",
               "merge_radius", "light_sampler", "guiding", "glossy_light_candidates", "time_limit_s", "daylit_points",
               "metropolis"});
  if (const auto d = c.find("daylit_points")) {
    const std::string mode = d->is_string() ? d->choice({"auto", "on", "off"}) : d->boolean() ? "on" : "off";
    s.daylit_points = mode == "auto" ? std::nullopt : std::optional<bool>(mode == "on");
  }
  if (const auto d = c.find("guiding")) {
    const std::string mode = d->is_string() ? d->choice({"on", "off", "mixture"}) : d->boolean() ? "on" : "off";
    s.integrator.guiding = mode != "off";
    s.integrator.guiding_mixture = mode == "mixture";
  }
  if (const auto d = c.find("light_sampler"))
    s.light_sampler = *parse_light_sampler_kind(d->choice({"bvh", "bvh-spectral", "power", "uniform"}));
  if (const auto d = c.find("wavelength_density"))
    s.wavelength_density = d->choice({"visible", "lights"}) == "lights" ? WavelengthDensityKind::lights
                                                                        : WavelengthDensityKind::visible;
  if (const auto d = c.find("distance_sampling")) {
    const std::string v = d->choice({"spectral_mis", "hero_only", "averaged", "spectral_tracking"});
    s.distance_sampling = v == "hero_only"           ? DistanceSampling::hero_only
                          : v == "averaged"          ? DistanceSampling::averaged
                          : v == "spectral_tracking" ? DistanceSampling::spectral_tracking
                                                     : DistanceSampling::spectral_mis;
  }
  s.max_depth_includes_media = c.boolean_or("max_depth_includes_media", s.max_depth_includes_media);
  if (const auto d = c.find("caustics"))
    s.integrator.caustic_light_tracing = d->choice({"path_tracing", "light_tracing"}) == "light_tracing";
  if (const auto d = c.find("method")) {
    const std::string method = d->choice({"path_tracing", "bidirectional", "vcm", "metropolis"});
    s.integrator.bidirectional = method == "bidirectional" || method == "vcm";
    s.integrator.vertex_merging = method == "vcm";
    s.integrator.metropolis = method == "metropolis";
  }
  if (const auto m = c.find("metropolis")) {
    // The Metropolis loop's settings (transport/integrators/metropolis_settings.h), used with "method": "metropolis".
    m->only_keys({"bootstrap_per_pixel", "chains", "sigma", "large_step_probability", "large_step_mis",
                  "bidirectional", "brightness_cap"});
    MetropolisSettings& ms = s.integrator.metropolis_settings;
    ms.bootstrap_per_pixel = float(m->number_or("bootstrap_per_pixel", ms.bootstrap_per_pixel, 1e-3, 1e4));
    if (const auto d = m->find("chains")) ms.chains = d->integer(1, 1 << 24);
    ms.sigma = float(m->number_or("sigma", ms.sigma, 1e-5, 0.5));
    ms.large_step_probability = float(m->number_or("large_step_probability", ms.large_step_probability, 0.0, 1.0));
    ms.large_step_mis = m->boolean_or("large_step_mis", ms.large_step_mis);
    ms.bidirectional = m->boolean_or("bidirectional", ms.bidirectional);
    ms.brightness_cap = float(m->number_or("brightness_cap", ms.brightness_cap, 0.0, 1e30));
  }
  if (const auto d = c.find("merge_radius")) s.integrator.merging.radius_m = float(d->number(1e-9, 1e9));
  if (const auto d = c.find("equiangular")) {
    const std::string v = d->choice({"points", "all", "off"});
    s.equiangular = v == "all" ? EquiangularLights::all : v == "off" ? EquiangularLights::off : EquiangularLights::points;
  }
  if (const auto sampler = c.find("sampler"))
    s.sampler = *parse_sampler_kind(sampler->choice({"sobol", "independent"}));
  if (const auto d = c.find("direct_lighting")) {
    const std::string v = d->choice({"mis", "nee_only", "bsdf_only"});
    s.integrator.direct_lighting = v == "nee_only"    ? DirectLighting::nee_only
                                   : v == "bsdf_only" ? DirectLighting::bsdf_only
                                                      : DirectLighting::mis;
  }
  if (const auto mode = c.find("wavelengths"))
    s.integrator.wavelengths = *parse_wavelength_mode(mode->choice({"hero", "single", "independent", "rgb"}));
  s.samples_per_pixel = c.integer_or("spp", s.samples_per_pixel, 1, 1 << 24);
  s.samples_per_pixel_given = c.has("spp");
  if (const auto limit = c.find("time_limit_s")) s.time_limit_s = limit->number(1e-3, 1e9);
  s.integrator.max_depth = c.integer_or("max_depth", s.integrator.max_depth, 0, 100000);
  s.integrator.russian_roulette_depth =
      c.integer_or("russian_roulette_depth", s.integrator.russian_roulette_depth, 1, 100000);
  if (const auto d = c.find("glossy_light_candidates")) {  // "auto" (0): PathIntegratorSettings::glossy_candidates_for
    if (d->is_string()) {
      d->choice({"auto"});
      s.integrator.glossy_light_candidates = 0;
    } else {
      s.integrator.glossy_light_candidates = d->integer(1, 64);
    }
  }
  s.seed = uint64_t(c.integer_or("seed", int(s.seed), 0, 2147483647));
}

}  // namespace

std::unique_ptr<Scene> load_scene(const nlohmann::json& document, const std::string& name,
                                  const std::filesystem::path& directory, SpectralLibrary& library) {
  auto scene = std::make_unique<Scene>();
  scene->source = name;
  const JsonCursor root(document, name);
  root.only_keys({"description", "camera", "film", "integrator", "spectra", "materials", "prototypes", "shapes",
                  "lights", "media", "sensors"});
  LoadContext context{*scene, SpectrumInputContext(library, directory), {}, {}, {}, {}, {}};
  if (const auto spectra = root.find("spectra")) {
    if (!spectra->is_object()) spectra->fail("expected an object of name → spectrum");
    context.spectra.set_named(*spectra);
  }
  for (const char* section : {"lights", "shapes"})
    if (root.has(section) && !root.at(section).is_array()) root.at(section).fail("expected an array");

  load_camera(root.at("camera"), *scene, library);
  if (const auto film = root.find("film")) load_film(*film, scene->settings);
  if (const auto integrator = root.find("integrator")) load_integrator(*integrator, scene->settings);
  context.spectra.set_rgb_transport(scene->settings.integrator.wavelengths == WavelengthMode::rgb);
  if (const auto materials = root.find("materials")) scene_loading::load_materials(*materials, context);
  if (const auto media = root.find("media")) scene_loading::load_media(*media, context);
  if (const auto prototypes = root.find("prototypes")) scene_loading::load_prototypes(*prototypes, context);
  if (const auto lights = root.find("lights")) scene_loading::load_lights(*lights, context);
  if (const auto shapes = root.find("shapes")) scene_loading::load_shapes(*shapes, context);
  scene_loading::finish_light_groups(*scene);
  if (const auto sensors = root.find("sensors")) load_sensors(*sensors);  // checked here; measured by render/sensors/
  // Included light definitions set it too (load_lights), as they are read.
  scene->photometric_lights = scene->photometric_lights || uses_photometric_units(document);

  // ∂p/∂u, ∂p/∂v are read only by normal and bump maps and by filtered image textures (their uv derivatives):
  // scenes without one skip their cost per hit.
  scene->geometry.set_surface_tangents(
      scene->texture_footprints ||
      std::any_of(scene->materials.begin(), scene->materials.end(), [](const Material& m) { return m.uses_tangents(); }));
  scene->geometry.commit();
  if (!context.instance_keys.empty()) {
    // Every ray starts at the camera's lens or on a surface: the box of those is what instances must see in range.
    BoundsD world;
    const Vec3 lo = scene->geometry.bounds_min(), hi = scene->geometry.bounds_max();
    if (is_finite(lo) && is_finite(hi) && lo.x <= hi.x) world.extend(lo), world.extend(hi);
    const float lens = scene->camera.lens_radius;
    for (const Transform* frame : {&scene->camera.camera_to_world,
                                   scene->camera.camera_to_world_end ? &*scene->camera.camera_to_world_end : nullptr}) {
      if (!frame) continue;
      const Vec3 eye = frame->point(Vec3{0, 0, 0});
      world.extend(eye - Vec3{lens, lens, lens});
      world.extend(eye + Vec3{lens, lens, lens});
    }
    const JsonCursor shapes = root.at("shapes");
    for (size_t i = 0; i < context.instance_keys.size(); ++i) {
      const JsonCursor where = scene_loading::instance_cursor(shapes, context.instance_keys[i]);
      if (const std::vector<Transform>* keys = scene->geometry.instance_motion_keys(i))
        for (const Transform& placement : *keys) check_instance_ray_space(world, placement, where);
      else
        check_instance_ray_space(world, scene->geometry.instance_to_world(i), where);
    }
  }
  const Vec3 extent = scene->geometry.bounds_max() - scene->geometry.bounds_min();
  scene->scene_scale = is_finite(extent) && length(extent) > 0.0f ? length(extent) : 1.0f;

  std::vector<const Light*> light_pointers;
  // Environments sample only what BSDF and phase sampling do badly wherever those are combined with light sampling
  // (EnvironmentLight::set_combined_with_bsdf_sampling says how); next-event estimation alone needs the full density.
  if (scene->settings.integrator.direct_lighting == DirectLighting::mis)
    for (const std::unique_ptr<Light>& light : scene->lights)
      if (auto* environment = dynamic_cast<EnvironmentLight*>(light.get()))
        environment->set_combined_with_bsdf_sampling(true);
  for (size_t i = 0; i < scene->lights.size(); ++i) {
    light_pointers.push_back(scene->lights[i].get());
    if (scene->lights[i]->is_infinite()) scene->infinite_lights.push_back(int(i));
  }
  const double scene_radius_m = 0.5 * double(scene->scene_scale);
  scene->light_sampler = make_light_sampler(scene->settings.light_sampler, light_pointers, scene_radius_m);
  // Daylit points: where asked, or by default where daylight enters through portals (a room's windows: the case
  // they are for; elsewhere their cost is not measured to pay). The volumetric integrator does not use them.
  // Bidirectional path tracing starts light subpaths as the same rays of daylight (also without portals: a sun's
  // rays then come from a disc around the scene), whatever the daylit points do.
  scene->settings.integrator.daylit_points = false;
  const bool daylit_points_wanted = scene->settings.daylit_points.value_or(true);
  if ((daylit_points_wanted || scene->settings.integrator.bidirectional) && !scene->has_media()) {
    const Vec3 centre = (scene->geometry.bounds_min() + scene->geometry.bounds_max()) * 0.5f;
    // The camera is where the scene is seen from: the inside of a room whose windows are portals.
    const Vec3 camera_position = scene->camera.camera_to_world.point(Vec3{0, 0, 0});
    auto daylight_rays =
        std::make_unique<DaylightRaySampler>(scene->lights, centre, float(scene_radius_m), camera_position);
    const bool points = daylit_points_wanted &&
                        (scene->settings.daylit_points.has_value() || daylight_rays->uses_portals());
    if (!daylight_rays->empty() && (points || scene->settings.integrator.bidirectional)) {
      scene->daylight_rays = std::move(daylight_rays);
      scene->settings.integrator.daylit_points = points;
    }
  }
  if (scene->settings.wavelength_density == WavelengthDensityKind::lights &&
      scene->settings.integrator.wavelengths != WavelengthMode::rgb)
    scene->wavelength_density = std::make_shared<const TabulatedWavelengthDensity>(
        emission_wavelength_density(scene->lights, PowerLightSampler(light_pointers, scene_radius_m),
                                    library.observer(StandardObserver::cie1931_2deg)));
  // Appended: the lights' own load-time warnings (a sun below the horizon) are already there.
  for (std::string& warning : light_coverage_warnings(*scene)) scene->warnings.push_back(std::move(warning));
  for (std::string& warning : refracted_light_warnings(*scene)) scene->warnings.push_back(std::move(warning));
  for (std::string& warning : unlit_medium_warnings(document, *scene)) scene->warnings.push_back(std::move(warning));
  // Zero-area triangles cannot be hit or shaded; removing them is right, but a count the user never sees would
  // hide a broken export.
  if (scene->degenerate_triangles_removed > 0)
    scene->warnings.push_back(std::to_string(scene->degenerate_triangles_removed) +
                              " degenerate triangles (zero area or not finite) were removed from the meshes");
  if (scene->vertices_without_normal > 0)
    scene->warnings.push_back(std::to_string(scene->vertices_without_normal) +
                              " mesh vertices have no normal (zero or not finite in the file): the triangles at "
                              "them are shaded flat");
  if (scene->meshes_with_normals_near_plane > 0)
    scene->warnings.push_back(std::to_string(scene->meshes_with_normals_near_plane) +
                              " meshes have shading normals in (or across) the plane of 1 % or more of their area: "
                              "on opaque surfaces paths that leave below that plane end there, which darkens them");
  return scene;
}

std::unique_ptr<Scene> load_scene(const std::filesystem::path& path, SpectralLibrary& library) {
  const nlohmann::json document = parse_json_file(path);
  return load_scene(document, path.string(), path.parent_path(), library);
}

}  // namespace rimu
