// pbrt-v4's goniometric light (docs/pbrt-import.md, Lights): an equal-area octahedral image of intensities, looked
// up by pbrt at EqualAreaSphereToSquare of the light-space direction with y and z swapped, one value per pixel (the
// mean of R, G, B), nearest pixel. The imported light must give, towards each pixel's direction, that pixel times
// pbrt's scale (in Rimu's film units), and "power" must set the flux.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "transport/sampling/equal_area_square.h"
#include "transport/lights/goniometric_light.h"
#include "pbrt_test_support.h"

using namespace rimu;
using nlohmann::json;

namespace {

const GoniometricLight& only_goniometric(const Scene& scene) {
  REQUIRE(scene.lights.size() == 1);
  const auto* light = dynamic_cast<const GoniometricLight*>(scene.lights[0].get());
  REQUIRE(light);
  return *light;
}

}  // namespace

TEST_CASE("pbrt goniometric light: the intensity towards each pixel's direction is pbrt's pixel times its scale") {
  const std::filesystem::path folder = test::test_data("pbrt");
  const PbrtImport imported = import_pbrt(folder / "goniometric.pbrt", test::library());
  CHECK(imported.ignored.empty());
  const json& l = imported.document["lights"][0];
  CHECK(l["type"] == "goniometric");
  const double nits_per_unit = SpectralResponse::from_spec(test::library(), "xyz").luminance_nits_per_unit_y();
  CHECK(l["candela_scale"].get<double>() == doctest::Approx(0.5 * nits_per_unit));  // a blackbody: Y normalised to 1
  const auto scene = load_scene(imported.document, "goniometric.pbrt", folder, test::library());
  const GoniometricLight& light = only_goniometric(*scene);
  // The light transform: Rotate 30° about z. pbrt's pixel (x, y) lies at light-space (w.x, w.z, w.y), w its
  // square point's direction; the file's pattern puts v = 1 + x + 4y there, with R, G, B = v, 2v, 3v (mean 2v).
  const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      for (const auto& [fx, fy] : {std::pair{0.5f, 0.5f}, {0.2f, 0.8f}, {0.85f, 0.1f}}) {
        const Vec3 w = equal_area_square_to_sphere({(float(x) + fx) / 4.0f, (float(y) + fy) / 4.0f});
        const Vec3 light_space{w.x, w.z, w.y};
        const Vec3 world{float(c * light_space.x - s * light_space.y), float(s * light_space.x + c * light_space.y), light_space.z};
        CAPTURE(x);
        CAPTURE(y);
        CHECK(light.table_value(normalize(world)) == doctest::Approx(0.5 * nits_per_unit * 2.0 * (1.0 + x + 4.0 * y)).epsilon(1e-6));
      }
    }
  // The comparison can fail: without pbrt's y-z swap the pixels land elsewhere.
  int unswapped_matches = 0;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const Vec3 w = equal_area_square_to_sphere({(x + 0.5f) / 4.0f, (y + 0.5f) / 4.0f});
      const Vec3 world{float(c * w.x - s * w.y), float(s * w.x + c * w.y), w.z};
      if (std::abs(light.table_value(world) - 0.5 * nits_per_unit * 2.0 * (1.0 + x + 4.0 * y)) < 1e-3 * nits_per_unit) ++unswapped_matches;
    }
  CHECK(unswapped_matches < 8);
}

TEST_CASE("pbrt goniometric light: power sets the flux, an RGB I keeps its luminance, errors name the line") {
  const std::filesystem::path folder = test::test_data("pbrt");
  const std::string text = test::file_text(folder / "goniometric.pbrt");
  const std::string with_power = std::regex_replace(text, std::regex("\"float scale\" 0.5"), "\"float scale\" 0.5 \"float power\" 100");
  const PbrtImport imported = import_pbrt_text(with_power, "goniometric.pbrt", folder, test::library());
  CHECK(imported.ignored.empty());
  const double nits_per_unit = SpectralResponse::from_spec(test::library(), "xyz").luminance_nits_per_unit_y();
  // pbrt: scale · power / k_e with k_e = 4π · mean(image), so ∫ I dω = scale · power (lm in pbrt's unit).
  CHECK(imported.document["lights"][0]["luminous_power_lm"].get<double>() == doctest::Approx(0.5 * 100 * nits_per_unit));
  const auto scene = load_scene(imported.document, "goniometric.pbrt", folder, test::library());
  CHECK(only_goniometric(*scene).table().integral_sr() == doctest::Approx(0.5 * 100 * nits_per_unit).epsilon(1e-9));

  const std::string rgb = std::regex_replace(text, std::regex("\"blackbody I\" 4000"), "\"rgb I\" [0.5 0.5 0.5]");
  const json rgb_light = import_pbrt_text(rgb, "goniometric.pbrt", folder, test::library()).document["lights"][0];
  CHECK(rgb_light["candela_scale"].get<double>() == doctest::Approx(0.5 * 0.5 * nits_per_unit).epsilon(1e-6));

  const std::string missing = std::regex_replace(text, std::regex("goniometric_4x4.pfm"), "nothing.pfm");
  try {
    import_pbrt_text(missing, "goniometric.pbrt", folder, test::library());
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("goniometric.pbrt:13: LightSource \"goniometric\": cannot find the image") != std::string::npos);
  }
}
