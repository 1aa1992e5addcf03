// Image textures and environment images: decoding, orientation, wrapping and upsampling per lookup.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "render/image_texture.h"
#include "render/rgb_environment_image.h"
#include "render/rgb_image.h"
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

TEST_CASE("float images are linear and reject NaN/Inf pixels with the file named") {
  const auto good = write_pfm("linear", 1, 1, {0.5f, 2.0f, 1e-6f});
  const RgbImage image = RgbImage::read(good, default_encoding_for(good));
  CHECK(image.pixel(0, 0).g == doctest::Approx(2.0));
  const auto bad = write_pfm("nan", 2, 1, {0.5f, 0.5f, 0.5f, std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f});
  try {
    RgbImage::read(bad, default_encoding_for(bad));
    FAIL("a NaN pixel must be rejected");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find(bad.string()) != std::string::npos);
    CHECK(std::string(e.what()).find("(1, 0)") != std::string::npos);
  }
  CHECK_THROWS_AS(RgbImage::read("/nonexistent/texture.png", {}), InputError);
}

TEST_CASE("an image texture returns the upsampled reflectance of its pixel at every wavelength") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  auto image = std::make_shared<const RgbImage>(1, 1, std::vector<float>{0.6f, 0.3f, 0.1f});
  const ImageTexture texture(image, upsampler, 1.0f);
  const ReflectanceSpectrum expected = upsampler->upsample_reflectance({0.6, 0.3, 0.1}).spectrum;
  for (float u : {0.05f, 0.35f, 0.65f, 0.95f}) {
    const SampledWavelengths lambda = SampledWavelengths::sample_visible(u);
    const SampledSpectrum got = texture.evaluate({0.3f, 0.7f}, lambda);
    const SampledSpectrum want = expected.evaluate(lambda);
    for (int lane = 0; lane < kLaneCount; ++lane) CHECK(got[lane] == doctest::Approx(want[lane]).epsilon(1e-6));
  }
  // A white texel is the perfect diffuser: exactly 1 (the upsampler's white is flat).
  auto white = std::make_shared<const RgbImage>(1, 1, std::vector<float>{1.0f, 1.0f, 1.0f});
  const SampledSpectrum w = ImageTexture(white, upsampler, 1.0f).evaluate({0.5f, 0.5f}, SampledWavelengths::sample_visible(0.3f));
  for (int lane = 0; lane < kLaneCount; ++lane) CHECK(w[lane] == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE("an environment image's luminance is its pixels' Y and black pixels emit nothing") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  auto image = std::make_shared<const RgbImage>(2, 1, std::vector<float>{1.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f});
  const RgbEnvironmentImage environment(image, upsampler);
  CHECK(environment.luminance(0, 0) == doctest::Approx(1.0).epsilon(1e-6));  // sRGB white has Y = 1
  CHECK(environment.luminance(1, 0) == 0.0f);
  const SampledSpectrum black = environment.radiance(1, 0, SampledWavelengths::sample_visible(0.5f));
  CHECK(max_lane(abs(black)) == 0.0f);
}
