// Feature layers (`rimu --aov`, render/output/aov_channels.h, transport/integrators/path_features.h): on scenes with
// known answers the albedo is the diffuse reflectance, the normal the plane's, the depth the distance along the
// camera path (through a mirror to the plane seen in it); every layer stays finite on black and empty scenes; the
// image is the same with and without layers; partial renders refuse them.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "render/denoise/denoise_exr.h"
#include "render/output/aov_channels.h"
#include "render/render_job.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::map<std::string, std::vector<float>> read_exr(const fs::path& path, int& width) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  width = dw.max.x - dw.min.x + 1;
  const int height = dw.max.y - dw.min.y + 1;
  std::map<std::string, std::vector<float>> out;
  Imf::FrameBuffer frame;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    auto& v = out[it.name()];
    v.assign(size_t(width) * size_t(height), 0.0f);
    frame.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, v.data(), dw, sizeof(float), sizeof(float) * size_t(width)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(dw.min.y, dw.max.y);
  return out;
}

struct Rendered {
  std::map<std::string, std::vector<float>> channels;
  int width = 0;
};

Rendered render_scene(const json& scene, const std::string& name, const std::string& aovs, bool denoise = false) {
  const fs::path dir = fs::temp_directory_path() / "rimu_aov_test";
  fs::create_directories(dir);
  const fs::path scene_path = dir / (name + ".json"), exr = dir / (name + ".exr");
  std::ofstream(scene_path) << scene.dump();
  RenderJob job;
  job.scene = scene_path;
  job.exr_output = exr;
  job.threads = 2;
  job.quiet = true;
  if (!aovs.empty()) job.aovs = parse_aov_list(aovs, "--aov");
  job.denoise = denoise;
  std::ostringstream log;
  run_render_job(job, log);
  Rendered r;
  r.channels = read_exr(exr, r.width);
  return r;
}

constexpr double kReflectance = 0.5;

// A diffuse plane z = 0 of reflectance 0.5 seen head-on from 2 m, under a distant light.
json plane_scene() {
  return json::parse(R"({
    "camera": {"from": [0, 0, -2], "to": [0, 0, 0], "vertical_fov_deg": 20},
    "film": {"resolution": [9, 9], "filter": {"type": "box"}},
    "integrator": {"spp": 8},
    "materials": {"plane": {"type": "diffuse", "reflectance": 0.5}},
    "lights": [{"type": "distant", "direction": [0, 0.3, -1], "irradiance": 1.0}],
    "shapes": [{"type": "quad", "material": "plane", "vertices": [[-50, -50, 0], [50, -50, 0], [50, 50, 0], [-50, 50, 0]]}]
  })");
}

}  // namespace

TEST_CASE("aov: a diffuse plane's albedo is its reflectance, its normal faces the camera, its depth is the distance") {
  const Rendered r = render_scene(plane_scene(), "plane", "all");
  const size_t centre = 4 * size_t(r.width) + 4;
  for (const char* c : {"albedo.X", "albedo.Y", "albedo.Z"}) {
    // A constant reflectance gives each sample's diffuse BSDF weight f·cos/pdf = ρ exactly (float rounding only).
    for (float v : r.channels.at(c)) CHECK(v == doctest::Approx(kReflectance).epsilon(1e-5));
  }
  for (float v : r.channels.at("albedo_variance")) CHECK(v < 1e-10f);
  for (size_t i = 0; i < r.channels.at("N.Z").size(); ++i) {
    CHECK(r.channels.at("N.X")[i] == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(r.channels.at("N.Z")[i] == doctest::Approx(-1.0).epsilon(1e-6));
  }
  // The centre pixel spans ±1.1° around the axis: the distance 2/cos θ exceeds 2 m by at most 2(1/cos 1.6° − 1) =
  // 8e-4 m (the pixel's corner).
  const float depth = r.channels.at("depth.Z")[centre];
  CHECK(depth >= 2.0f - 1e-5f);
  CHECK(depth <= 2.0f + 8e-4f);
  for (const char* name : {"variance", "half_even.Y", "half_odd.Y", "depth_variance", "N_variance"})
    for (float v : r.channels.at(name)) CHECK(std::isfinite(v));
  // Every pixel took 8 samples, 4 in each half: their mean is the beauty.
  for (size_t i = 0; i < r.channels.at("Y").size(); ++i)
    CHECK(0.5f * (r.channels.at("half_even.Y")[i] + r.channels.at("half_odd.Y")[i]) ==
          doctest::Approx(r.channels.at("Y")[i]).epsilon(1e-5));
}

TEST_CASE("aov: a smooth mirror shows the albedo, normal and distance of the plane it reflects") {
  // The mirror x = z (normal (1, 0, −1)/√2) turns the camera's +z rays to +x, onto a plane x = 3 of reflectance
  // 0.25: the camera path is 2 m to the mirror and 3 m on.
  json scene = json::parse(R"({
    "camera": {"from": [0, 0, -2], "to": [0, 0, 0], "vertical_fov_deg": 8},
    "film": {"resolution": [9, 9], "filter": {"type": "box"}},
    "integrator": {"spp": 8},
    "materials": {"mirror": {"type": "conductor", "metal": "gold", "roughness": 0},
                  "plane": {"type": "diffuse", "reflectance": 0.25}},
    "lights": [{"type": "distant", "direction": [-1, 0.2, 0], "irradiance": 1.0}],
    "shapes": [{"type": "quad", "material": "mirror", "vertices": [[-1, -1, -1], [-1, 1, -1], [1, 1, 1], [1, -1, 1]]},
               {"type": "quad", "material": "plane", "vertices": [[3, -50, -50], [3, 50, -50], [3, 50, 50], [3, -50, 50]]}]
  })");
  const Rendered r = render_scene(scene, "mirror", "albedo,normal,depth");
  const size_t centre = 4 * size_t(r.width) + 4;
  for (const char* c : {"albedo.X", "albedo.Y", "albedo.Z"})
    for (float v : r.channels.at(c)) CHECK(v == doctest::Approx(0.25).epsilon(1e-5));
  for (float v : r.channels.at("N.X")) CHECK(v == doctest::Approx(-1.0).epsilon(1e-6));
  // The centre pixel spans ±0.45°: 5/cos θ exceeds 5 m by at most 5(1/cos 0.64° − 1) = 3.1e-4 m.
  CHECK(r.channels.at("depth.Z")[centre] >= 5.0f - 1e-4f);
  CHECK(r.channels.at("depth.Z")[centre] <= 5.0f + 3.2e-4f);
  CHECK(r.channels.count("variance") == 0);
  CHECK(r.channels.count("half_even.X") == 0);
}

TEST_CASE("aov: black and empty scenes write finite layers, escaped rays have albedo, normal and depth 0") {
  json black = plane_scene();
  black["materials"]["plane"]["reflectance"] = 0.0;
  json empty = json::parse(R"({
    "camera": {"from": [0, 0, -2], "to": [0, 0, 0], "vertical_fov_deg": 20},
    "film": {"resolution": [6, 5]},
    "integrator": {"spp": 4},
    "lights": [{"type": "distant", "direction": [0, 0.3, -1], "irradiance": 1.0}]
  })");
  for (const auto& [scene, name] : {std::pair{black, "black"}, std::pair{empty, "empty"}}) {
    CAPTURE(name);
    const Rendered r = render_scene(scene, name, "all", true);
    for (const auto& [channel, values] : r.channels)
      for (float v : values) {
        CAPTURE(channel);
        CHECK(std::isfinite(v));
      }
    for (float v : r.channels.at("albedo.Y")) CHECK(v == 0.0f);
    if (std::string(name) == "empty") {
      for (float v : r.channels.at("depth.Z")) CHECK(v == 0.0f);
      for (float v : r.channels.at("N.Z")) CHECK(v == 0.0f);
    }
  }
}

TEST_CASE("aov: the image is the same with and without feature layers") {
  const Rendered plain = render_scene(plane_scene(), "plain", "");
  const Rendered layered = render_scene(plane_scene(), "layered", "albedo");
  CHECK(plain.channels.count("albedo.X") == 0);
  for (const char* c : {"X", "Y", "Z"}) CHECK(plain.channels.at(c) == layered.channels.at(c));
}

TEST_CASE("aov: rimu denoise names the layers a render lacks and writes nothing, with them it keeps the noisy beauty") {
  const fs::path dir = fs::temp_directory_path() / "rimu_aov_test";
  const fs::path out = dir / "denoised.exr";
  fs::remove(out);
  render_scene(plane_scene(), "for_denoise_plain", "albedo");
  std::ostringstream log;
  CHECK_THROWS_WITH_AS(denoise_exr_file(dir / "for_denoise_plain.exr", out, {}, log),
                       doctest::Contains("half_even.X"), InputError);
  CHECK_THROWS_WITH_AS(denoise_exr_file(dir / "for_denoise_plain.exr", out, {}, log),
                       doctest::Contains("--aov all"), InputError);
  CHECK_FALSE(fs::exists(out));
  const Rendered full = render_scene(plane_scene(), "for_denoise_full", "all");
  denoise_exr_file(dir / "for_denoise_full.exr", out, {}, log);
  int width = 0;
  const auto denoised = read_exr(out, width);
  CHECK(denoised.at("noisy.Y") == full.channels.at("Y"));
  CHECK(denoised.at("albedo.Y") == full.channels.at("albedo.Y"));
  for (float v : denoised.at("Y")) CHECK(std::isfinite(v));
}

TEST_CASE("aov: partial renders, checkpoints and bad lists are refused before rendering") {
  RenderJob job;
  job.exr_output = fs::temp_directory_path() / "rimu_aov_test_refused.exr";
  job.quiet = true;
  job.aovs = AovSelection::all();
  job.samples = SampleRange{0, 4};
  std::ostringstream log;
  CHECK_THROWS_WITH_AS(run_render_job(job, log), doctest::Contains("--samples"), InputError);
  job.samples.reset();
  job.checkpoint_interval_s = 10.0;
  CHECK_THROWS_WITH_AS(run_render_job(job, log), doctest::Contains("--checkpoint"), InputError);
  job.aovs = {};
  job.denoise = true;
  CHECK_THROWS_WITH_AS(run_render_job(job, log), doctest::Contains("--denoise"), InputError);
  CHECK_FALSE(fs::exists(job.exr_output));
  CHECK_THROWS_WITH_AS(parse_aov_list("albedo,colour", "--aov"), doctest::Contains("'colour'"), InputError);
  CHECK_THROWS_WITH_AS(parse_aov_list("depth,depth", "--aov"), doctest::Contains("twice"), InputError);
  CHECK(aov_list_text(parse_aov_list("normal,albedo", "--aov")) == "albedo,normal");
}

TEST_CASE("aov: the scene's film \"aov\" asks for layers, --aov replaces it, a bad list names the key") {
  json scene = plane_scene();
  scene["film"]["aov"] = "depth";
  const Rendered from_scene = render_scene(scene, "scene_key", "");
  CHECK(from_scene.channels.count("depth.Z") == 1);
  CHECK(from_scene.channels.count("albedo.X") == 0);
  const Rendered replaced = render_scene(scene, "scene_key_replaced", "normal");
  CHECK(replaced.channels.count("N.X") == 1);
  CHECK(replaced.channels.count("depth.Z") == 0);
  scene["film"]["aov"] = "depth,shadows";
  CHECK_THROWS_WITH_AS(render_scene(scene, "scene_key_bad", ""), doctest::Contains("/film/aov"), InputError);
}

TEST_CASE("aov: a subsurface object's albedo is the albedo it was authored with, as a diffuse surface of that colour") {
  // A box of skin-like medium under a smooth diffuse-entry boundary: the boundary BSDF's own one-sample albedo was 0
  // whenever the sample took the mirror lobe; the feature is now the medium's surface albedo A.
  const json colour = {{"rgb", {0.8, 0.3, 0.2}}};
  json diffuse = plane_scene();
  diffuse["materials"]["plane"]["reflectance"] = colour;
  json subsurface = plane_scene();
  subsurface["materials"] = {{"skin", {{"type", "dielectric"}, {"ior", 1.4}, {"diffuse_entry", true}}}};
  subsurface["media"] = {{"flesh", {{"type", "homogeneous"}, {"albedo", colour}, {"mean_free_path", 1.0},
                                    {"mean_free_path_scale_m", 0.01}, {"boundary_material", "skin"},
                                    {"counts_towards_max_depth", false}}}};
  subsurface["shapes"] = {{{"type", "box"}, {"min", {-50, -50, 0}}, {"max", {50, 50, 10}}, {"material", "skin"}}};
  const Rendered plane = render_scene(diffuse, "albedo_plane", "albedo");
  const Rendered skin = render_scene(subsurface, "albedo_subsurface", "albedo");
  for (const char* c : {"albedo.X", "albedo.Y", "albedo.Z"}) {
    CAPTURE(c);
    const std::vector<float>& a = plane.channels.at(c);
    const std::vector<float>& b = skin.channels.at(c);
    REQUIRE(a.size() == b.size());
    for (size_t i = 0; i < a.size(); ++i) CHECK(b[i] == doctest::Approx(a[i]).epsilon(1e-5));
  }
}
