// Hero-wavelength unbiasedness: spectral MIS over four lanes (docs/transport.md) must estimate the same image as
// tracing one wavelength per path. The scene is chosen so that every lane sees different transport:
// - the light is CIE F11, a tri-band fluorescent lamp whose power sits in narrow mercury/phosphor lines
//   (CIE 15:2004 Table T.6): neighbouring wavelengths differ by an order of magnitude;
// - the walls are ColorChecker patches (Ohta 1997 spectra, data/spectra/reflectances) with steep edges: red,
//   blue and green;
// - a smooth sphere of Schott N-SF11 glass (strong dispersion, Sellmeier coefficients from the Schott catalogue)
//   stands between the camera and the light: a specular refraction has a different direction for every
//   wavelength, so after it only the hero lane can continue (the partners' pdfs are zero and spectral MIS must
//   give the hero the whole weight). The floor below it receives a dispersive caustic.
// Both modes are unbiased for every pixel, so their means agree within the error bars of the paired difference
// (integration_support.h). Both renders use the same seed: the single-wavelength render then traces the same hero
// paths, and its estimate is correlated with the hero render's (common random numbers), which shrinks the
// variance of the difference without biasing it. The paired-difference error bar Σ(a_i − b_i)²/N² stays valid
// because pixels remain independent of each other.
#include <doctest/doctest.h>

#include <cmath>

#include "integration_support.h"

using namespace rimu;
using namespace rimu::test;

namespace {

constexpr const char* kColorChecker = "spectra/reflectances/colorchecker_classic_ohta1997_5nm.csv";

nlohmann::json patch(const char* column) {
  return {{"type", "diffuse"}, {"reflectance", {{"csv", kColorChecker}, {"column", column}}}};
}

nlohmann::json dispersive_scene(const char* mode) {
  // A room 4 m wide: red floor, blue back wall, green left wall, a 2×2 m F11 panel under the ceiling (lighting
  // the walls through NEE with low variance) and a small F11 lamp behind the glass sphere, seen through it.
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 0.3, -3], "to": [0, 0.1, 0], "vertical_fov_deg": 40},
    "film": {"resolution": [24, 24], "filter": {"type": "box"}},
    "integrator": {"max_depth": 12},
    "materials": {
      "glass": {"type": "dielectric", "glass": "sf11"},
      "lamp": {"type": "diffuse", "reflectance": 0}
    },
    "shapes": [
      {"type": "quad", "material": "floor", "vertices": [[-2, -0.5, -4], [-2, -0.5, 3], [2, -0.5, 3], [2, -0.5, -4]]},
      {"type": "quad", "material": "back", "vertices": [[-2, -0.5, 2.5], [-2, 2, 2.5], [2, 2, 2.5], [2, -0.5, 2.5]]},
      {"type": "quad", "material": "side", "vertices": [[-1.5, -0.5, -4], [-1.5, 2, -4], [-1.5, 2, 3], [-1.5, -0.5, 3]]},
      {"type": "sphere", "center": [0, 0, 0], "radius": 0.45, "material": "glass"},
      {"type": "quad", "material": "lamp", "emission": {"illuminant": "F11", "scale": 0.01},
       "vertices": [[-1, 2, -0.5], [1, 2, -0.5], [1, 2, 1.5], [-1, 2, 1.5]]},
      {"type": "quad", "material": "lamp", "emission": {"illuminant": "F11", "scale": 0.01},
       "vertices": [[-0.3, -0.1, 1.5], [-0.3, 0.5, 1.5], [0.3, 0.5, 1.5], [0.3, -0.1, 1.5]]}
    ]
  })");
  scene["materials"]["floor"] = patch("red");
  scene["materials"]["back"] = patch("blue");
  scene["materials"]["side"] = patch("green");
  scene["integrator"]["wavelengths"] = mode;
  return scene;
}

}  // namespace

TEST_CASE("hero wavelengths: F11 light, ColorChecker walls and an SF11 glass sphere render the same as single wavelengths") {
  const auto hero_scene = scene_from_json(dispersive_scene("hero"));
  const auto single_scene = scene_from_json(dispersive_scene("single"));
  // 512 spp: the second check below (the test's power: its 4.5σ band must be narrower than 5 % of the signal) had
  // only a 17 % margin at 256 spp in Z, where the caustic's fireflies sit, and a change of the sampler's random
  // stream could cross it; 512 spp gives 50 % (Z: 6.6e-5 against 1.3e-4).
  const RenderedFilm hero = render_xyz(*hero_scene, 512, 31);
  const RenderedFilm single = render_xyz(*single_scene, 512, 31);
  CHECK(hero.film->sample_counts().discarded() == 0);
  CHECK(single.film->sample_counts().discarded() == 0);
  // X, Y and Z separately: a lane weighted wrongly would tint the image even if Y happened to agree.
  for (int channel = 0; channel < 3; ++channel) {
    std::vector<double> a, b;
    const PixelBounds& bounds = hero.film->pixel_bounds();
    for (int y = bounds.y0; y < bounds.y1; ++y) {
      for (int x = bounds.x0; x < bounds.x1; ++x) {
        a.push_back(hero.film->pixel_value(x, y)[size_t(channel)]);
        b.push_back(single.film->pixel_value(x, y)[size_t(channel)]);
      }
    }
    const Estimate difference = paired_difference(a, b);
    CAPTURE(channel);
    CAPTURE(mean_of(a));
    CAPTURE(mean_of(b));
    CAPTURE(difference.mean);
    CAPTURE(difference.standard_error);
    CHECK(std::abs(difference.mean) <= kSigmas * difference.standard_error);
    CHECK(kSigmas * difference.standard_error < 0.05 * mean_of(a));
  }
}
