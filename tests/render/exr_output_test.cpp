// EXR output: values, channels, chromaticities and metadata survive a round trip; failures leave nothing behind.
#include <doctest/doctest.h>

#include <ImfChannelList.h>
#include <ImfChromaticitiesAttribute.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <map>
#include <unistd.h>

#include "render/output/display_output.h"
#include "render/output/exr_output.h"
#include "render/output/output_file.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// A fresh empty folder under the system temp folder, removed at the end of the test.
struct ExrScratchFolder {
  fs::path path;
  explicit ExrScratchFolder(const std::string& name)
      : path(fs::temp_directory_path() / ("rimu-film-test-" + name + "-" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ExrScratchFolder() { fs::remove_all(path); }
  size_t entry_count() const { return size_t(std::distance(fs::directory_iterator(path), fs::directory_iterator())); }
};

// A film whose pixels differ: pixel (x, y) gets a few samples at wavelengths depending on x and y.
void fill(Film& film) {
  const PixelBounds& b = film.pixel_bounds();
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x)
      for (int s = 0; s < 3; ++s)
        film.add_sample(x, y, Float4(0.01f * float(1 + x + 10 * y + s)),
                        SampledWavelengths::sample_visible(float((x * 7 + y * 3 + s) % 20) / 20.0f + 0.01f));
}

// Every channel of the file as floats, keyed by name (data window only).
std::map<std::string, std::vector<float>> read_channels(const fs::path& path, Imath::Box2i& data_window) {
  Imf::InputFile file(path.c_str());
  data_window = file.header().dataWindow();
  const int w = data_window.max.x - data_window.min.x + 1, h = data_window.max.y - data_window.min.y + 1;
  std::map<std::string, std::vector<float>> channels;
  Imf::FrameBuffer fb;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    auto& values = channels[it.name()];
    values.resize(size_t(w) * h);
    fb.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, values.data(), data_window, sizeof(float), sizeof(float) * w));
  }
  file.setFrameBuffer(fb);
  file.readPixels(data_window.min.y, data_window.max.y);
  return channels;
}

}  // namespace

TEST_CASE("EXR round trip: XYZ film with crop window, spectral bins and metadata") {
  ExrScratchFolder folder("exr");
  Film film(FilmOptions{6, 4, PixelBounds{1, 1, 5, 3}, 5}, SpectralResponse::cie_xyz(test::library()));
  fill(film);
  film.add_sample(2, 2, Float4(std::nanf("")), SampledWavelengths::sample_visible(0.5f));  // one discarded sample

  ExrOptions options;
  options.metadata.samples_per_pixel = 3;
  options.metadata.seed = 0xFFFFFFFFFFFFFFF0ull;
  options.metadata.render_time_s = 1.25;
  options.metadata.interrupted = true;
  options.metadata.extra["integrator"] = "path";

  for (const ExrPixelType type : {ExrPixelType::float32, ExrPixelType::half}) {
    const bool is_half = type == ExrPixelType::half;
    CAPTURE(is_half);
    options.pixel_type = type;
    const fs::path path = folder.path / (is_half ? "half.exr" : "float.exr");
    write_exr(path, film, options);

    Imath::Box2i data_window;
    const auto channels = read_channels(path, data_window);
    CHECK(data_window.min.x == 1);
    CHECK(data_window.min.y == 1);
    CHECK(data_window.max.x == 4);
    CHECK(data_window.max.y == 2);
    // X, Y, Z and five spectral bins of 94 nm centred at 407, 501, 595, 689, 783 nm (Fichet et al. 2021 names).
    std::vector<std::string> names;
    for (const auto& [name, values] : channels) names.push_back(name);
    CHECK(names == std::vector<std::string>{"S0.407nm", "S0.501nm", "S0.595nm", "S0.689nm", "S0.783nm", "X", "Y", "Z"});

    // Float: the film's double means rounded to float, exactly. Half: rounding to 11 significant bits, so a
    // relative error ≤ 2⁻¹¹ (values here are far above the subnormal range).
    const double tolerance = is_half ? std::ldexp(1.0, -11) : 0.0;
    for (int y = 1; y < 3; ++y) {
      for (int x = 1; x < 5; ++x) {
        const size_t i = size_t(y - 1) * 4 + size_t(x - 1);
        const auto v = film.pixel_value(x, y);
        for (int c = 0; c < 3; ++c) {
          const float expected = float(v[c]);
          const float got = channels.at(std::string(1, "XYZ"[c]))[i];
          CHECK(std::abs(got - expected) <= tolerance * std::abs(expected));
        }
        for (int bin = 0; bin < 5; ++bin) {
          const float expected = float(film.spectral_value(x, y, bin));
          CHECK(std::abs(channels.at(spectral_channel_name(film.binning(), bin))[i] - expected) <=
                tolerance * std::abs(expected));
        }
      }
    }

    Imf::InputFile file(path.c_str());
    const Imf::Header& h = file.header();
    CHECK(h.displayWindow().max.x == 5);
    CHECK(h.displayWindow().max.y == 3);
    const auto* chromaticities = h.findTypedAttribute<Imf::ChromaticitiesAttribute>("chromaticities");
    REQUIRE(chromaticities != nullptr);
    CHECK(chromaticities->value().red == Imath::V2f(1.0f, 0.0f));
    CHECK(chromaticities->value().green == Imath::V2f(0.0f, 1.0f));
    CHECK(chromaticities->value().blue == Imath::V2f(0.0f, 0.0f));
    CHECK(chromaticities->value().white == Imath::V2f(1.0f / 3.0f, 1.0f / 3.0f));
    CHECK(h.typedAttribute<Imf::IntAttribute>("rimu:spp").value() == 3);
    CHECK(h.typedAttribute<Imf::StringAttribute>("rimu:seed").value() == "18446744073709551600");
    CHECK(h.typedAttribute<Imf::DoubleAttribute>("rimu:renderTimeSeconds").value() == 1.25);
    CHECK(h.typedAttribute<Imf::StringAttribute>("rimu:interrupted").value() == "interrupted at 3 spp");
    CHECK(h.typedAttribute<Imf::StringAttribute>("rimu:filmResponse").value() == "CIE 1931 2°");
    CHECK(h.typedAttribute<Imf::StringAttribute>("rimu:version").value() == "0.1.0");
    CHECK(h.typedAttribute<Imf::StringAttribute>("rimu:integrator").value() == "path");
    CHECK(h.typedAttribute<Imf::DoubleAttribute>("rimu:discardedNaN").value() == 1.0);
    CHECK(h.typedAttribute<Imf::DoubleAttribute>("rimu:samplesAccepted").value() == 24.0);
    CHECK(h.typedAttribute<Imf::StringAttribute>("spectralLayoutVersion").value() == "1.0");
  }
  CHECK(folder.entry_count() == 2);  // the two files, no temporaries
}

TEST_CASE("EXR of a camera film: R, G, B channels, no chromaticities, the camera named") {
  ExrScratchFolder folder("exr-camera");
  Film film(FilmOptions{3, 2, {}, 0}, SpectralResponse::camera_rgb(test::library(), "sony_ilce_9"));
  fill(film);
  const fs::path path = folder.path / "camera.exr";
  write_exr(path, film, ExrOptions{ExrPixelType::float32, {}, false, std::nullopt, {}});
  Imf::InputFile file(path.c_str());
  const Imf::Header& h = file.header();
  CHECK(h.findTypedAttribute<Imf::ChromaticitiesAttribute>("chromaticities") == nullptr);
  CHECK(h.typedAttribute<Imf::StringAttribute>("rimu:camera").value() == "pbrt_physlight_sony_ilce_9_10nm");
  CHECK(h.findTypedAttribute<Imf::StringAttribute>("rimu:interrupted") == nullptr);
  CHECK(h.channels().findChannel("R") != nullptr);
  CHECK(h.channels().findChannel("G") != nullptr);
  CHECK(h.channels().findChannel("B") != nullptr);
  CHECK(h.channels().findChannel("Y") == nullptr);
}

TEST_CASE("writing into a missing folder fails cleanly and leaves no file") {
  ExrScratchFolder folder("missing");
  Film film(FilmOptions{2, 2, {}, 0}, SpectralResponse::cie_xyz(test::library()));
  const fs::path path = folder.path / "no-such-folder" / "out.exr";
  CHECK_THROWS_WITH_AS(write_exr(path, film), doctest::Contains(path.string().c_str()), InputError);
  CHECK_THROWS_WITH_AS(write_exr(path, film), doctest::Contains("does not exist"), InputError);
  CHECK_FALSE(fs::exists(path));
  CHECK(folder.entry_count() == 0);
  // A folder where the file should be is refused too.
  CHECK_THROWS_AS(write_exr(folder.path, film), InputError);
}

TEST_CASE("a library failure mid-write leaves neither the file nor the temporary") {
  ExrScratchFolder folder("failure");
  const fs::path path = folder.path / "out.exr";
  fs::path temporary_seen;
  CHECK_THROWS_WITH_AS(write_atomically(path,
                                        [&](const fs::path& temporary) {
                                          temporary_seen = temporary;
                                          std::ofstream(temporary) << "half a file";
                                          throw std::runtime_error("disk full (simulated)");
                                        }),
                       doctest::Contains("disk full (simulated)"), OutputError);
  CHECK(temporary_seen.parent_path() == folder.path);  // same folder: the rename cannot cross file systems
  CHECK_FALSE(fs::exists(temporary_seen));
  CHECK_FALSE(fs::exists(path));
  CHECK(folder.entry_count() == 0);

  // An existing file is replaced only when the new one is complete.
  std::ofstream(path) << "old";
  CHECK_THROWS_AS(write_atomically(path, [](const fs::path&) { throw std::runtime_error("no"); }), OutputError);
  std::ifstream in(path);
  std::string content;
  in >> content;
  CHECK(content == "old");
}

TEST_CASE("half output clamps instead of overflowing to Inf") {
  ExrScratchFolder folder("clamp");
  Film film(FilmOptions{1, 1, {}, 0}, SpectralResponse::cie_xyz(test::library()));
  film.add_sample(0, 0, Float4(1e9f), SampledWavelengths::sample_visible(0.4f));
  const fs::path path = folder.path / "bright.exr";
  ExrOptions half;
  half.pixel_type = ExrPixelType::half;
  write_exr(path, film, half);
  Imath::Box2i window;
  const auto channels = read_channels(path, window);
  CHECK(channels.at("Y")[0] == 65504.0f);
}

TEST_CASE("half range: values half floats would clamp or keep imprecisely are counted and warned about") {
  // One sample per pixel at one wavelength: the film value is radiance × c(λ)/p(λ) (× ¼ for the lane mean), so
  // scaling the radiance scales X, Y, Z alike. 2⁻¹⁴ is half's smallest normal value.
  const SampledWavelengths lambda = SampledWavelengths::sample_visible(0.4f);
  const auto film_at = [&](float radiance) {
    auto film = std::make_unique<Film>(FilmOptions{4, 1, {}, 0}, SpectralResponse::cie_xyz(test::library()));
    for (int x = 0; x < 4; ++x) film->add_sample(x, 0, Float4(radiance), lambda);
    return film;
  };
  const auto unit_film = film_at(1.0f);
  const Film& unit = *unit_film;
  const double y = unit.output_value(0, 0)[1];
  REQUIRE(y > 0.0);
  SUBCASE("an ordinary image: nothing to say") {
    const HalfRangeCounts counts = half_range_counts(unit);
    CHECK(counts.nonzero == 12);
    CHECK(counts.below_normal == 0);
    CHECK(counts.above_max == 0);
    CHECK(half_range_warning(counts, "a.exr").empty());
  }
  SUBCASE("a dim image (Y ≈ 1e-6): every value below the normal range") {
    const HalfRangeCounts counts = half_range_counts(*film_at(float(1e-6 / y)));
    CHECK(counts.below_normal == counts.nonzero);
    const std::string warning = half_range_warning(counts, "dim.exr");
    CHECK(warning.find("dim.exr") != std::string::npos);
    CHECK(warning.find("100 % of the non-zero values") != std::string::npos);
    CHECK(warning.find("without --half") != std::string::npos);
  }
  SUBCASE("a bright image (Y ≈ 1e5): clamped values counted") {
    const HalfRangeCounts counts = half_range_counts(*film_at(float(1e5 / y)));
    CHECK(counts.above_max >= 4);  // at least Y of every pixel
    CHECK(half_range_warning(counts, "b.exr").find("above 65504") != std::string::npos);
  }
  SUBCASE("a few subnormal shadows (under a tenth) are not worth a warning") {
    HalfRangeCounts counts{100, 9, 0};
    CHECK(half_range_warning(counts, "c.exr").empty());
    counts.below_normal = 10;
    CHECK_FALSE(half_range_warning(counts, "c.exr").empty());
  }
}

TEST_CASE("no NaN or Inf reaches an image: an overflowing output transform is written finite and counted") {
  // An exposure scale of 1e300 times a film value of ~1 overflows a float (3.4e38) to Inf; a NaN in the white
  // balance matrix makes NaN. The EXR writer replaces them (NaN → 0, ±Inf → ± the largest value of the type) and
  // says how many; the display image clamps (NaN → 0, Inf → 255).
  ExrScratchFolder folder("finite");
  Film film(FilmOptions{2, 1, {}, 0}, SpectralResponse::cie_xyz(test::library()));
  film.add_sample(0, 0, Float4(1.0f), SampledWavelengths::sample_visible(0.4f));
  film.add_sample(1, 0, Float4(1.0f), SampledWavelengths::sample_visible(0.6f));
  film.set_output_transform(FilmOutputTransform{Matrix3::identity(), 1e300});
  for (const auto type : {ExrPixelType::float32, ExrPixelType::half}) {
    const fs::path path = folder.path / (type == ExrPixelType::half ? "half.exr" : "float.exr");
    ExrOptions options;
    options.pixel_type = type;
    const size_t replaced = write_exr(path, film, options);
    Imath::Box2i window;
    for (const auto& [name, values] : read_channels(path, window))
      for (float v : values) {
        CAPTURE(name);
        CHECK(std::isfinite(v));
      }
    if (type == ExrPixelType::float32) {
      CHECK(replaced == 6);  // X, Y, Z of both pixels
      Imf::InputFile file(path.c_str());
      CHECK(file.header().typedAttribute<Imf::DoubleAttribute>("rimu:nonFiniteValuesReplaced").value() == 6.0);
    }
  }
  Matrix3 nan_matrix = Matrix3::identity();
  nan_matrix(0, 0) = std::numeric_limits<double>::quiet_NaN();
  film.set_output_transform(FilmOutputTransform{nan_matrix, 1.0});
  ExrOptions options;
  options.pixel_type = ExrPixelType::float32;
  CHECK(write_exr(folder.path / "nan.exr", film, options) == 2);  // X of both pixels
  Imath::Box2i window;
  CHECK(read_channels(folder.path / "nan.exr", window).at("X")[0] == 0.0f);

  // The display image: Inf clamps to white, NaN to 0 (the Raw view shows the film's numbers, so each channel is
  // its own: X NaN → 0; Y, Z of ~1e300 → 255).
  film.set_output_transform(FilmOutputTransform{nan_matrix, 1e300});
  DisplayOptions raw;
  raw.view = "Raw";
  const std::vector<uint8_t> pixels = display_pixels(film, raw);
  REQUIRE(pixels.size() == 6);
  CHECK(pixels[0] == 0);
  CHECK(pixels[1] == 255);
  CHECK(pixels[2] == 255);
}
