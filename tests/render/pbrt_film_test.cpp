// pbrt-v4's Film sensor, ISO, shutter and white balance, and its spectral and gbuffer films (docs/pbrt-import.md,
// "Film"): imported onto Rimu's physical camera and films; pixel values scale with pbrt's imaging ratio t·S/100.
#include <doctest/doctest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "integration_support.h"
#include "render/render_job.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "pbrt_test_support.h"

using namespace rimu;
using nlohmann::json;

using namespace rimu::test::pbrt_t;

namespace pbrt_film_test {

// The written EXR's three colour channels (X, Y, Z or the camera's R, G, B, in the file's order), as floats.
std::array<std::vector<float>, 3> render_channels(const std::filesystem::path& scene, const std::filesystem::path& exr,
                                                  uint64_t seed) {
  RenderJob job;
  job.scene = scene;
  job.exr_output = exr;
  job.half_exr = false;  // 32-bit floats, the default: half would round to 2^-11 relative
  job.quiet = true;
  job.threads = 1;
  job.seed = seed;
  std::ostringstream log;
  run_render_job(job, log);
  Imf::InputFile file(exr.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  const size_t w = size_t(window.max.x - window.min.x + 1), h = size_t(window.max.y - window.min.y + 1);
  std::vector<std::string> names;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) names.push_back(it.name());
  std::array<std::vector<float>, 3> channels;
  Imf::FrameBuffer fb;
  int found = 0;
  for (const char* set : {"XYZ", "RGB"}) {
    for (int c = 0; c < 3; ++c) {
      const std::string name(1, set[c]);
      if (std::find(names.begin(), names.end(), name) == names.end()) continue;
      channels[size_t(c)].resize(w * h);
      fb.insert(name, Imf::Slice::Make(Imf::FLOAT, channels[size_t(c)].data(), window, sizeof(float), sizeof(float) * w));
      ++found;
    }
  }
  REQUIRE(found == 3);
  file.setFrameBuffer(fb);
  file.readPixels(window.min.y, window.max.y);
  return channels;
}

std::vector<double> as_doubles(const std::vector<float>& v) { return {v.begin(), v.end()}; }

TEST_CASE("pbrt film: iso and the camera's shutter become Rimu's physical camera with pbrt's imaging ratio") {
  const PbrtImport imported = import_text(
      "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float shutteropen\" 0.25 \"float shutterclose\" 0.75\n"
      "Film \"rgb\" \"float iso\" 400 \"float whitebalance\" 5000\nWorldBegin\n");
  CHECK(imported.ignored.empty());
  const json& camera = imported.document["camera"];
  REQUIRE(camera.contains("exposure"));
  CHECK(camera["exposure"]["iso"] == 400.0);
  CHECK(camera["exposure"]["shutter_s"] == 0.5);
  CHECK(camera["exposure"]["compensation_ev"] == 0.0);
  // Rimu's scale 0.18·tS/(12.5 N²) per nit equals pbrt's tS/100 per film unit (72 983 nt) at N = 324.2.
  const double nits_per_unit = SpectralResponse::from_spec(test::library(), "xyz").luminance_nits_per_unit_y();
  const double n = camera["exposure"]["f_number"].get<double>();
  CHECK(0.18 * nits_per_unit / (12.5 * n * n) == doctest::Approx(1.0 / 100.0).epsilon(1e-12));
  CHECK(n == doctest::Approx(324.2).epsilon(1e-3));
  // pbrt's Spectra::D(5000) is CIE daylight at 5000·1.4388/1.4380 K.
  CHECK(camera["white_balance"]["daylight_cct"].get<double>() == doctest::Approx(5002.78).epsilon(1e-5));
  // No iso and no shutter: no physical camera (pbrt's imaging ratio is 1, Rimu's film units); no white balance.
  const json plain = import_text(kCamera + "Film \"rgb\"\nWorldBegin\n").document["camera"];
  CHECK_FALSE(plain.contains("exposure"));
  CHECK_FALSE(plain.contains("white_balance"));
  // Below 4000 K pbrt balances to a blackbody.
  CHECK(import_text(kCamera + "Film \"rgb\" \"float whitebalance\" 3000\nWorldBegin\n").document["camera"]["white_balance"]["cct"]
            .get<double>() == doctest::Approx(3000.0 * 1.4388 / 1.4380));
  // Errors at the statement's line.
  CHECK(import_error("LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float shutteropen\" 1 \"float shutterclose\" 1\nWorldBegin\n")
            .find("t.pbrt:2: Camera: \"shutterclose\" must be later") != std::string::npos);
  CHECK(import_error(kCamera + "Film \"rgb\" \"float iso\" -100\nWorldBegin\n").find("t.pbrt:3") != std::string::npos);
  CHECK(import_error(kCamera + "Film \"rgb\" \"float whitebalance\" 500\nWorldBegin\n").find("t.pbrt:3: Film: \"whitebalance\"") !=
        std::string::npos);
}

TEST_CASE("pbrt film: a camera sensor becomes the colour-corrected camera film with pbrt's default 6500 K white balance") {
  const PbrtImport imported = import_text(kCamera + "Film \"rgb\" \"string sensor\" \"nikon_d850\"\nWorldBegin\n");
  CHECK(imported.document["film"]["response"] == "camera-xyz:pbrt_physlight_nikon_d850_10nm");
  CHECK(imported.document["camera"]["white_balance"]["daylight_cct"].get<double>() == doctest::Approx(6500.0 * 1.4388 / 1.4380));
  CHECK(imported.ignored.empty());  // pbrt-v4's PixelSensor pipeline: the fit to XYZ under the white balance
  CHECK(import_error(kCamera + "Film \"rgb\" \"string sensor\" \"leica_m3\"\nWorldBegin\n")
            .find("t.pbrt:3: Film: unknown \"sensor\" \"leica_m3\"") != std::string::npos);
}

TEST_CASE("pbrt film: spectral buckets, gbuffer, savefp16, maxcomponentvalue, diagonal") {
  const PbrtImport spectral = import_text(kCamera + "Film \"spectral\" \"integer nbuckets\" 8\nWorldBegin\n");
  CHECK(spectral.ignored.empty());
  CHECK(spectral.document["film"]["spectral_bins"] == 8);
  CHECK(import_text(kCamera + "Film \"spectral\"\nWorldBegin\n").document["film"]["spectral_bins"] == 16);  // pbrt's default
  const PbrtImport narrow = import_text(kCamera + "Film \"spectral\" \"float lambdamin\" 400 \"float lambdamax\" 700\nWorldBegin\n");
  REQUIRE(narrow.ignored.size() == 1);
  CHECK(narrow.ignored[0].what.find("lambdamin") != std::string::npos);
  const PbrtImport gbuffer = import_text(kCamera + "Film \"gbuffer\" \"string coordinatesystem\" \"world\"\nWorldBegin\n");
  REQUIRE(gbuffer.ignored.size() == 1);
  CHECK(gbuffer.ignored[0].what.find("Film \"gbuffer\": the auxiliary channels") == 0);
  CHECK_FALSE(gbuffer.document["film"].contains("spectral_bins"));
  // Rimu writes 32-bit floats unless run with --half: savefp16 false (or unset) is honoured, true is listed; a
  // sample clamp becomes the film's (a value that is not > 0 is listed).
  CHECK(import_text(kCamera + "Film \"rgb\" \"bool savefp16\" false \"float diagonal\" 50\nWorldBegin\n").ignored.empty());
  const PbrtImport fp16 = import_text(kCamera + "Film \"rgb\" \"bool savefp16\" true\nWorldBegin\n");
  REQUIRE(fp16.ignored.size() == 1);
  CHECK(fp16.ignored[0].what.find("--half") != std::string::npos);
  const PbrtImport clamped = import_text(kCamera + "Film \"rgb\" \"float maxcomponentvalue\" 10\nWorldBegin\n");
  CHECK(clamped.ignored.empty());
  CHECK(clamped.document["film"]["max_sample_value"] == 10.0);
  CHECK(import_text(kCamera + "Film \"rgb\" \"float maxcomponentvalue\" 0\nWorldBegin\n").ignored.size() == 1);
  // "exposuretime" is no pbrt-v4 Film parameter (the time is the camera's shutter): reported as unused.
  CHECK(import_text(kCamera + "Film \"rgb\" \"float exposuretime\" 2\nWorldBegin\n").ignored.size() == 1);
}

TEST_CASE("pbrt film: a camera sensor with iso, shutter and white balance renders as the hand-written JSON") {
  const test::ScratchFolder folder("pbrt-film-sensor");
  const auto pbrt = render_channels(test::test_data("pbrt/film_sensor.pbrt"), folder / "pbrt.exr", 1);
  // The importer writes pbrt's spectra for the file's RGB reflectances (docs/pbrt-import.md, "RGB parameters"), which
  // the camera sees differently from the JSON's upsampled {"rgb"}: the hand-written scene gets the same spectra.
  json equivalent = json::parse(std::ifstream(test::test_data("pbrt/film_sensor_equivalent.json")));
  for (auto& [name, material] : equivalent["materials"].items()) {
    const std::vector<double> rgb = material["reflectance"]["rgb"];
    material["reflectance"] = test::pbrt_rgb_reflectance(rgb[0], rgb[1], rgb[2]);
  }
  std::ofstream(folder / "equivalent.json") << equivalent.dump();
  const auto json_render = render_channels(folder / "equivalent.json", folder / "json.exr", 2);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    for (double deviation : test::block_deviations(as_doubles(pbrt[size_t(c)]), as_doubles(json_render[size_t(c)])))
      CHECK(deviation <= test::kSigmas);
  }
  // The comparison can fail: the same JSON without the white balance is caught.
  json unbalanced = equivalent;
  unbalanced["camera"].erase("white_balance");
  std::ofstream(folder / "unbalanced.json") << unbalanced.dump();
  const auto other = render_channels(folder / "unbalanced.json", folder / "unbalanced.exr", 2);
  double worst = 0.0;
  for (double deviation : test::block_deviations(as_doubles(pbrt[0]), as_doubles(other[0])))
    worst = std::max(worst, deviation);
  CHECK(worst > test::kSigmas);
}

TEST_CASE("pbrt film: pixel values scale exactly with iso times exposure time") {
  // The same seed renders the same film; only the written scale differs. ISO 100 over 1 s (pbrt's defaults given
  // explicitly) writes the film values themselves: pbrt's imaging ratio 1.
  const test::ScratchFolder folder("pbrt-film-iso");
  const auto scene = [&](const std::string& name, const std::string& camera, const std::string& film) {
    std::ifstream in(test::test_data("pbrt/film_sensor.pbrt"));
    std::ostringstream out;
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("Camera", 0) == 0) line = "Camera \"perspective\" \"float fov\" 30 " + camera;
      else if (line.rfind("Film", 0) == 0) line = "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 32 " + film;
      else if (line.rfind("  \"float iso\"", 0) == 0) continue;
      out << line << "\n";
    }
    const auto path = folder / name;
    std::ofstream(path) << out.str();
    return path;
  };
  const auto plain = render_channels(scene("plain.pbrt", "", ""), folder / "plain.exr", 7);
  const auto unit = render_channels(scene("unit.pbrt", "\"float shutterclose\" 1", "\"float iso\" 100"), folder / "unit.exr", 7);
  const auto eight = render_channels(scene("eight.pbrt", "\"float shutteropen\" 0.5 \"float shutterclose\" 2.5", "\"float iso\" 400"),
                                     folder / "eight.exr", 7);
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) {
    for (size_t i = 0; i < plain[size_t(c)].size(); ++i) {
      const double v = plain[size_t(c)][i];
      sum += v;
      CHECK(unit[size_t(c)][i] == doctest::Approx(v).epsilon(1e-6));
      CHECK(eight[size_t(c)][i] == doctest::Approx(8.0 * v).epsilon(1e-6));  // t·S/100 = 2·400/100
    }
  }
  CHECK(sum > 0.0);
}

}  // namespace pbrt_film_test

TEST_CASE("pbrt parameters given twice: pbrt-v4 reads the first, and the second is listed") {
  // pbrt-v3-scenes' contemporary-bathroom.pbrt gives its resolution twice (a second line added under the first).
  const PbrtImport imported = test::import_pbrt_test_text(
      "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 40 "
      "\"integer yresolution\" 30\n  \"integer xresolution\" 80 \"integer yresolution\" 60\nWorldBegin\n");
  CHECK(imported.document["film"]["resolution"] == nlohmann::json::array({40, 30}));
  REQUIRE(imported.ignored.size() == 2);
  CHECK_CONTAINS(imported.ignored[0].what, "\"integer xresolution\"", "given again", "reads the first");
  CHECK(imported.ignored[0].first.line == 4);
}
