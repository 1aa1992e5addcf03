// `rimu display --false-colour`: the legend's log scale, its default range, and the round trip that matters to a
// lighting designer: an EXR of one known luminance comes out in the legend's colour at that value. Colours are
// compared in 8-bit codes with a tolerance of 2 (rounding of the palette's interpolation and of the PNG).
#include <doctest/doctest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <unistd.h>

#include "render/film/film.h"
#include "render/output/exr_output.h"
#include "render/output/false_colour_image.h"
#include "render/output/plot_output.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

struct Folder {
  fs::path path = fs::temp_directory_path() / ("rimu-false-colour-" + std::to_string(::getpid()));
  Folder() { fs::create_directories(path); }
  ~Folder() { fs::remove_all(path); }
};

// An XYZ-film EXR whose every pixel has luminance `nits` (Y = nits / the film's nits per unit Y).
fs::path constant_luminance_exr(const fs::path& path, double nits, int width = 24, int height = 16) {
  FilmOptions options;
  options.width = width;
  options.height = height;
  Film film(options, SpectralResponse::cie_xyz(test::library()));
  const double y = nits / film.response().luminance_nits_per_unit_y();
  FilmTile tile = film.make_tile(film.pixel_bounds());
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) {
      double* p = tile.pixel(px, py);
      p[0] = 0.95 * y, p[1] = y, p[2] = 1.09 * y;
      p[FilmTile::kWeight] = 1.0;
    }
  film.merge_tile(tile);
  write_exr(path, film);
  return path;
}

std::array<int, 3> centre_colour(const fs::path& png) {
  auto in = OIIO::ImageInput::open(png.string());
  REQUIRE(in);
  const int w = in->spec().width, h = in->spec().height, channels = in->spec().nchannels;
  std::vector<uint8_t> pixels(size_t(w) * size_t(h) * size_t(channels));
  REQUIRE(in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()));
  // The image sits left of the legend: its centre is left of the PNG's centre; take the centre of the plot area,
  // found as the middle of the widest run of one colour on the middle row.
  const size_t row = size_t(h / 2) * size_t(w) * size_t(channels);
  int best_start = 0, best_length = 0;
  for (int x = 0; x < w;) {
    int end = x + 1;
    while (end < w && std::equal(&pixels[row + size_t(end) * channels], &pixels[row + size_t(end) * channels] + 3,
                                 &pixels[row + size_t(x) * channels]))
      ++end;
    if (end - x > best_length) best_start = x, best_length = end - x;
    x = end;
  }
  const size_t at = row + size_t(best_start + best_length / 2) * size_t(channels);
  return {pixels[at], pixels[at + 1], pixels[at + 2]};
}

void check_colour(const std::array<int, 3>& got, const std::array<double, 3>& expected) {
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    CHECK(std::abs(got[size_t(c)] - expected[size_t(c)]) <= 2.0);
  }
}

}  // namespace

TEST_CASE("false colour: the log legend position, the palette at its stops, the default range") {
  const FalseColourRange range{1, 10000};
  CHECK(false_colour_position(1, range) == doctest::Approx(0.0));
  CHECK(false_colour_position(100, range) == doctest::Approx(0.5));
  CHECK(false_colour_position(10, range) == doctest::Approx(0.25));
  CHECK(false_colour_position(1e6, range) == 1.0);  // clamped
  CHECK(false_colour_position(-3, range) == 0.0);
  CHECK(false_colour_position(std::nan(""), range) == 0.0);
  // The palette's stops are viridis' end points and quartiles.
  check_colour({0x44, 0x01, 0x54}, false_colour_rgb(0.0));
  check_colour({0x21, 0x91, 0x8c}, false_colour_rgb(0.5));
  check_colour({0xfd, 0xe7, 0x25}, false_colour_rgb(1.0));
  // 1st and 99th percentiles of 1..1000 (one value each): 11 and 990 (nearest rank over 1000 values).
  std::vector<double> values;
  for (int k = 1; k <= 1000; ++k) values.push_back(k);
  values.push_back(0.0);        // black pixels do not count
  values.push_back(std::nan(""));
  const FalseColourRange automatic = default_false_colour_range(values, "--range");
  CHECK(automatic.low == doctest::Approx(11).epsilon(0.1));
  CHECK(automatic.high == doctest::Approx(990).epsilon(0.01));
  // A uniform image: a decade either side of its value.
  const FalseColourRange uniform = default_false_colour_range(std::vector<double>(50, 300.0), "--range");
  CHECK(uniform.low == doctest::Approx(30));
  CHECK(uniform.high == doctest::Approx(3000));
  CHECK_THROWS_WITH_AS(default_false_colour_range({0.0, 0.0}, "--range"), doctest::Contains("--range"), InputError);
}

TEST_CASE("false colour: bad quantities and ranges name their flag") {
  CHECK(parse_false_colour_quantity("illuminance", "--false-colour") == FalseColourQuantity::illuminance);
  CHECK_THROWS_WITH_AS(parse_false_colour_quantity("lux", "--false-colour"), doctest::Contains("--false-colour"),
                       InputError);
  const FalseColourRange r = parse_false_colour_range("1:1e4", "--range");
  CHECK(r.low == 1.0);
  CHECK(r.high == 10000.0);
  for (const char* bad : {"100", "0:10", "10:1", "1:nan", "a:b", "1:2:3", "-1:5", ":5"})
    CHECK_THROWS_WITH_AS(parse_false_colour_range(bad, "--range"), doctest::Contains("--range"), InputError);
}

TEST_CASE("false colour: a constant-luminance EXR comes out in the legend's colour at its value") {
  if (!fs::exists(gnuplot_binary())) return;  // the plot tests need gnuplot (tests/render/plot_output_test.cpp)
  Folder folder;
  const fs::path exr = constant_luminance_exr(folder.path / "card.exr", 100.0);
  std::ostringstream log;
  SUBCASE("luminance: 100 nt on 1:10000 is the middle of the legend") {
    write_exr_false_colour(exr, folder.path / "nt.png", FalseColourQuantity::luminance, FalseColourRange{1, 10000}, log);
    check_colour(centre_colour(folder.path / "nt.png"), false_colour_rgb(0.5));
    CHECK(log.str().find("log scale 1 to 10000 nt (--range)") != std::string::npos);
  }
  SUBCASE("illuminance: π × 100 nt = 314.2 lx sits log10(31.42)/4 up a 10:1e5 legend") {
    write_exr_false_colour(exr, folder.path / "lx.png", FalseColourQuantity::illuminance, FalseColourRange{10, 1e5},
                           log);
    check_colour(centre_colour(folder.path / "lx.png"), false_colour_rgb((1.0 + std::log10(std::numbers::pi)) / 4));
  }
  SUBCASE("the default range of a uniform image puts it in the middle") {
    write_exr_false_colour(exr, folder.path / "auto.png", FalseColourQuantity::luminance, std::nullopt, log);
    check_colour(centre_colour(folder.path / "auto.png"), false_colour_rgb(0.5));
    CHECK(log.str().find("1st-99th percentile") != std::string::npos);
  }
  SUBCASE("outputs that cannot work are refused before anything is read, naming --png") {
    CHECK_THROWS_WITH_AS(write_exr_false_colour(exr, folder.path / "no_such_folder" / "x.png",
                                                FalseColourQuantity::luminance, std::nullopt, log),
                         doctest::Contains("--png"), InputError);
    CHECK_THROWS_WITH_AS(write_exr_false_colour(exr, folder.path / "x.jpg", FalseColourQuantity::luminance,
                                                std::nullopt, log),
                         doctest::Contains("--png"), InputError);
    CHECK_THROWS_AS(write_exr_false_colour(folder.path / "missing.exr", folder.path / "y.png",
                                           FalseColourQuantity::luminance, std::nullopt, log),
                    InputError);
    CHECK(!fs::exists(folder.path / "y.png"));
  }
}
