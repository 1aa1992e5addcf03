// Display output: the OCIO views against the sRGB formulas, and a PNG that OpenImageIO reads back.
#include <doctest/doctest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>

#include "render/output/display_output.h"
#include "render/output/output_file.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace display_output_test {

// IEC 61966-2-1:1999: XYZ (D65) → linear sRGB (the standard's 4-decimal matrix) and the piecewise encoding.
std::array<double, 3> xyz_to_linear_srgb(const std::array<double, 3>& xyz) {
  const double m[3][3] = {{3.2406, -1.5372, -0.4986}, {-0.9689, 1.8758, 0.0415}, {0.0557, -0.2040, 1.0570}};
  std::array<double, 3> rgb{};
  for (int i = 0; i < 3; ++i) rgb[i] = m[i][0] * xyz[0] + m[i][1] * xyz[1] + m[i][2] * xyz[2];
  return rgb;
}
double srgb_encode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

// XYZ of D65 (CIE 15:2004 Table T.3, x = 0.31272, y = 0.32903) scaled to luminance Y.
std::array<double, 3> d65_grey(double y) {
  const double x = 0.31272, yy = 0.32903;
  return {y * x / yy, y, y * (1.0 - x - yy) / yy};
}

TEST_CASE("Standard view: plain sRGB encoding of XYZ, with exposure") {
  // OCIO's "DISPLAY - CIE-XYZ-D65_to_sRGB" against IEC 61966-2-1's matrix and curve. OCIO derives its matrix from the
  // primaries rather than using the rounded 4-decimal one: they differ by ~1e-4, and 18 % grey must encode to
  // 1.055·0.18^(1/2.4) − 0.055 = 0.4614 within 5e-4 (D65's 5-decimal chromaticity contributes another ~1e-5).
  const DisplayTransform standard(ResponseKind::cie_xyz, DisplayOptions{});
  for (const double y : {0.18, 0.5, 0.01}) {
    CAPTURE(y);
    const auto xyz = d65_grey(y);
    std::vector<float> rgb = {float(xyz[0]), float(xyz[1]), float(xyz[2])};
    standard.apply(rgb, 1);
    for (int c = 0; c < 3; ++c) CHECK(rgb[c] == doctest::Approx(srgb_encode(y)).epsilon(5e-4));
  }
  // A saturated colour: same budget per channel.
  const std::array<double, 3> xyz = {0.2, 0.15, 0.05};
  std::vector<float> rgb = {0.2f, 0.15f, 0.05f};
  standard.apply(rgb, 1);
  const auto linear = xyz_to_linear_srgb(xyz);
  for (int c = 0; c < 3; ++c) CHECK(std::abs(rgb[c] - srgb_encode(linear[c])) <= 1e-3);

  // +1 EV doubles the scene values: 0.09 shown at +1 EV is 0.18 shown at 0 EV.
  const DisplayTransform brighter(ResponseKind::cie_xyz, DisplayOptions{1.0, "Standard", "sRGB", {}, {}});
  const auto half_grey = d65_grey(0.09);
  std::vector<float> g = {float(half_grey[0]), float(half_grey[1]), float(half_grey[2])};
  brighter.apply(g, 1);
  CHECK(g[1] == doctest::Approx(srgb_encode(0.18)).epsilon(5e-4));
}

TEST_CASE("ACES 1.0 SDR view keeps D65 grey neutral and compresses highlights") {
  // The inverse Bradford (XYZ D65 → ACES white) and the ODT's D60 → D65 adaptation cancel on neutrals: R = G = B to
  // within OCIO's float pipeline (1e-3). The tone curve maps scene white (Y = 1) below display white.
  const DisplayTransform aces(ResponseKind::cie_xyz, DisplayOptions{0.0, "ACES 1.0 SDR", "sRGB", {}, {}});
  for (const double y : {0.18, 1.0, 16.0}) {
    CAPTURE(y);
    const auto xyz = d65_grey(y);
    std::vector<float> rgb = {float(xyz[0]), float(xyz[1]), float(xyz[2])};
    aces.apply(rgb, 1);
    CHECK(rgb[0] == doctest::Approx(rgb[1]).epsilon(1e-3));
    CHECK(rgb[2] == doctest::Approx(rgb[1]).epsilon(1e-3));
    CHECK(rgb[1] < 1.0f);
    CHECK(rgb[1] > 0.0f);
  }
}

TEST_CASE("unknown views and configs are InputErrors naming what exists") {
  CHECK_THROWS_WITH_AS(DisplayTransform(ResponseKind::cie_xyz, DisplayOptions{0.0, "Filmic", "sRGB", {}, {}}),
                       doctest::Contains("Standard, ACES 1.0 SDR"), InputError);
  CHECK_THROWS_WITH_AS(DisplayTransform(ResponseKind::cie_xyz, DisplayOptions{0.0, "Standard", "sRGB", "/nope.ocio", {}}),
                       doctest::Contains("/nope.ocio"), InputError);
}

TEST_CASE("PNG is written, readable, of the crop window's size, with the expected pixel values") {
  const fs::path folder = fs::temp_directory_path() / ("rimu-film-test-png-" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  Film film(FilmOptions{9, 7, PixelBounds{1, 2, 8, 7}, 0}, SpectralResponse::cie_xyz(test::library()));
  // One sample per pixel at wavelengths near 555 nm with a small radiance: a mid-grey-green pixel value.
  for (int y = 2; y < 7; ++y)
    for (int x = 1; x < 8; ++x)
      film.add_sample(x, y, Float4(0.02f * float(x) / 7.0f),
                      SampledWavelengths(Float4(540.0f, 550.0f, 560.0f, 570.0f), Float4(0.01f)));
  const fs::path path = folder / "display.png";
  write_display_image(path, film);

  auto in = OIIO::ImageInput::open(path.string());
  REQUIRE(in);
  const OIIO::ImageSpec& spec = in->spec();
  CHECK(spec.width == 7);
  CHECK(spec.height == 5);
  CHECK(spec.nchannels == 3);
  std::vector<uint8_t> pixels(size_t(spec.width) * spec.height * 3);
  REQUIRE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, pixels.data()));
  in->close();
  // Pixel (x, y) of the film is PNG pixel (x − 1, y − 2). Expected: IEC 61966-2-1 applied to the film's XYZ, ±1
  // code value (the OCIO/IEC matrix difference above is < 0.3 code values; rounding adds 0.5).
  for (const auto& [x, y] : {std::pair{1, 2}, std::pair{4, 3}, std::pair{7, 6}}) {
    const auto linear = xyz_to_linear_srgb(film.pixel_value(x, y));
    for (int c = 0; c < 3; ++c) {
      const int expected = int(std::lround(srgb_encode(linear[c]) * 255.0));
      const int got = pixels[(size_t(y - 2) * 7 + size_t(x - 1)) * 3 + c];
      CAPTURE(x);
      CAPTURE(c);
      CHECK(std::abs(got - expected) <= 1);
    }
  }
  CHECK(std::distance(fs::directory_iterator(folder), fs::directory_iterator()) == 1);  // no temporary left
  CHECK_THROWS_AS(write_display_image(folder / "missing" / "x.png", film), InputError);
  fs::remove_all(folder);
}

}  // namespace display_output_test
