// rimu.Library.render: a scene file rendered into a numpy array (height × width × 3, the film's channels: CIE XYZ
// for the default "xyz" response, camera RGB for a camera film), with the scene's exposure and white balance.
#include <pybind11/stl.h>

#include <optional>

#include "bindings.h"
#include "render/camera/camera_exposure.h"
#include "render/film/film.h"
#include "render/film/render_size.h"
#include "render/renderer.h"
#include "render/scene/scene.h"
#include "spectral/error.h"

namespace rimu::python {
namespace {

// The scene's "film.filter" as the renderer's pixel filter (the same mapping rimu's render job uses).
PixelFilter filter_of(const FilterSettings& f) {
  if (f.type == "box") return PixelFilter::box(f.radius_px);
  if (f.type == "blackman-harris") return PixelFilter::blackman_harris(f.radius_px);
  return PixelFilter::gaussian(f.radius_px, f.sigma_px);
}

py::array_t<float> render_scene(SpectralLibrary& library, const std::string& scene_path, std::optional<long long> width,
                                std::optional<long long> height, std::optional<long long> samples_per_pixel,
                                std::optional<uint64_t> seed, long long threads,
                                std::optional<double> max_sample_value) {
  // Every number is checked before the scene is loaded, against the limits `rimu` applies to its options.
  if (samples_per_pixel) check_render_count(*samples_per_pixel, 1, kMaxSamplesPerPixel, argument("samples_per_pixel"));
  if (threads != 0) check_render_count(threads, 1, kMaxRenderThreads, argument("threads"));
  if (max_sample_value && !Film::valid_sample_clamp(*max_sample_value))
    throw InputError(argument("max_sample_value"),
                     std::string("expected a number from ") + Film::sample_clamp_range() + " (the sample clamp), got " +
                         std::to_string(*max_sample_value));
  const std::unique_ptr<Scene> scene = for_argument("scene", [&] {
    return load_scene(scene_path.empty() ? default_scene_path(library) : std::filesystem::path(scene_path), library);
  });
  RenderSettings& s = scene->settings;
  std::tie(s.width, s.height) =
      resolution_keeping_aspect(s.width, s.height, width, height, argument("width"), argument("height"));
  if (samples_per_pixel) s.samples_per_pixel = int(*samples_per_pixel);
  if (seed) s.seed = *seed;
  Film film({s.width, s.height, std::nullopt, 0}, SpectralResponse::from_spec(library, s.film_response));
  film.set_output_transform(film_output_transform(s.camera_exposure, film.response(), library));
  film.set_max_sample_value(max_sample_value ? max_sample_value : s.max_sample_value);
  RenderOptions options;
  options.samples_per_pixel = s.samples_per_pixel;
  options.threads = int(threads);
  options.seed = s.seed;
  options.sampler = s.sampler;
  {
    py::gil_scoped_release release;  // other Python threads may run while the tiles render
    render(*scene, filter_of(s.filter), film, options);
  }
  py::array_t<float> image({s.height, s.width, 3});
  auto out = image.mutable_unchecked<3>();
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const std::array<double, 3> v = film.output_value(x, y);
      for (int c = 0; c < 3; ++c) out(y, x, c) = float(v[size_t(c)]);
    }
  return image;
}

}  // namespace

void bind_render(py::module_& m) {
  auto lib = py::reinterpret_borrow<py::class_<SpectralLibrary>>(m.attr("Library"));
  lib.def("render", &render_scene, py::arg("scene") = "", py::arg("width") = py::none(), py::arg("height") = py::none(),
          py::arg("samples_per_pixel") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = 0,
          py::arg("max_sample_value") = py::none(),
          "Renders a scene file (default: the Cornell box) and returns the film as a float32 array of shape "
          "(height, width, 3): CIE XYZ for the default film, after the scene's exposure and white balance. "
          "width or height given alone keeps the scene's aspect ratio (the other is scaled and rounded); both at "
          "most 32768. threads=0 uses every core. max_sample_value: the sample clamp (the scene's film "
          "\"max_sample_value\" by default; docs/rendering.md, \"Sample clamp\"). "
          "Deterministic for a given seed and sample count.\n\n"
          "Example: image = lib.render('data/scenes/cornell_box/scene.json', width=32, samples_per_pixel=4)");
}

}  // namespace rimu::python
