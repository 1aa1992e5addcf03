// Image textures and environment images: decoding, orientation, wrapping, and the upsampling of a lookup's
// filtered RGB (an environment image converts each pixel once, at load time).
#include <doctest/doctest.h>

#include <algorithm>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "render/image/image_texture.h"
#include "render/image/rgb_radiance_image.h"
#include "render/image/rgb_image.h"
#include "spectral/error.h"
#include "test_image_files.h"
#include "test_support.h"

using namespace rimu;

using test::write_pfm;
using test::write_ppm;

TEST_CASE("8-bit images are sRGB-decoded to linear, row 0 is the top, v = 0 is the bottom") {
  // 2x2: top row red (255,0,0) and 128 grey; bottom row black and white.
  const auto path = write_ppm("orient", 2, 2, {255, 0, 0, 128, 128, 128, 0, 0, 0, 255, 255, 255});
  const ImageEncoding encoding = default_encoding_for(path);
  CHECK(encoding.srgb_transfer);
  const RgbImage image = RgbImage::read(path, encoding);
  CHECK(image.pixel(0, 0).r == doctest::Approx(1.0));
  // IEC 61966-2-1: 128/255 decodes to ((0.50196 + 0.055)/1.055)^2.4 = 0.21586.
  CHECK(image.pixel(1, 0).g == doctest::Approx(0.21586).epsilon(1e-4));
  // Texel centres: (u, v) = (0.25, 0.75) is the top-left texel, (0.75, 0.25) the bottom-right one.
  CHECK(image.bilinear({0.25f, 0.75f}).r == doctest::Approx(1.0).epsilon(1e-6));
  CHECK(image.bilinear({0.75f, 0.25f}).b == doctest::Approx(1.0).epsilon(1e-6));
  // Repeat wrapping: u + 1 is the same place.
  CHECK(image.bilinear({1.25f, 0.75f}).r == doctest::Approx(1.0).epsilon(1e-5));
}

TEST_CASE("float images are linear and reject NaN/Inf pixels at load, naming the file and the first bad pixel") {
  const auto good = write_pfm("linear", 1, 1, {0.5f, 2.0f, 1e-6f});
  const RgbImage image = RgbImage::read(good, default_encoding_for(good));
  CHECK(image.pixel(0, 0).g == doctest::Approx(2.0));
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  // Row 0 is the top; PFM stores the bottom row first, which write_pfm takes care of. Pixel (1, 0) is the first
  // bad one in reading order; (0, 1) is bad too and must not be the one named.
  for (const float bad_value : {nan, inf, -inf}) {
    CAPTURE(bad_value);
    const auto bad = write_pfm("nonfinite", 2, 2, {0.5f, 0.5f, 0.5f, bad_value, 0.0f, 0.0f,  //
                                                   0.0f, bad_value, 0.0f, 0.1f, 0.1f, 0.1f});
    try {
      RgbImage::read(bad, default_encoding_for(bad));
      FAIL("a non-finite pixel must be rejected");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(bad.string()) != std::string::npos);
      CHECK(std::string(e.what()).find("(1, 0)") != std::string::npos);
      CHECK(std::string(e.what()).find("not a finite number") != std::string::npos);
    }
  }
  CHECK_THROWS_AS(RgbImage::read("/nonexistent/texture.png", {}), InputError);
}

TEST_CASE("an image texture's lookup at a texel is that texel's fast upsampling, close to the exact one") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  // 2×2 texels, row 0 at the top: orange, dark purple (the basis's zero-region case), white, a light cyan.
  const Rgb texels[4] = {{0.6, 0.3, 0.1}, {0.3, 0.0, 0.2}, {1.0, 1.0, 1.0}, {0.2, 0.7, 0.8}};
  std::vector<float> rgb;
  for (const Rgb& t : texels) rgb.insert(rgb.end(), {float(t.r), float(t.g), float(t.b)});
  auto image = std::make_shared<const RgbImage>(2, 2, rgb);
  const ImageTexture texture(image, upsampler, 0.5f);
  // Texel (x, y) has its centre at u = (x + 0.5)/2, v = 1 − (y + 0.5)/2 (v = 0 at the bottom row).
  for (int t = 0; t < 4; ++t) {
    CAPTURE(t);
    const int x = t % 2, y = t / 2;
    const Vec2 uv{(x + 0.5f) / 2.0f, 1.0f - (y + 0.5f) / 2.0f};
    const ReflectanceSpectrum fast = upsampler->fast_reflectance_spectrum(texels[t]);
    const ReflectanceSpectrum exact = upsampler->upsample_reflectance(texels[t]).spectrum;
    // The lookup clamps after interpolating between knots (UpsamplingBasis::evaluate), the knot spectrum before:
    // they differ by at most how far the texel's unclamped knots lie outside [0, 1] (its ringing), times scale.
    double beyond = 0;
    for (double v : upsampler->basis().knots(upsampler->reflectance_coefficients(texels[t])))
      beyond = std::max(beyond, std::abs(v - std::clamp(v, 0.0, 1.0)));
    for (float u : {0.05f, 0.35f, 0.65f, 0.95f}) {
      const SampledWavelengths lambda = SampledWavelengths::sample_visible(u);
      const SampledSpectrum got = texture.evaluate(uv, lambda);
      const SampledSpectrum want_fast = fast.evaluate(lambda) * Float4(0.5f);
      const SampledSpectrum want_exact = exact.evaluate(lambda) * Float4(0.5f);
      for (int lane = 0; lane < kLaneCount; ++lane) {
        // The same representation: float rounding, and the clamping order where the texel rings.
        CHECK(std::abs(got[lane] - want_fast[lane]) <= 1e-5f + 0.5f * float(beyond));
        // Against the exact path: the basis's stated distance (largest knot difference ≤ 0.04, here × 0.5).
        CHECK(std::abs(got[lane] - want_exact[lane]) <= 0.02f);
      }
    }
  }
  // Halfway between the orange and the purple texel: the smoothest spectrum of their mean colour (pbrt-v4's order:
  // the RGB is filtered, then upsampled once), each texel scaled by 0.5 first.
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 600.0f, 700.0f), Float4(1.0f));
  const SampledSpectrum mid = texture.evaluate({0.5f, 0.75f}, lambda);
  const Rgb mean{0.25 * (float(texels[0].r) + float(texels[1].r)), 0.25 * (float(texels[0].g) + float(texels[1].g)),
                 0.25 * (float(texels[0].b) + float(texels[1].b))};
  const SampledSpectrum want_mid = upsampler->basis().evaluate(upsampler->reflectance_coefficients(mean),
                                                               lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
  for (int lane = 0; lane < kLaneCount; ++lane) CHECK(mid[lane] == doctest::Approx(want_mid[lane]).epsilon(1e-5));
  // A white texel is the perfect diffuser: 1 up to the float rounding of 16 coefficients.
  auto white = std::make_shared<const RgbImage>(1, 1, std::vector<float>{1.0f, 1.0f, 1.0f});
  const SampledSpectrum w = ImageTexture(white, upsampler, 1.0f).evaluate({0.5f, 0.5f}, SampledWavelengths::sample_visible(0.3f));
  for (int lane = 0; lane < kLaneCount; ++lane) CHECK(w[lane] == doctest::Approx(1.0).epsilon(1e-5));
}

TEST_CASE("an environment image's pixels are converted once to the fast emission, close to the exact one") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  const Rgb pixels[3] = {{1e4, 2e3, 5e2}, {0.02, 0.05, 0.3}, {1e-6, 1e-6, 1e-6}};
  std::vector<float> rgb;
  for (const Rgb& p : pixels) rgb.insert(rgb.end(), {float(p.r), float(p.g), float(p.b)});
  const RgbRadianceImage environment(std::make_shared<const RgbImage>(3, 1, rgb), upsampler);
  for (int x = 0; x < 3; ++x) {
    CAPTURE(x);
    const Rgb p{float(pixels[x].r), float(pixels[x].g), float(pixels[x].b)};
    const EmissionSpectrum fast = upsampler->fast_emission_spectrum(p);
    const EmissionSpectrum exact = upsampler->upsample_emission(p).spectrum;
    for (float u : {0.1f, 0.4f, 0.7f}) {
      const SampledWavelengths lambda = SampledWavelengths::sample_visible(u);
      const SampledSpectrum got = environment.radiance(x, 0, lambda);
      const SampledSpectrum want = fast.evaluate(lambda), want_exact = exact.evaluate(lambda);
      const float peak = float(exact.max_value());
      // Clamped at 0 after interpolating between knots (UpsamplingBasis::evaluate), the knot spectrum before:
      // they differ by at most the depth of the pixel's negative ringing, in radiance.
      double below = 0;
      for (double v : upsampler->basis().knots(upsampler->emission_coefficients(p))) below = std::max(below, -v);
      const SampledSpectrum ringing_radiance =
          Float4(float(below * upsampler->emission_scale())) * upsampler->illuminant()->sample(lambda);
      for (int lane = 0; lane < kLaneCount; ++lane) {
        CHECK(std::abs(got[lane] - want[lane]) <= 1e-5f * std::abs(want[lane]) + ringing_radiance[lane] + 1e-30f);
        // Shapes agree to the basis's stated distance, relative to the spectrum's own scale.
        CHECK(std::abs(got[lane] - want_exact[lane]) <= 0.04f * peak);
      }
    }
    // The pixel's integral over wavelength, upsampled once, is the generic four-lookup sum bit for bit (the light's
    // power and sampling weights are built from it).
    CHECK(environment.radiance_integral(x, 0) == environment.RadianceImage::radiance_integral(x, 0));
    CHECK(environment.radiance_integral(x, 0) > 0.0);
  }
  // The row at once (what lights call when they are built): the same numbers, bit for bit.
  std::vector<double> row(3);
  environment.radiance_integrals(0, row);
  for (int x = 0; x < 3; ++x) CHECK(row[x] == environment.radiance_integral(x, 0));
}

TEST_CASE("an environment image's luminance is its pixels' Y and black pixels emit nothing") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  auto image = std::make_shared<const RgbImage>(2, 1, std::vector<float>{1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f});
  const RgbRadianceImage environment(image, upsampler);
  CHECK(environment.luminance(0, 0) == doctest::Approx(1.0).epsilon(1e-6));  // sRGB white has Y = 1
  CHECK(environment.luminance(1, 0) == 0.0f);
  const SampledSpectrum black = environment.radiance(1, 0, SampledWavelengths::sample_visible(0.5f));
  CHECK(max_lane(abs(black)) == 0.0f);
}
