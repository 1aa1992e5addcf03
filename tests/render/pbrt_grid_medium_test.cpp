// pbrt-v4 "uniformgrid" media in the importer (src/render/scene/pbrt/pbrt_media.cpp, docs/pbrt-import.md "Media"):
// the density grid inline in the document, trilinear like pbrt's, placed by the CTM at MakeNamedMedium; bad grids
// with file:line; and a pbrt scene with a rotated grid rendering the same image as the same scene in Rimu's JSON.
// "nanovdb" media: the JSON grid medium reading the .nvdb file (written here with NanoVDB's builder), emission listed.
#include <doctest/doctest.h>

#include <fstream>
#include <optional>
#include <vector>

#include <nanovdb/util/GridBuilder.h>

#include "integration_support.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "test_support.h"
#include "transport/media/nanovdb_io.h"
#include "pbrt_test_support.h"

using namespace rimu;
using nlohmann::json;

namespace pbrt_grid_medium_test {

const std::string kCamera = "Scale -1 1 1\nLookAt 0 0 0  0 0 1  0 1 0\nCamera \"perspective\"\n";

PbrtImport import_text(const std::string& text) { return test::import_pbrt_test_text(text, "grid.pbrt"); }

std::string error_of(const std::string& text) { return test::pbrt_import_error(text, "grid.pbrt"); }

// A 2³ "density" grid at index [0, 1]³ (0.25 m voxels from the origin), voxel (1, 0, 1) holding 4 and the rest 1.
// 2³ voxels of 0.25 m, density 1 but 4 at voxel (1, 0, 1); with `temperature_k`, also a "temperature" grid of
// that value on the same voxels.
void write_cloud(const std::filesystem::path& path, std::optional<float> temperature_k = std::nullopt) {
  std::vector<nanovdb::GridHandle<>> grids;
  for (const bool temperature : {false, true}) {
    if (temperature && !temperature_k) break;
    nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
    auto accessor = builder.getAccessor();
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
          accessor.setValue(nanovdb::Coord(x, y, z),
                            temperature ? *temperature_k : x == 1 && y == 0 && z == 1 ? 4.0f : 1.0f);
    grids.push_back(builder.getHandle<>(0.25, nanovdb::Vec3d(0.0), temperature ? "temperature" : "density"));
  }
  nanovdb::io::writeGrids(path.string(), grids, nanovdb::io::Codec::ZIP);
}

TEST_CASE("pbrt grid media: a uniformgrid becomes a trilinear Rimu grid medium with its density inline") {
  const PbrtImport imported = import_text(
      kCamera + "WorldBegin\nAttributeBegin\nTranslate 1 2 3\n"
                "MakeNamedMedium \"cloud\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"integer ny\" 1 \"integer nz\" 3\n"
                "  \"float density\" [0 1 2 3 4 5] \"point3 p0\" [1 0 0] \"point3 p1\" [-1 2 1] \"float scale\" 2\n"
                "  \"rgb sigma_s\" [0.5 0.5 0.5] \"float g\" 0.3\nAttributeEnd\n"
                "MediumInterface \"cloud\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n");
  CHECK_MESSAGE(imported.ignored.empty(), describe_ignored(imported.ignored));
  const json& cloud = imported.document["media"]["cloud"];
  CHECK(cloud["type"] == "grid");
  CHECK(cloud["interpolation"] == "trilinear");
  CHECK(cloud["voxels"] == json({2, 1, 3}));
  CHECK(cloud["density"] == json({0, 1, 2, 3, 4, 5}));
  // pbrt's bounds are the componentwise min and max of p0 and p1.
  CHECK(cloud["bounds_min"] == json({-1, 0, 0}));
  CHECK(cloud["bounds_max"] == json({1, 2, 1}));
  CHECK(cloud["sigma_a"].get<double>() == doctest::Approx(2.0));  // pbrt's default 1 × scale
  CHECK(cloud["sigma_s"].get<double>() == doctest::Approx(1.0));
  CHECK(cloud["g"].get<double>() == doctest::Approx(0.3));
  CHECK(cloud.contains("transform"));
  const auto scene = load_scene(imported.document, "grid.pbrt", test::test_data("pbrt"), test::library());
  REQUIRE(scene->media.size() == 1);
  const GridMedium* grid = scene->media[0].grid();
  REQUIRE(grid != nullptr);
  CHECK(grid->interpolation() == GridInterpolation::trilinear);
  // The CTM at MakeNamedMedium places the box: the voxel centre (0.5, 1, 5/6) of the grid's space, voxel (1, 0, 2)
  // with density 5, sits at (1.5, 3, 3 + 5/6) in pbrt's world; Rimu's world is pbrt's mirrored in x (the camera's
  // "Scale -1 1 1" cancels the mirror here).
  CHECK(grid->density({1.5f, 3.0f, 3.0f + 5.0f / 6.0f}) == doctest::Approx(5.0f).epsilon(1e-4));
  CHECK(grid->density({0.5f, 1.0f, 3.0f + 5.0f / 6.0f}) == doctest::Approx(0.0f));  // outside the box
}

TEST_CASE("pbrt grid media: bad grids are errors at the pbrt file and line") {
  const std::string world = kCamera + "WorldBegin\n";
  const std::string grid = "MakeNamedMedium \"g\" \"string type\" \"uniformgrid\" ";
  CHECK(error_of(world + grid + "\"integer nx\" 2\n \"float density\" [1 2 3]\n") ==
        "grid.pbrt:6: MakeNamedMedium \"g\" (uniformgrid): \"density\" has 3 values; expected nx·ny·nz = 2·1·1 = 2");
  CHECK(error_of(world + grid + "\"integer nx\" 2\n \"float density\" [1 -2]\n") ==
        "grid.pbrt:6: MakeNamedMedium \"g\" (uniformgrid): \"density\" value 1 is -2.0; densities must be finite and >= 0");
  CHECK(error_of(world + grid + "\"integer nx\" 0 \"float density\" [1]\n") ==
        "grid.pbrt:5: MakeNamedMedium \"g\" (uniformgrid): \"nx\", \"ny\" and \"nz\" must be 1..4096 (they are 0, 1, 1)");
  CHECK(error_of(world + grid + "\"integer nx\" 1\n") == "grid.pbrt:5: MakeNamedMedium \"g\" (uniformgrid): needs \"float density\" (nx·ny·nz values)");
  CHECK(error_of(world + grid + "\"float density\" [1] \"point3 p0\" [0 0 0] \"point3 p1\" [1 0 1]\n") ==
        "grid.pbrt:5: MakeNamedMedium \"g\" (uniformgrid): the box \"p0\"–\"p1\" is empty");
  CHECK(error_of(world + grid + "\"float density\" [1 nan]\n").find("grid.pbrt:5: ") == 0);
}

TEST_CASE("pbrt grid media: a rotated density grid renders the same image as the same scene written in Rimu's JSON") {
  const std::filesystem::path pbrt_file = test::test_data("pbrt/grid_medium.pbrt");
  const PbrtImport imported = import_pbrt(pbrt_file, test::library());
  CHECK_MESSAGE(imported.ignored.empty(), describe_ignored(imported.ignored));
  const auto from_pbrt = load_scene(imported.document, pbrt_file.string(), pbrt_file.parent_path(), test::library());
  std::ifstream in(test::test_data("pbrt/grid_medium_equivalent.json"));
  const json hand_written = json::parse(in);
  const auto from_json = load_scene(hand_written, "grid_medium_equivalent.json", pbrt_file.parent_path(), test::library());
  for (double deviation : test::render_block_deviations(*from_pbrt, *from_json)) CHECK(deviation <= test::kSigmas);

  // The comparison can fail: the grid without its CTM's translation (0.75 m lower, half under the floor) is caught.
  json unmoved = hand_written;
  unmoved["media"]["haze"]["transform"].erase(1);
  const auto wrong = load_scene(unmoved, "unmoved.json", pbrt_file.parent_path(), test::library());
  CHECK(test::worst_deviation(test::render_block_deviations(*from_pbrt, *wrong)) > test::kSigmas);
}

TEST_CASE("grid media in JSON: inline densities are checked at their key") {
  const auto with_medium = [](const json& medium) {
    json m = medium;
    m.update({{"type", "grid"}, {"boundary_material", "edge"}, {"index_matched", true}, {"sigma_a", 1}, {"sigma_s", 0},
              {"bounds_min", {0, 0, 0}}, {"bounds_max", {1, 1, 1}}});
    return json{{"camera", {{"from", {0, 0, -3}}, {"to", {0, 0, 0}}}},
                {"film", {{"resolution", {8, 8}}}},
                {"materials", {{"edge", {{"type", "diffuse"}, {"reflectance", 0.5}}}}},
                {"media", {{"m", m}}},
                {"shapes", json::array({{{"type", "sphere"}, {"center", {0.5, 0.5, 0.5}}, {"radius", 1}, {"material", "edge"}}})}};
  };
  const auto error_of_json = [&](const json& medium) {
    try {
      test::scene_from_json(with_medium(medium));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of_json({{"voxels", {2, 1, 1}}, {"density", {1, 2}}, {"interpolation", "trilinear"}}) == "no error");
  CHECK(error_of_json({{"voxels", {2, 1, 1}}, {"density", {1}}}).find("/media/m/density: expected nx·ny·nz = 2 numbers") != std::string::npos);
  CHECK(error_of_json({{"voxels", {2, 1, 1}}, {"density", {1, -1}}}).find("/media/m/density/1: a density must be a finite number >= 0") !=
        std::string::npos);
  CHECK(error_of_json({{"voxels", {2, 1}}, {"density", {1, 1}}}).find("/media/m/voxels: expected [nx, ny, nz]") != std::string::npos);
  CHECK(error_of_json({{"voxels", {1, 1, 1}}, {"density", {1}}, {"procedural", "cloud"}}).find("exactly one of") != std::string::npos);
  CHECK(error_of_json({{"voxels", {1, 1, 1}}, {"density", {1}}, {"interpolation", "cubic"}}).find("/media/m/interpolation") != std::string::npos);
  CHECK(error_of_json({{"voxels", {1, 1, 1}}, {"density", {1}}, {"transform", json::array({json{{"scale", 0}}})}}).find("/media/m/transform") !=
        std::string::npos);
}

TEST_CASE("pbrt grid media: a nanovdb medium becomes a trilinear grid medium reading the .nvdb file") {
  const test::ScratchFolder folder("pbrt_nanovdb");
  write_cloud(folder / "cloud.nvdb");
  const std::string text =
      kCamera + "WorldBegin\nAttributeBegin\nTranslate 1 2 3\n"
                "MakeNamedMedium \"smoke\" \"string type\" \"nanovdb\" \"string filename\" \"cloud.nvdb\"\n"
                "  \"rgb sigma_a\" [0.5 0.5 0.5] \"rgb sigma_s\" [1 1 1] \"float g\" 0.877 \"float scale\" 4\n"
                "  \"float Lescale\" 0.1 \"float temperaturecutoff\" 100 \"float temperaturescale\" 2000\nAttributeEnd\n"
                "MediumInterface \"smoke\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n";
  const PbrtImport imported = import_pbrt_text(text, "cloud.pbrt", folder.path, test::library());
  REQUIRE(imported.ignored.size() == 1);
  CHECK(imported.ignored[0].what.find("\"Lescale\", \"temperatureoffset\", \"temperaturescale\" (the file has no "
                                      "\"temperature\" grid, so nothing emits, as in pbrt-v4)") != std::string::npos);
  CHECK_FALSE(imported.document["media"]["smoke"].contains("emission"));
  const json& smoke = imported.document["media"]["smoke"];
  CHECK(smoke["type"] == "grid");
  CHECK(smoke["interpolation"] == "trilinear");
  CHECK(std::filesystem::path(smoke["file"].get<std::string>()).filename() == "cloud.nvdb");
  CHECK(!smoke.contains("grid"));  // pbrt-v4 reads "density", the loader's default
  CHECK(!smoke.contains("bounds_min"));
  CHECK(smoke["g"].get<double>() == doctest::Approx(0.877));
  CHECK(smoke.contains("transform"));
  const auto scene = load_scene(imported.document, "cloud.pbrt", folder.path, test::library());
  REQUIRE(scene->media.size() == 1);
  const GridMedium* grid = scene->media[0].grid();
  REQUIRE(grid != nullptr);
  // Voxel (1, 0, 1)'s centre is (0.25, 0, 0.25) in the file's world, (1.25, 2, 3.25) after the Translate, and
  // x-mirrored into Rimu's world by the camera's "Scale -1 1 1" as in the uniformgrid case above.
  CHECK(grid->density({1.25f, 2.0f, 3.25f}) == doctest::Approx(4.0f).epsilon(1e-5));
  CHECK(grid->density({1.0f, 2.0f, 3.0f}) == doctest::Approx(1.0f).epsilon(1e-5));
  CHECK(grid->density({2.0f, 2.0f, 3.0f}) == 0.0f);

  CHECK(test::pbrt_import_error(kCamera + "WorldBegin\nMakeNamedMedium \"m\" \"string type\" \"nanovdb\" "
                                          "\"string filename\" \"absent.nvdb\"\n",
                                "grid.pbrt")
            .find("grid.pbrt:5: MakeNamedMedium \"m\" (nanovdb): cannot find the NanoVDB file '") == 0);
}

TEST_CASE("pbrt grid media: a nanovdb file's temperature grid becomes the medium's black-body emission") {
  // pbrt-v4: Lescale × the peak-normalised black body at T = (value − temperaturecutoff) × temperaturescale, a raw
  // radiance: in Rimu's film units × ∫ȳ dλ (106.857 nm for the 1931 observer at 1 nm), the factor pbrt's light
  // normalisation carries (bench/pbrt_scenes/fire_nanovdb.pbrt matches pbrt-v4's image, docs/pbrt-import.md).
  const test::ScratchFolder folder("pbrt_nanovdb_fire");
  write_cloud(folder / "fire.nvdb", 1.5f);
  const std::string text = kCamera + "WorldBegin\n"
                           "MakeNamedMedium \"fire\" \"string type\" \"nanovdb\" \"string filename\" \"fire.nvdb\"\n"
                           "  \"float Lescale\" 0.1 \"float temperaturecutoff\" 0.5 \"float temperaturescale\" 2000\n"
                           "MediumInterface \"fire\" \"\"\nMaterial \"interface\"\nShape \"sphere\"\n";
  const PbrtImport imported = import_pbrt_text(text, "fire.pbrt", folder.path, test::library());
  CHECK(imported.ignored.empty());
  const json& emission = imported.document["media"]["fire"]["emission"];
  CHECK(emission["temperature_grid"] == "temperature");
  CHECK(emission["temperature_offset_k"].get<double>() == 0.5);
  CHECK(emission["temperature_scale"].get<double>() == 2000.0);
  CHECK(emission["scale"].get<double>() == doctest::Approx(0.1 * 106.857).epsilon(1e-4));
  const auto scene = load_scene(imported.document, "fire.pbrt", folder.path, test::library());
  REQUIRE(scene->media[0].emission() != nullptr);
  // T = (1.5 − 0.5) × 2000 = 2000 K at the voxels' centres.
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f / 470.0f));
  const BlackbodySpectrum shape(2000.0, BlackbodySpectrum::Scale::peak_one);
  const Float4 le = scene->media[0].emission()->radiance_at({0.125f, 0.125f, 0.125f}, lambda);
  for (int k = 0; k < 4; ++k)
    CHECK(le[k] == doctest::Approx(0.1 * 106.857 * shape.value(lambda.lambda_nm(k))).epsilon(1e-4));
}

TEST_CASE("grid media in JSON: a .nvdb file, and its errors at the key with the file's path") {
  const test::ScratchFolder folder("json_nanovdb");
  write_cloud(folder / "cloud.nvdb");
  folder.write("text.nvdb", "plain text");
  const auto error_of_json = [&](const json& keys) {
    json m = {{"type", "grid"}, {"boundary_material", "edge"}, {"index_matched", true}, {"sigma_a", 1}, {"sigma_s", 0}};
    m.update(keys);
    const json document = {
        {"camera", {{"from", {0, 0, -3}}, {"to", {0, 0, 0}}}},
        {"film", {{"resolution", {8, 8}}}},
        {"materials", {{"edge", {{"type", "diffuse"}, {"reflectance", 0.5}}}}},
        {"media", {{"m", m}}},
        {"shapes", json::array({{{"type", "sphere"}, {"center", {0.25, 0.25, 0.25}}, {"radius", 1}, {"material", "edge"}}})}};
    try {
      load_scene(document, "s.json", folder.path, test::library());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(error_of_json({{"file", "cloud.nvdb"}, {"interpolation", "trilinear"}}) == "no error");
  CHECK(error_of_json({{"file", "cloud.nvdb"}, {"grid", "density"}, {"transform", json::array({json{{"scale", 2}}})}}) ==
        "no error");
  const std::string missing = error_of_json({{"file", "none.nvdb"}});
  CAPTURE(missing);
  CHECK(missing.find("/media/m/file") != std::string::npos);
  CHECK(missing.find("none.nvdb: no such file") != std::string::npos);
  const std::string text = error_of_json({{"file", "text.nvdb"}});
  CHECK(text.find("/media/m/file") != std::string::npos);
  CHECK(text.find("text.nvdb: not a NanoVDB file") != std::string::npos);
  const std::string name = error_of_json({{"file", "cloud.nvdb"}, {"grid", "temperature"}});
  CHECK(name.find("cloud.nvdb: no grid named \"temperature\"; the file holds \"density\" (float)") != std::string::npos);
  CHECK(error_of_json({{"file", "cloud.nvdb"}, {"bounds_min", {0, 0, 0}}}).find("/media/m/bounds_min: a .nvdb grid's box comes from the file") !=
        std::string::npos);
  CHECK(error_of_json({{"procedural", "cloud"}, {"grid", "density"}, {"bounds_min", {0, 0, 0}}, {"bounds_max", {1, 1, 1}}})
            .find("/media/m/grid: \"grid\" names a grid of a .nvdb file") != std::string::npos);
}

}  // namespace pbrt_grid_medium_test
