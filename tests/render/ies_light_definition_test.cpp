// Authoring IES lights (`rimu-light --type ies --file x.ies --lumens 800`): the definition round trip through a
// scene's "include", the report's lumens against an independent quadrature of the table, the candela in the main
// planes and the lux on the axis, recolouring at constant lumens, the polar plot through the plot output code, and
// errors that name their flag. Meter tolerances: five standard errors (tests/render/meter_reading_check.h).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <unistd.h>

#include "meter_reading_check.h"
#include "render/output/plot_output.h"
#include "render/reports/ies_report.h"
#include "render/scene/ies_light_definition.h"
#include "render/scene/scene.h"
#include "spectral/error.h"
#include "spectral/photometry/light_units.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using rimu::test::kPi;

// A bilateral (0-180°) table whose C planes differ, so the plane table and the quadrature see the C dependence:
// 400 cd at nadir in every plane; at 45° 300 cd in C 0°, 200 cd in C 90°, 100 cd in C 180°; dark at 90°.
const char* kBilateral = R"(IESNA:LM-63-2002
[TEST] rimu authoring test
TILT=NONE
1 1000 1.0 3 3 1 2 0 0 0
1.0 1.0 12
0 45 90
0 90 180
400 300 0
400 200 0
400 100 0
)";

struct Folder {
  fs::path path = fs::temp_directory_path() / ("rimu-ies-authoring-" + std::to_string(::getpid()));
  Folder() { fs::create_directories(path); }
  ~Folder() { fs::remove_all(path); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return path / name;
  }
};

// ∫ I dω by the midpoint rule on a fine (γ, C) grid, independent of CandelaDistribution's closed form. With
// n_gamma × n_c cells the error of the midpoint rule on the bilinear interpolant is below 1e-4 relative here.
double quadrature_lumens(const CandelaDistribution& table, int n_gamma = 1800, int n_c = 720) {
  double sum = 0;
  const double dg = kPi / n_gamma, dc = 2 * kPi / n_c;
  for (int i = 0; i < n_gamma; ++i) {
    const double g = (i + 0.5) * dg;
    for (int j = 0; j < n_c; ++j) sum += table.intensity_deg(g * 180 / kPi, (j + 0.5) * dc * 180 / kPi) * std::sin(g);
  }
  return sum * dg * dc;
}

}  // namespace

TEST_CASE("IES authoring: 800 lm written, included in a scene and measured") {
  Folder folder;
  folder.write("lamp.ies", kBilateral);
  const IesLightDefinition light =
      ies_light_from_options("lamp.ies", 800.0, json{{"blackbody", 3000}}, test::library(), folder.path);
  CHECK(fs::path(light.file).is_absolute());
  const json written = ies_light_definition_json(light);
  CHECK(written["type"] == "ies");
  CHECK(written["luminous_power_lm"] == 800.0);
  std::ofstream(folder.path / "lamp.json") << written.dump(2);

  // Read back: the same definition.
  const IesLightDefinition back = read_ies_light_definition(written, "lamp.json");
  CHECK(back.file == light.file);
  CHECK(*back.luminous_power_lm == 800.0);

  // The report says 800 lm, and an independent quadrature of the scaled table agrees within its error.
  const IesPhotometry ies = read_ies_file(folder.path / "lamp.ies");
  const json report = inspect_ies_json(ies, {}, 800.0);
  CHECK(report["total_luminous_flux_lm"].get<double>() == doctest::Approx(800.0).epsilon(1e-12));
  const double scale = ies_candela_scale(ies, 800.0);
  CHECK(quadrature_lumens(*candela_distribution(ies, scale)) == doctest::Approx(800.0).epsilon(1e-4));
  // Planes: γ 0, 10, ..., 90 (the file's range); at 45° the scaled 300, 200, 100 and (bilateral) C 270° = C 90°.
  const auto& planes = report["planes"];
  REQUIRE(planes["gamma_deg"].size() == 10);
  CHECK(planes["c0_cd"][0].get<double>() == doctest::Approx(400 * scale));
  CHECK(planes["c180_cd"][9].get<double>() == doctest::Approx(0.0));
  // On the axis: E = I(0)/d² at 1, 2, 3 m.
  for (int k = 0; k < 3; ++k)
    CHECK(report["on_axis_illuminance"][k]["lx"].get<double>() ==
          doctest::Approx(400 * scale / ((k + 1.0) * (k + 1.0))));

  // Included in a scene, 2 m above a meter: the light meter reads I(0)/4 and the light's power is 800 lm.
  const json scene_document{
      {"camera", {{"from", {0, 1, 5}}, {"to", {0, 0, 0}}}},
      {"lights", json::array({{{"include", "lamp.json"}, {"position", {0, 2, 0}}, {"direction", {0, -1, 0}}}})}};
  const auto scene = load_scene(scene_document, "lamp scene", folder.path, test::library());
  test::check_reading(measure_illuminance_lx(scene->transport_view(), {0, 0, 0}, {0, 1, 0},
                                             test::library().photopic_v(), 2000, 7),
                      400 * scale / 4);
  const double efficacy = shape_integrals(BlackbodySpectrum(3000, BlackbodySpectrum::Scale::peak_one),
                                          test::library().photopic_v()).efficacy_lm_W();
  CHECK(scene->lights[0]->total_power_w(1.0) * efficacy == doctest::Approx(800.0).epsilon(1e-6));

  SUBCASE("recolouring keeps the lumens") {
    const IesLightDefinition cool = recolor_ies_light(back, json{{"blackbody", 5000}}, test::library(), folder.path);
    CHECK(*cool.luminous_power_lm == 800.0);
    std::ofstream(folder.path / "lamp.json") << ies_light_definition_json(cool).dump(2);
    const auto recoloured = load_scene(scene_document, "lamp scene", folder.path, test::library());
    const double cool_efficacy =
        shape_integrals(BlackbodySpectrum(5000, BlackbodySpectrum::Scale::peak_one), test::library().photopic_v())
            .efficacy_lm_W();
    CHECK(recoloured->lights[0]->total_power_w(1.0) * cool_efficacy == doctest::Approx(800.0).epsilon(1e-6));
  }
}

TEST_CASE("IES authoring: errors name the flag or the file and line") {
  Folder folder;
  folder.write("lamp.ies", kBilateral);
  folder.write("broken.ies", "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n100\n");
  const auto fails = [&](const std::string& file, std::optional<double> lumens, std::optional<json> spectrum,
                         const std::string& expected) {
    CHECK_THROWS_WITH_AS(ies_light_from_options(file, lumens, spectrum, test::library(), folder.path),
                         doctest::Contains(expected.c_str()), InputError);
  };
  fails("", 800.0, std::nullopt, "--file");
  fails("lamp.ies", -5.0, std::nullopt, "--lumens");
  fails("lamp.ies", 1e31, std::nullopt, "--lumens");
  fails("broken.ies", 800.0, std::nullopt, "broken.ies:7");
  fails("missing.ies", 800.0, std::nullopt, "missing.ies");
  fails("lamp.ies", 800.0, json{{"csv", (folder.path / "none.csv").string()}}, "none.csv");
  // A definition with a key the format does not have.
  CHECK_THROWS_WITH_AS(read_ies_light_definition(json{{"type", "ies"}, {"file", "x.ies"}, {"spectrum", 1.0},
                                                      {"lumens", 800}},
                                                 "def.json"),
                       doctest::Contains("lumens"), InputError);
  const IesPhotometry ies = read_ies_file(folder.path / "lamp.ies");
  CHECK_THROWS_WITH_AS(inspect_ies_text(ies, {}, -1.0), doctest::Contains("--lumens"), InputError);
}

TEST_CASE("IES polar plot: written through the plot output code, bad paths refused naming the option") {
  Folder folder;
  const IesPhotometry ies = parse_ies(kBilateral, "lamp.ies");
  CHECK_THROWS_WITH_AS(plot_ies_polar_png(ies, folder.path / "missing" / "polar.png", 800.0, "--plot"),
                       doctest::Contains("--plot"), InputError);
  CHECK_THROWS_WITH_AS(plot_ies_polar_png(ies, folder.path / "polar.jpg", 800.0, "--plot-polar"),
                       doctest::Contains("--plot-polar"), InputError);
  CHECK(!fs::exists(folder.path / "polar.jpg"));
  if (!fs::exists(gnuplot_binary())) return;
  plot_ies_polar_png(ies, folder.path / "polar.png", 800.0);
  std::ifstream png(folder.path / "polar.png", std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  CHECK(std::string(signature + 1, 3) == "PNG");
  CHECK(fs::file_size(folder.path / "polar.png") > 1000);
}
