// The `rimu` job's outputs end to end (run_render_job): options that cannot work fail before the render and leave
// no file; formats follow the file names; no NaN or Inf reaches an image; a photometric scene without a camera
// exposure gets a usable display image; a camera film is displayed through its fitted matrix; the EXR is 32-bit float
// unless --half; and the files carry the standard metadata other programs read (the PNG's sRGB chunk, OpenEXR's
// standard attributes, the spectral layout's emissiveUnits); `rimu display` makes the same display image from the EXR.
#include <doctest/doctest.h>

#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "render/camera/physical_camera.h"
#include "render/output/exr_display_source.h"
#include "render/render_job.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A Lambertian card of `reflectance` filling the view, lit at normal incidence by a distant light `light`
// (spectrum and amount keys), with `camera_extra` merged into the camera.
json card_scene(double reflectance, const json& light, const json& camera_extra = json::object()) {
  json camera{{"from", {0.0, 0.0, 3.0}}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 20}};
  camera.update(camera_extra);
  json distant{{"type", "distant"}, {"direction", {0, 0, 1}}};
  distant.update(light);
  return json{{"camera", camera},
              {"film", {{"resolution", {8, 8}}, {"filter", {{"type", "box"}}}}},
              {"integrator", {{"spp", 2}, {"max_depth", 2}}},
              {"materials", {{"card", {{"type", "diffuse"}, {"reflectance", reflectance}}}}},
              {"lights", json::array({distant})},
              {"shapes", json::array({{{"type", "quad"},
                                       {"vertices", {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}}},
                                       {"material", "card"}}})}};
}

const json kPhotometricSun{{"spectrum", {{"illuminant", "D65"}}}, {"illuminance_lx", 1000}};

struct Workspace {
  fs::path folder;
  explicit Workspace(const std::string& name)
      : folder(fs::temp_directory_path() / ("rimu-job-outputs-" + name + "-" + std::to_string(::getpid()))) {
    fs::remove_all(folder);
    fs::create_directories(folder);
  }
  ~Workspace() { fs::remove_all(folder); }
  // A job on `scene` writing folder/out.exr, quiet, one thread.
  RenderJob job(const json& scene) const {
    std::ofstream(folder / "scene.json") << scene.dump(2);
    RenderJob j;
    j.scene = folder / "scene.json";
    j.exr_output = folder / "out.exr";
    j.quiet = true;
    j.threads = 1;
    return j;
  }
  size_t files_besides_scene() const {
    size_t n = 0;
    for (const auto& entry : fs::directory_iterator(folder)) n += entry.path().filename() != "scene.json";
    return n;
  }
};

std::string message_of(const RenderJob& job) {
  std::ostringstream log;
  try {
    run_render_job(job, log);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("expected an InputError; log: " << log.str());
  return {};
}

struct Png {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  std::string format;
};
Png read_image(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  REQUIRE(in);
  Png png{in->spec().width, in->spec().height, {}, in->format_name()};
  png.rgb.resize(size_t(png.width) * size_t(png.height) * 3);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, png.rgb.data()));
  return png;
}
double mean_of(const std::vector<uint8_t>& v, int channel = -1) {
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < v.size(); ++i)
    if (channel < 0 || int(i % 3) == channel) sum += v[i], ++n;
  return sum / double(n);
}

}  // namespace

TEST_CASE("-o and --png naming one file are refused before rendering") {
  Workspace w("same");
  RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
  job.exr_output = w.folder / "same.exr";
  job.png_output = w.folder / "sub" / ".." / "same.exr";
  const std::string what = message_of(job);
  CHECK(what.find("same file") != std::string::npos);
  CHECK(w.files_besides_scene() == 0);
}

TEST_CASE("file formats follow the names: -o is OpenEXR only, --png writes PNG, JPEG or TIFF by extension") {
  Workspace w("formats");
  SUBCASE("-o with another extension is refused") {
    RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
    job.exr_output = w.folder / "out.png";
    CHECK(message_of(job).find("needs a name ending in .exr") != std::string::npos);
    CHECK(w.files_besides_scene() == 0);
  }
  SUBCASE("an extension OpenImageIO's display formats do not have is refused") {
    RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
    job.png_output = w.folder / "v.bmp";
    CHECK(message_of(job).find("expected .png, .jpg") != std::string::npos);
    CHECK(w.files_besides_scene() == 0);
  }
  SUBCASE("--png v.jpg is a JPEG, v.TIF a TIFF, v.png a PNG") {
    for (const auto& [name, format] : {std::pair{"v.jpg", "jpeg"}, {"v.TIF", "tiff"}, {"v.png", "png"}}) {
      RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
      job.png_output = w.folder / name;
      std::ostringstream log;
      run_render_job(job, log);
      CAPTURE(name);
      CHECK(read_image(w.folder / name).format == format);
    }
  }
}

TEST_CASE("options that cannot work fail before the render, leave no file and name the user's path") {
  Workspace w("early");
  RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
  job.png_output = w.folder / "v.png";
  SUBCASE("unknown view") {
    job.view = "bogus";
    CHECK(message_of(job).find("unknown view 'bogus'") != std::string::npos);
  }
  SUBCASE("non-finite or huge display exposure") {
    job.exposure_ev = std::nan("");
    CHECK(message_of(job).find("--exposure") != std::string::npos);
    job.exposure_ev = 2000.0;
    CHECK(message_of(job).find("--exposure") != std::string::npos);
  }
  SUBCASE("a display image in a folder where nothing can be created") {
    job.png_output = "/proc/rimu-test.png";
    const std::string what = message_of(job);
    CHECK(what.find("/proc/rimu-test.png") != std::string::npos);
    CHECK(what.find("rimu-incomplete") == std::string::npos);
  }
  SUBCASE("an EXR in a folder where nothing can be created") {
    job.exr_output = "/proc/rimu-test.exr";
    CHECK(message_of(job).find("/proc/rimu-test.exr") != std::string::npos);
  }
  CHECK(w.files_besides_scene() == 0);
}

TEST_CASE("physical camera options outside the scene keys' ranges are InputErrors naming the option, before rendering") {
  // ISO 1e-300, 1e-300 s, f/1e-300 made 0/0 = NaN of the exposure scale (an all-NaN image, exit 0); --ev 2000 and
  // ISO inf made it Inf.
  Workspace w("camera");
  RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
  SUBCASE("ISO, shutter and f-number of 1e-300") {
    job.iso = 1e-300;
    job.shutter_s = 1e-300;
    job.f_number = 1e-300;
    CHECK(message_of(job).find("--iso") != std::string::npos);
  }
  SUBCASE("--ev 2000") {
    job.compensation_ev = 2000.0;
    CHECK(message_of(job).find("--ev: expected an exposure compensation in stops in -30 to 30") != std::string::npos);
  }
  SUBCASE("--iso inf") {
    job.iso = INFINITY;
    CHECK(message_of(job).find("--iso") != std::string::npos);
  }
  SUBCASE("--f-number nan") {
    job.f_number = NAN;
    CHECK(message_of(job).find("--f-number") != std::string::npos);
  }
  CHECK(w.files_besides_scene() == 0);
}

TEST_CASE("an exposure scale that underflows or overflows is bad input, not an image of NaN or Inf") {
  // Direct library callers bypass the option ranges: 0/0 and 2^2000 must still not become an image.
  const SpectralResponse xyz = SpectralResponse::cie_xyz(test::library());
  CHECK_THROWS_AS(film_exposure_scale(PhysicalCameraSettings{1e-300, 1e-300, 1e-300, 0.0}, xyz), InputError);
  CHECK_THROWS_AS(film_exposure_scale(PhysicalCameraSettings{100.0, 0.01, 16.0, 2000.0}, xyz), InputError);
  CHECK_THROWS_AS(film_exposure_scale(PhysicalCameraSettings{100.0, 0.01, 16.0, -2000.0}, xyz), InputError);
  CHECK(film_exposure_scale(PhysicalCameraSettings{}, xyz) > 0.0);
}

TEST_CASE("a photometric scene without a camera exposure gets a metered display image, the EXR stays in film units") {
  // An 18 % card under 1000 lx: L = 0.18·1000/π = 57.3 nt, Y = L/72 983 in film units, which the Standard view
  // showed at code 2-3 of 255. Metered, the mean luminance is shown as 0.18, sRGB-encoded 0.4614 → code 117.7;
  // the card is uniform and D65-lit, so every channel is near it. ±6 codes: the 2-spp noise of an 8×8 film is
  // about ±2 % in Y (±1 code after encoding), and OCIO's sRGB matrix differs from IEC's 4-decimal one by < 0.3.
  Workspace w("metered");
  RenderJob job = w.job(card_scene(0.18, kPhotometricSun));
  job.png_output = w.folder / "v.png";
  job.quiet = false;  // the note on metering is not printed with -q
  std::ostringstream log;
  run_render_job(job, log);
  CHECK(log.str().find("metered") != std::string::npos);
  const Png png = read_image(w.folder / "v.png");
  for (int c = 0; c < 3; ++c) CHECK(mean_of(png.rgb, c) == doctest::Approx(117.7).epsilon(6.0 / 117.7));
  CHECK(log.str().find("nearly black") == std::string::npos);

  SUBCASE("--exposure is compensation on top of the meter") {
    job.exposure_ev = -1.0;  // 0.09 → code 84.6
    std::ostringstream log2;
    run_render_job(job, log2);
    CHECK(mean_of(read_image(w.folder / "v.png").rgb, 1) == doctest::Approx(84.6).epsilon(5.0 / 84.6));
  }
  SUBCASE("the same light through \"include\" (a rimu-light definition) is metered as well") {
    // Before, only the scene file was searched for photometric keys: the included sun left the image near black.
    json sun{{"type", "distant"}, {"direction", {0, 0, 1}}};
    sun.update(kPhotometricSun);
    std::ofstream(w.folder / "sun.json") << sun.dump();
    json scene = card_scene(0.18, kPhotometricSun);
    scene["lights"] = json::array({{{"include", "sun.json"}}});
    RenderJob included = w.job(scene);
    included.png_output = w.folder / "included.png";
    included.quiet = false;
    std::ostringstream log2;
    run_render_job(included, log2);
    CHECK(log2.str().find("metered") != std::string::npos);
    const Png png = read_image(w.folder / "included.png");
    for (int c = 0; c < 3; ++c) CHECK(mean_of(png.rgb, c) == doctest::Approx(117.7).epsilon(6.0 / 117.7));
  }
}

TEST_CASE("a nearly black or nearly all clipped display image is warned about, with the fraction") {
  Workspace w("levels");
  // A radiometric scene (no metering): 1e-6 W/m² is black on display, and +30 stops clips it.
  RenderJob job = w.job(card_scene(0.5, {{"spectrum", {{"illuminant", "D65"}}}, {"irradiance_w_m2", 1e-6}}));
  job.png_output = w.folder / "v.png";
  std::ostringstream dark;
  run_render_job(job, dark);
  CHECK(dark.str().find("100 % of " + job.png_output->string() + " is nearly black") != std::string::npos);
  CHECK(dark.str().find("--exposure") != std::string::npos);
  job.exposure_ev = 40.0;
  std::ostringstream bright;
  run_render_job(job, bright);
  CHECK(bright.str().find("100 % of " + job.png_output->string() + " is clipped") != std::string::npos);
}

TEST_CASE("a camera film is displayed through its fitted camera-to-XYZ matrix, written in the EXR") {
  // A grey card under D65 through the Nikon D850: raw sensor R, G, B shown as Rec.709 were green (G/R ≈ 1.9 for
  // D65 on this sensor). Through the fitted matrix the grey is grey: each channel within 4 % of the mean (the fit's
  // residual on the ColorChecker's neutral patches is well under 1 ΔE00, i.e. under 1 % in chroma).
  Workspace w("camera-film");
  RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
  job.film = "camera:nikon_d850";
  job.png_output = w.folder / "v.png";
  job.quiet = false;  // the note on the fitted matrix is not printed with -q
  std::ostringstream log;
  run_render_job(job, log);
  CHECK(log.str().find("camera-to-XYZ matrix fitted") != std::string::npos);
  const Png png = read_image(w.folder / "v.png");
  const double r = mean_of(png.rgb, 0), g = mean_of(png.rgb, 1), b = mean_of(png.rgb, 2), mean = (r + g + b) / 3;
  CAPTURE(r);
  CAPTURE(g);
  CAPTURE(b);
  for (double v : {r, g, b}) CHECK(std::abs(v - mean) < 0.04 * mean);
  Imf::InputFile exr((w.folder / "out.exr").c_str());
  const auto* m = exr.header().findTypedAttribute<Imf::M33fAttribute>("cameraToXYZ");
  REQUIRE(m != nullptr);
  CHECK(m->value()[1][1] > 0.0f);  // G contributes to Y
}

TEST_CASE("the files carry the standard metadata: PNG sRGB chunk, EXR standard attributes, spectral emissiveUnits") {
  Workspace w("metadata");
  RenderJob job = w.job(card_scene(0.18, kPhotometricSun));
  job.png_output = w.folder / "v.png";
  job.iso = 400.0;
  job.shutter_s = 1.0 / 50.0;
  job.f_number = 2.8;
  job.film = "spectral:4";
  std::ostringstream log;
  run_render_job(job, log);

  // PNG: an sRGB chunk (chunk type bytes "sRGB" after a length) so browsers and viewers colour-manage it as sRGB.
  std::ifstream png_file(w.folder / "v.png", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(png_file)), std::istreambuf_iterator<char>());
  CHECK(bytes.find("sRGB") != std::string::npos);

  Imf::InputFile exr((w.folder / "out.exr").c_str());
  const Imf::Header& h = exr.header();
  REQUIRE(Imf::hasIsoSpeed(h));
  CHECK(Imf::isoSpeed(h) == doctest::Approx(400.0));
  REQUIRE(Imf::hasExpTime(h));
  CHECK(Imf::expTime(h) == doctest::Approx(0.02));
  REQUIRE(Imf::hasAperture(h));
  CHECK(Imf::aperture(h) == doctest::Approx(2.8));
  // whiteLuminance = the written Y = 1 in cd/m²: L_m/0.18 = 12.5·2.8²/(0.02·400)/0.18 = 68.06 nt.
  REQUIRE(Imf::hasWhiteLuminance(h));
  CHECK(Imf::whiteLuminance(h) == doctest::Approx(12.5 * 2.8 * 2.8 / (0.02 * 400.0) / 0.18).epsilon(1e-6));
  REQUIRE(Imf::hasCapDate(h));
  CHECK(Imf::capDate(h).size() == 19);  // "YYYY:MM:DD hh:mm:ss"
  CHECK(Imf::hasUtcOffset(h));
  const auto* software = h.findTypedAttribute<Imf::StringAttribute>("software");
  REQUIRE(software != nullptr);
  CHECK(software->value().rfind("Rimu ", 0) == 0);
  const auto* units = h.findTypedAttribute<Imf::StringAttribute>("emissiveUnits");
  REQUIRE(units != nullptr);
  CHECK(units->value() == "W.m^-2.sr^-1");
  CHECK(h.find("rimu:spectralUnits") == h.end());
  CHECK(h.findTypedAttribute<Imf::StringAttribute>("spectralLayoutVersion")->value() == "1.0");
}

TEST_CASE("the EXR holds 32-bit floats by default, half floats only with --half, and then a dim scene is warned about") {
  // An 18 % card under 0.1 lx (a bright moonlit night) without an exposure: L = 0.18·0.1/π cd/m², Y = L/72 983 =
  // 7.85e-8 in film units, below half's smallest normal value (6.1e-5), where half steps by 2⁻²⁴ ≈ 6e-8: the card
  // would be written as 1 or 2 of those steps. 16 spp over 64 pixels: the mean's noise is about 1 %; ±5 %.
  Workspace w("pixel-type");
  RenderJob job = w.job(card_scene(0.18, {{"spectrum", {{"illuminant", "D65"}}}, {"illuminance_lx", 0.1}}));
  job.samples_per_pixel = 16;
  auto y_channel = [&](Imf::PixelType& type) {
    Imf::InputFile exr((w.folder / "out.exr").c_str());
    const Imath::Box2i window = exr.header().dataWindow();
    const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
    REQUIRE(exr.header().channels().findChannel("Y") != nullptr);
    type = exr.header().channels().findChannel("Y")->type;
    std::vector<float> y(size_t(width) * size_t(height));
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data() - window.min.x - window.min.y * width),
                                 sizeof(float), sizeof(float) * size_t(width)));
    exr.setFrameBuffer(frame);
    exr.readPixels(window.min.y, window.max.y);
    return y;
  };
  const double expected_y = 0.18 * 0.1 / M_PI / 72983.0;

  std::ostringstream log;
  run_render_job(job, log);
  Imf::PixelType type{};
  const std::vector<float> y = y_channel(type);
  CHECK(type == Imf::FLOAT);
  double sum = 0;
  for (float v : y) sum += v;
  CHECK(sum / double(y.size()) == doctest::Approx(expected_y).epsilon(0.05));
  CHECK(log.str().find("half floats") == std::string::npos);

  job.half_exr = true;
  std::ostringstream half_log;
  run_render_job(job, half_log);
  const std::vector<float> half_y = y_channel(type);
  CHECK(type == Imf::HALF);
  for (float v : half_y) CHECK(std::ldexp(double(v), 24) == std::round(std::ldexp(double(v), 24)));  // whole steps
  CHECK(half_log.str().find(job.exr_output.string() + " is written as half floats: 100 % of the non-zero values lie "
                                                      "below half's normal range") != std::string::npos);
  CHECK(half_log.str().find("without --half") != std::string::npos);
}

namespace {

// The largest difference of two display images' codes (same size required).
int largest_code_difference(const Png& a, const Png& b) {
  REQUIRE(a.rgb.size() == b.rgb.size());
  int largest = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) largest = std::max(largest, std::abs(int(a.rgb[i]) - int(b.rgb[i])));
  return largest;
}

}  // namespace

TEST_CASE("rimu display: an EXR's display image equals the render's own, metering and camera matrix included") {
  // The EXR holds each pixel as a float32 of the film's double value: a code can differ by one where a value lies
  // on a rounding boundary of the 8-bit encoding, never by more.
  Workspace w("display");
  const auto render_and_display = [&](RenderJob job, double exposure_ev, const std::string& name) {
    job.png_output = w.folder / (name + "_render.png");
    job.exposure_ev = exposure_ev;
    std::ostringstream render_log, display_log;
    run_render_job(job, render_log);
    DisplayOptions options;
    options.exposure_ev = exposure_ev;
    const fs::path shown = w.folder / (name + "_display.png");
    write_exr_display_image(job.exr_output, shown, options, false, display_log);
    const Png rendered = read_image(*job.png_output);
    CHECK(mean_of(rendered.rgb) > 20.0);  // neither black nor clipped, so equal codes say something
    CHECK(mean_of(rendered.rgb) < 235.0);
    CHECK(largest_code_difference(rendered, read_image(shown)) <= 1);
    return display_log.str();
  };
  SUBCASE("a photometric scene is metered again, --exposure on top") {
    const RenderJob job = w.job(card_scene(0.18, kPhotometricSun));
    CHECK(render_and_display(job, 0.0, "metered").find("metered") != std::string::npos);
    render_and_display(job, -1.5, "compensated");
  }
  SUBCASE("film units, another exposure") {
    const RenderJob job = w.job(card_scene(0.5, {{"spectrum", {{"illuminant", "D65"}}}, {"irradiance_w_m2", 500.0}}));
    CHECK(render_and_display(job, 1.0, "film_units").find("metered") == std::string::npos);
  }
  SUBCASE("a camera film through its fitted matrix") {
    RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
    job.film = "camera:nikon_d850";
    CHECK(render_and_display(job, 0.0, "camera").find("camera-to-XYZ matrix") != std::string::npos);
  }
  SUBCASE("a partial render through its sums") {
    RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
    job.samples = SampleRange{0, 2};
    render_and_display(job, 0.5, "partial");
  }
  SUBCASE("bad input: nothing is written") {
    const RenderJob job = w.job(card_scene(0.5, kPhotometricSun));
    std::ostringstream log;
    run_render_job(job, log);
    const auto refused = [&](const fs::path& exr, const fs::path& shown, const std::string& expected) {
      try {
        write_exr_display_image(exr, shown, {}, false, log);
        FAIL("expected an InputError");
      } catch (const InputError& e) {
        CHECK_MESSAGE(std::string(e.what()).find(expected) != std::string::npos, e.what());
      }
      CHECK(!fs::exists(shown));
    };
    refused(job.exr_output, w.folder / "shown.bmp", "expected .png");
    refused(w.folder / "missing.exr", w.folder / "shown.png", "missing.exr");
    // An EXR Rimu did not write (no rimu:filmResponse): written here through OpenImageIO.
    const fs::path foreign = w.folder / "foreign.exr";
    {
      auto out = OIIO::ImageOutput::create(foreign.string());
      REQUIRE(out);
      const std::vector<float> pixels(4 * 4 * 3, 0.5f);
      REQUIRE(out->open(foreign.string(), OIIO::ImageSpec(4, 4, 3, OIIO::TypeDesc::FLOAT)));
      REQUIRE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
      out->close();
    }
    refused(foreign, w.folder / "shown.png", "is not an image Rimu wrote");
    // The display image may not replace the EXR it is made from.
    try {
      write_exr_display_image(job.exr_output, job.exr_output, {}, false, log);
      FAIL("expected an InputError");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(".exr") != std::string::npos);
    }
    CHECK(fs::file_size(job.exr_output) > 0);
  }
}
