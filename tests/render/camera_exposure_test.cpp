// The physical camera through the whole `rimu` path (scene keys and job options → run_render_job → EXR): an 18 %
// card under a sunny-16 sun is written at the value the reflected-light meter equation gives (ISO 2720, K = 12.5),
// and white balance makes a white card lit by a warm light neutral (D65's chromaticity on an XYZ film).
#include <doctest/doctest.h>

#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <ImfDoubleAttribute.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <unistd.h>

#include "render/camera/camera_exposure.h"
#include "render/render_job.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

using rimu::test::kPi;

// A Lambertian card of `reflectance` filling the view, lit at normal incidence by a sun of `spectrum` and `lux`.
json card_scene(double reflectance, json spectrum, double lux, json camera_extra) {
  json camera{{"from", {0.0, 0.0, 3.0}}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 20}};
  camera.update(camera_extra);
  return json{{"camera", camera},
              {"film", {{"resolution", {16, 16}}, {"filter", {{"type", "box"}}}}},
              {"integrator", {{"spp", 8}, {"max_depth", 2}}},
              {"materials", {{"card", {{"type", "diffuse"}, {"reflectance", reflectance}}}}},
              {"lights", json::array({{{"type", "distant"}, {"direction", {0, 0, 1}}, {"spectrum", spectrum},
                                       {"illuminance_lx", lux}}})},
              {"shapes", json::array({{{"type", "quad"}, {"vertices", {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}}},
                                       {"material", "card"}}})}};
}

struct WrittenImage {
  std::vector<float> x, y, z;
  Imf::Header header;
};

// Writes the scene, runs the job on it and reads the EXR's X, Y, Z back.
WrittenImage render_job(const json& scene, RenderJob job) {
  const fs::path folder = fs::temp_directory_path() / ("rimu-camera-exposure-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  std::ofstream(folder / "scene.json") << scene.dump(2);
  job.scene = folder / "scene.json";
  job.exr_output = folder / "out.exr";
  job.half_exr = false;  // 32-bit floats, the default: half would round the values to 2^-11 relative
  job.quiet = true;
  job.threads = 1;
  std::ostringstream log;
  run_render_job(job, log);
  Imf::InputFile file(job.exr_output.c_str());
  WrittenImage image;
  image.header = file.header();
  const Imath::Box2i window = file.header().dataWindow();
  const size_t w = size_t(window.max.x - window.min.x + 1), h = size_t(window.max.y - window.min.y + 1);
  Imf::FrameBuffer fb;
  for (auto [name, values] : {std::pair{"X", &image.x}, {"Y", &image.y}, {"Z", &image.z}}) {
    values->resize(w * h);
    fb.insert(name, Imf::Slice::Make(Imf::FLOAT, values->data(), window, sizeof(float), sizeof(float) * w));
  }
  file.setFrameBuffer(fb);
  file.readPixels(window.min.y, window.max.y);
  fs::remove_all(folder);
  return image;
}

// The mean of per-pixel values d_i and its standard error (pixels are independent estimates of the same value).
std::pair<double, double> mean_and_error(const std::vector<double>& d) {
  double sum = 0.0, sum2 = 0.0;
  for (double v : d) sum += v;
  const double mean = sum / double(d.size());
  for (double v : d) sum2 += (v - mean) * (v - mean);
  return {mean, std::sqrt(sum2 / double(d.size() - 1) / double(d.size()))};
}

}  // namespace

TEST_CASE("an 18 percent card at sunny 16 is written at the meter-equation value, K = 12.5") {
  // L = ρE/π = 0.18·100000/π = 5729.6 nt; sunny 16 (f/16, 1/100 s, ISO 100): L_m = 12.5·16²/(0.01·100) = 3200 nt;
  // written value v = 0.18·L/L_m = 0.32228. Tolerance: 5 standard errors over the 256 pixels (the card is flat
  // and its light deterministic; the noise is the hero-wavelength sampling).
  const double expected = 0.18 * (0.18 * 100000.0 / kPi) / 3200.0;
  auto check_card = [&](const WrittenImage& image) {
    std::vector<double> y(image.y.begin(), image.y.end());
    const auto [mean, error] = mean_and_error(y);
    CAPTURE(mean);
    CAPTURE(error);
    CHECK(error < 0.005 * expected);
    CHECK(std::abs(mean - expected) <= 5.0 * error);
  };
  SUBCASE("from the scene's camera keys") {
    const json exposure{{"iso", 100}, {"shutter_s", 0.01}, {"f_number", 16}, {"compensation_ev", 0}};
    const WrittenImage image = render_job(card_scene(0.18, {{"daylight", 5500}}, 100000.0, {{"exposure", exposure}}), {});
    check_card(image);
    // The metadata records the settings; luminanceNitsPerUnitY describes the written Y: L_m/0.18 = 17 777.8 nt.
    CHECK(image.header.typedAttribute<Imf::StringAttribute>("rimu:iso").value() == "100");
    CHECK(image.header.typedAttribute<Imf::StringAttribute>("rimu:fNumber").value() == "16");
    CHECK(image.header.typedAttribute<Imf::StringAttribute>("rimu:meteredLuminanceNits").value() == "3200");
    CHECK(image.header.typedAttribute<Imf::DoubleAttribute>("rimu:luminanceNitsPerUnitY").value() ==
          doctest::Approx(3200.0 / 0.18).epsilon(1e-12));
  }
  SUBCASE("job options override the scene (f/8 in the scene, f/16 on the command line)") {
    const json exposure{{"iso", 100}, {"shutter_s", 0.01}, {"f_number", 8}};
    RenderJob job;
    job.f_number = 16.0;
    check_card(render_job(card_scene(0.18, {{"daylight", 5500}}, 100000.0, {{"exposure", exposure}}), job));
  }
  SUBCASE("job options alone turn the physical camera on") {
    RenderJob job;
    job.iso = 200.0;
    job.compensation_ev = -1.0;  // +1 stop of ISO, −1 stop of compensation: sunny 16 again
    check_card(render_job(card_scene(0.18, {{"daylight", 5500}}, 100000.0, json::object()), job));
  }
}

TEST_CASE("white balance to the light's own white makes a white card neutral") {
  // A white card (ρ = 0.9) under a 2700 K blackbody sun. Balanced to 2700 K, the XYZ film's white is D65's:
  // x 0.31272, y 0.32903 (CIE 15:2004 Table T.3; the CAT maps the source white onto D65's exactly, and the 1 nm sums
  // of the film agree with the 5 nm table to ±2e-5). Chromaticity errors: first-order (delta method) standard
  // errors over the pixels, 5 of them, plus the table's 2e-5.
  auto chromaticity = [](const WrittenImage& image) {
    double sx = 0, sy = 0, sz = 0;
    const size_t n = image.x.size();
    for (size_t i = 0; i < n; ++i) sx += image.x[i], sy += image.y[i], sz += image.z[i];
    const double s = sx + sy + sz, x = sx / s, y = sy / s;
    std::vector<double> dx(n), dy(n);
    for (size_t i = 0; i < n; ++i) {
      const double si = double(image.x[i]) + image.y[i] + image.z[i];
      dx[i] = (image.x[i] - x * si) / (s / double(n));
      dy[i] = (image.y[i] - y * si) / (s / double(n));
    }
    return std::array<double, 4>{x, y, mean_and_error(dx).second, mean_and_error(dy).second};
  };
  for (const json& balance : {json{{"cct", 2700}}, json("none")}) {
    CAPTURE(balance.dump());
    const auto c = chromaticity(render_job(card_scene(0.9, {{"blackbody", 2700}}, 1000.0, {{"white_balance", balance}}), {}));
    CAPTURE(c[0]);
    CAPTURE(c[1]);
    if (balance.is_object()) {
      CHECK(c[2] < 1e-3);
      CHECK(std::abs(c[0] - 0.31272) <= 5.0 * c[2] + 2e-5);
      CHECK(std::abs(c[1] - 0.32903) <= 5.0 * c[3] + 2e-5);
    } else {
      // Unbalanced, the card has the light's own colour: x ≈ 0.46 for 2700 K (CIE 15 Planckian locus).
      CHECK(c[0] > 0.44);
    }
  }
  SUBCASE("the same from the command line's --white-balance") {
    RenderJob job;
    job.white_balance = "2700K";
    const auto c = chromaticity(render_job(card_scene(0.9, {{"blackbody", 2700}}, 1000.0, json::object()), job));
    CHECK(std::abs(c[0] - 0.31272) <= 5.0 * c[2] + 2e-5);
    CHECK(std::abs(c[1] - 0.32903) <= 5.0 * c[3] + 2e-5);
  }
}

TEST_CASE("physical camera inputs: bad settings are InputErrors naming the key or option") {
  CHECK_THROWS_WITH_AS(
      render_job(card_scene(0.18, 1.0, 100.0, {{"exposure", {{"iso", 0}, {"shutter_s", 0.01}, {"f_number", 16}}}}), {}),
      doctest::Contains("/camera/exposure/iso"), InputError);
  CHECK_THROWS_WITH_AS(render_job(card_scene(0.18, 1.0, 100.0, {{"white_balance", {{"illuminant", "D66"}}}}), {}),
                       doctest::Contains("/camera/white_balance/illuminant"), InputError);
  CHECK_THROWS_WITH_AS(render_job(card_scene(0.18, 1.0, 100.0, {{"white_balance", {{"cct", 500}}}}), {}),
                       doctest::Contains("/camera/white_balance/cct"), InputError);
  CHECK(parse_shutter_time_s("1/100", "--shutter") == 0.01);
  CHECK(parse_shutter_time_s("0.5", "--shutter") == 0.5);
  CHECK_THROWS_WITH_AS(parse_shutter_time_s("fast", "--shutter"), doctest::Contains("--shutter"), InputError);
  CHECK_THROWS_WITH_AS(parse_shutter_time_s("1/0", "--shutter"), doctest::Contains("--shutter"), InputError);
}
