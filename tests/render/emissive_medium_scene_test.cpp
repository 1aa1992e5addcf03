// A medium's "emission" in the scene format (docs/media.md, "Emissive media"): its luminance as the camera reads
// it, a NanoVDB temperature grid against the equivalent uniform black body, light groups, and the errors.
#include <doctest/doctest.h>

#include <nanovdb/util/GridBuilder.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "input_error_check.h"
#include "integration_support.h"
#include "meter_reading_check.h"
#include "render/reports/light_meter.h"
#include "test_support.h"
#include "transport/media/nanovdb_io.h"

using namespace rimu;
using nlohmann::json;

namespace emissive_medium_scene_test {

// A camera inside a scene-wide medium that absorbs 50/m (scattering `sigma_s`) and emits `emission`: the
// radiance it sees is L_e (1 − e^{−50·∞}) = L_e exactly when nothing scatters, and still L_e with scattering
// (equilibrium in an unbounded medium).
json glowing_fog(json emission, double sigma_s = 0.0) {
  return json{{"camera", {{"from", {0, 0, 0}}, {"to", {0, 0, 1}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 30}}},
              {"film", {{"resolution", {8, 8}}, {"filter", {{"type", "box"}, {"radius", 0.5}}}}},
              {"materials", {{"black", {{"type", "diffuse"}, {"reflectance", 0}}}}},
              {"media",
               {{"glow",
                 {{"type", "homogeneous"}, {"sigma_a", 50}, {"sigma_s", sigma_s}, {"contains_camera", true},
                  {"emission", std::move(emission)}}}}},
              {"shapes", json::array()}};
}

MeterReading camera_luminance(const json& document, int spp, uint64_t seed = 3) {
  const auto scene = test::scene_from_json(document);
  const auto rendered = test::render_xyz(*scene, spp, seed);
  return measure_luminance_nt(*rendered.film, rendered.film->pixel_bounds());
}

// An .nvdb file with two grids on the same 4³ voxels of 1 m around the origin (box [−2.5, 1.5]³ m): "density" 1 and
// "temperature" `kelvin`.
void write_fire(const std::filesystem::path& path, float kelvin) {
  std::vector<nanovdb::GridHandle<>> grids;
  for (const auto& [name, value] : {std::pair{"density", 1.0f}, std::pair{"temperature", kelvin}}) {
    nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
    auto accessor = builder.getAccessor();
    for (int z = -2; z < 2; ++z)
      for (int y = -2; y < 2; ++y)
        for (int x = -2; x < 2; ++x) accessor.setValue(nanovdb::Coord(x, y, z), value);
    grids.push_back(builder.getHandle<>(1.0, nanovdb::Vec3d(0.0), name));
  }
  nanovdb::io::writeGrids(path.string(), grids);
}

}  // namespace emissive_medium_scene_test

using namespace emissive_medium_scene_test;

TEST_CASE("emissive media: the camera reads the authored luminance, with and without scattering") {
  // "luminance_nt" is the luminance of an optically thick body of the medium: what the camera sees inside one.
  const json d65 = {{"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", 1000}};
  test::check_reading(camera_luminance(glowing_fog(d65), 4), 1000.0);
  test::check_reading(camera_luminance(glowing_fog(d65, 150.0), 64), 1000.0, 0.02);
  // The absolute form: a radiance spectrum in W/(m²·sr·nm), whose luminance is K_m ∫ L ȳ dλ (72 983 nt for 1).
  test::check_reading(camera_luminance(glowing_fog({{"constant", 0.01}}), 4), 729.833, 0.01);
}

TEST_CASE("emissive media: a NanoVDB temperature grid renders as the uniform black body of its temperature") {
  const test::ScratchFolder folder("emissive_medium_fire");
  write_fire(folder / "fire.nvdb", 1900.0f);
  // (1900 − 100) × 1.25 = 2250 K, peak scaled to 0.02; against {"blackbody": 2250, "scale": 0.02} (peak one).
  json fire = glowing_fog(json::object());
  json& glow = fire["media"]["glow"];
  glow = {{"type", "grid"}, {"file", (folder / "fire.nvdb").string()}, {"sigma_a", 50}, {"sigma_s", 0},
          {"contains_camera", true},
          {"emission", {{"temperature_grid", "temperature"}, {"temperature_offset_k", 100}, {"temperature_scale", 1.25},
                        {"scale", 0.02}}}};
  const MeterReading grid = camera_luminance(fire, 16, 5);
  const MeterReading uniform = camera_luminance(glowing_fog({{"blackbody", 2250}, {"scale", 0.02}}), 16, 6);
  CAPTURE(grid.value);
  CAPTURE(uniform.value);
  CHECK(grid.value > 0.0);
  CHECK(std::fabs(grid.value - uniform.value) <= 5.0 * std::hypot(grid.standard_error, uniform.standard_error));
  CHECK(grid.standard_error < 0.02 * grid.value);
  glow["emission"]["temperature_offset_k"] = 1900;  // T = 0 K everywhere: nothing emits
  CHECK(camera_luminance(fire, 2).value == 0.0);
}

TEST_CASE("emissive media: light groups take the medium's light") {
  json named = glowing_fog({{"constant", 0.01}});
  named["media"]["glow"]["light_group"] = "fire";
  named["lights"] = json::array({{{"type", "point"}, {"position", {0, 5, 0}}, {"intensity", 1}, {"light_group", "lamp"}}});
  const auto scene = test::scene_from_json(named);
  REQUIRE(scene->light_groups.size() == 2);
  CHECK(scene->light_groups[size_t(scene->media[0].emission_light_group())] == "fire");
  // Without the key, the medium joins "ungrouped" as an unmarked light does.
  named["media"]["glow"].erase("light_group");
  const auto unmarked = test::scene_from_json(named);
  CHECK(unmarked->light_groups[size_t(unmarked->media[0].emission_light_group())] == "ungrouped");
  // And a scene without groups puts it in group 0.
  CHECK(test::scene_from_json(glowing_fog({{"constant", 0.01}}))->media[0].emission_light_group() == 0);
}

TEST_CASE("emissive media: errors name the key") {
  json no_absorption = glowing_fog({{"constant", 1}});
  no_absorption["media"]["glow"]["sigma_a"] = 0;
  no_absorption["media"]["glow"]["sigma_s"] = 1;
  CHECK_THROWS_WITH_AS(test::scene_from_json(no_absorption),
                       doctest::Contains("/media/glow/emission: a medium emits sigma_a"), InputError);
  json group_without_light = glowing_fog({{"constant", 1}});
  group_without_light["media"]["glow"].erase("emission");
  group_without_light["media"]["glow"]["light_group"] = "fire";
  CHECK_THROWS_WITH_AS(test::scene_from_json(group_without_light), doctest::Contains("/media/glow/light_group"),
                       InputError);
  CHECK_THROWS_WITH_AS(test::scene_from_json(glowing_fog({{"temperature_grid", "temperature"}})),
                       doctest::Contains("/media/glow/emission/temperature_grid: a temperature grid is read from"),
                       InputError);
  CHECK_THROWS_WITH_AS(test::scene_from_json(glowing_fog({{"spectrum", {{"blackbody", 2000}}}, {"luminous_power_lm", 5}})),
                       doctest::Contains("medium light cannot be given in lm"), InputError);
  CHECK_THROWS_WITH_AS(test::scene_from_json(glowing_fog({{"constant", -1}})), doctest::Contains("/media/glow/emission"),
                       InputError);
}
