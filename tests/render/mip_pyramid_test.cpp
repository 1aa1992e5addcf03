// MIP maps (render/image/mip_pyramid.h): every level keeps the image's mean, filtered lookups are weighted means
// (exact on a constant image), the level follows the footprint, 8-bit levels are their region's linear mean to half a
// code, and a texture's lookup upsamples the filtered RGB once.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "render/image/image_texture.h"
#include "render/image/mip_pyramid.h"
#include "render/image/rgb_texels.h"
#include "test_support.h"

using namespace rimu;

namespace {

double mean_of_level(const MipPyramid<float>& p, int level) {
  double sum = 0.0;
  for (int y = 0; y < p.height(level); ++y)
    for (int x = 0; x < p.width(level); ++x) sum += double(p.texel(level, x, y));
  return sum / (double(p.width(level)) * double(p.height(level)));
}

MipPyramid<float> random_pyramid(int width, int height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  std::vector<float> texels(size_t(width) * size_t(height));
  for (float& t : texels) t = value(rng);
  return MipPyramid<float>(width, height, std::move(texels));
}

float filtered(const MipPyramid<float>& p, TextureFilterOptions options, Vec2 st, Vec2 dx, Vec2 dy, float* weight_sum = nullptr) {
  float value = 0.0f, weights = 0.0f;
  p.lookup(options, st, dx, dy, [&](const float* const t[4], const float w[4]) {
    for (int j = 0; j < 4; ++j) value += w[j] * *t[j], weights += w[j];
  });
  if (weight_sum) *weight_sum = weights;
  return value;
}

constexpr TextureFilter kFilters[] = {TextureFilter::point, TextureFilter::bilinear, TextureFilter::trilinear,
                                      TextureFilter::ewa};

}  // namespace

TEST_CASE("MIP pyramid: levels halve down to 1×1 and each keeps the image's mean (odd and even sides)") {
  for (const auto& [w, h] : {std::pair{64, 64}, std::pair{37, 20}, std::pair{5, 1}, std::pair{1, 9}, std::pair{3, 3}}) {
    CAPTURE(w);
    CAPTURE(h);
    const MipPyramid<float> p = random_pyramid(w, h, uint32_t(w * 100 + h));
    CHECK(p.width(p.levels() - 1) == 1);
    CHECK(p.height(p.levels() - 1) == 1);
    CHECK(p.levels() == 1 + int(std::floor(std::log2(double(std::max(w, h))))));
    const double mean = mean_of_level(p, 0);
    for (int level = 1; level < p.levels(); ++level) {
      CAPTURE(level);
      CHECK(p.width(level) == std::max(1, p.width(level - 1) / 2));
      // Float sums of ≤ 2368 texels in [0, 1): rounding ≤ ~1e-6 of the mean.
      CHECK(mean_of_level(p, level) == doctest::Approx(mean).epsilon(1e-5));
    }
    // ≤ 4/3 of the base's texels (the documented memory cost).
    CHECK(double(p.texel_count()) <= 4.0 / 3.0 * double(w) * double(h) + double(p.levels()) + double(w + h));
  }
}

TEST_CASE("MIP pyramid: every filter is exact on a constant image at any footprint, its weights summing to 1") {
  const MipPyramid<float> p(13, 8, std::vector<float>(13 * 8, 0.375f));
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f), derivative(-0.5f, 0.5f), scale(-12.0f, 2.0f);
  for (const TextureFilter filter : kFilters) {
    CAPTURE(int(filter));
    for (int i = 0; i < 200; ++i) {
      const float s = std::exp2(scale(rng));  // footprints from 1/4000 to 4 image widths
      const Vec2 st{coordinate(rng), coordinate(rng)};
      const Vec2 dx{derivative(rng) * s, derivative(rng) * s}, dy{derivative(rng) * s, derivative(rng) * s};
      float weights = 0.0f;
      const float v = filtered(p, {filter, 8.0f}, st, dx, dy, &weights);
      CHECK(weights == doctest::Approx(1.0f).epsilon(1e-5));
      CHECK(v == doctest::Approx(0.375f).epsilon(1e-5));
    }
  }
}

TEST_CASE("MIP pyramid: the footprint picks the level (a texel checkerboard reads its mean once a texel is wider)") {
  // 16×16 texels alternating 0 and 1: level 1 and above are 0.5 everywhere.
  std::vector<float> texels(256);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) texels[size_t(y * 16 + x)] = float((x + y) % 2);
  const MipPyramid<float> p(16, 16, std::move(texels));
  const Vec2 centre{(3 + 0.5f) / 16.0f, 1.0f - (5 + 0.5f) / 16.0f};  // texel (3, 5): value 0
  for (const TextureFilter filter : kFilters) {
    CAPTURE(int(filter));
    // No footprint: the texel itself.
    CHECK(filtered(p, {filter, 8.0f}, centre, {}, {}) == doctest::Approx(0.0f).epsilon(1e-6));
    // A footprint of two texels each way (width 4 texels, level 2): the mean.
    const Vec2 dx{2.0f / 16.0f, 0.0f}, dy{0.0f, 2.0f / 16.0f};
    CHECK(filtered(p, {filter, 8.0f}, centre, dx, dy) == doctest::Approx(0.5f).epsilon(1e-5));
  }
  // Trilinear blends continuously: a footprint growing from 1 to 2 texels wide moves the value from the texel to the mean
  // monotonically (no jump where the level crosses an integer).
  float previous = -1.0f;
  for (int i = 0; i <= 16; ++i) {
    const float half_width = (0.5f + 0.5f * float(i) / 16.0f) / 16.0f;  // width 1 → 2 texels: level 0 → 1
    const float v = filtered(p, {TextureFilter::trilinear, 8.0f}, centre, {half_width, 0}, {0, half_width});
    CHECK(v >= previous - 1e-6f);
    previous = v;
  }
  CHECK(previous == doctest::Approx(0.5f).epsilon(1e-5));
}

TEST_CASE("MIP pyramid: EWA follows an anisotropic footprint, bounded by max_anisotropy") {
  // Stripes along t (value = x mod 2): a footprint long along t and one texel wide across keeps them; long across
  // them averages them away.
  std::vector<float> texels(64 * 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) texels[size_t(y * 64 + x)] = float((x / 4) % 2);  // stripes 4 texels wide
  const MipPyramid<float> p(64, 64, std::move(texels));
  const Vec2 centre{(1 + 0.5f) / 64.0f, 0.5f};  // inside the first stripe (value 0), away from its edges
  const Vec2 along{0.0f, 16.0f / 64.0f}, across_thin{0.5f / 64.0f, 0.0f};
  CHECK(filtered(p, {TextureFilter::ewa, 64.0f}, centre, across_thin, along) < 0.05f);
  // Trilinear takes the largest derivative: the same footprint blurs the stripes to their mean.
  CHECK(filtered(p, {TextureFilter::trilinear, 8.0f}, centre, across_thin, along) == doctest::Approx(0.5f).epsilon(1e-4));
  // With max_anisotropy 1 the ellipse is widened to a circle of the major axis: the mean again.
  CHECK(filtered(p, {TextureFilter::ewa, 1.0f}, centre, across_thin, along) == doctest::Approx(0.5f).epsilon(0.05));
}

TEST_CASE("image texture: a filtered lookup upsamples the filtered RGB once") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  // 2×2 texels of two colours in a checker: level 1 is their mean.
  const Rgb a{0.7, 0.2, 0.1}, b{0.1, 0.4, 0.8};
  std::vector<float> rgb;
  for (const Rgb& t : {a, b, b, a}) rgb.insert(rgb.end(), {float(t.r), float(t.g), float(t.b)});
  auto image = std::make_shared<const RgbImage>(2, 2, rgb);
  const SampledWavelengths lambda{Float4(420.0f, 510.0f, 580.0f, 660.0f), Float4(1.0f / 470.0f)};
  const auto upsampled = [&](Rgb c) {
    return upsampler->basis().evaluate(upsampler->reflectance_coefficients(c), lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
  };
  const SampledSpectrum mean = upsampled({0.5 * (a.r + b.r), 0.5 * (a.g + b.g), 0.5 * (a.b + b.b)});
  const SampledSpectrum at_a = upsampled(a);
  for (const TextureFilter filter : kFilters) {
    CAPTURE(int(filter));
    const ImageTexture texture(image, upsampler, 1.0f, false, {filter, 8.0f});
    CHECK(texture.levels() == 2);
    const Vec2 st{0.25f, 0.75f};  // texel (0, 0): colour a
    const SampledSpectrum sharp = texture.evaluate_footprint(st, {}, {}, lambda);
    const SampledSpectrum plain = texture.evaluate(st, lambda);
    const SampledSpectrum wide = texture.evaluate_footprint(st, {1.0f, 0.0f}, {0.0f, 1.0f}, lambda);
    for (int lane = 0; lane < 4; ++lane) {
      CAPTURE(lane);
      CHECK(sharp[lane] == doctest::Approx(plain[lane]).epsilon(1e-5));
      CHECK(plain[lane] == doctest::Approx(at_a[lane]).epsilon(1e-5));
      // The coarsest level is the mean colour (float rounding), upsampled once.
      CHECK(wide[lane] == doctest::Approx(mean[lane]).epsilon(1e-4));
    }
  }
}

TEST_CASE("image texture: 8-bit texels are kept as codes, their levels the linear mean to half a code") {
  SpectralLibrary& library = test::library();
  auto upsampler = std::make_shared<const RgbUpsampler>(library, RgbColourSpace::named("srgb-linear"));
  // 4×2 sRGB codes with mixed values: level 1 (2×1) averages 2×2 blocks in linear light, level 2 both blocks.
  const std::vector<std::uint8_t> codes = {200, 30, 10,  10, 90, 220, 255, 255, 255, 0,   0,  0,
                                           17,  128, 64, 240, 5, 99,  1,   2,   3,   250, 128, 60};
  const float* table = RgbImage::decode_table(true);
  auto image = std::make_shared<const RgbImage>(4, 2, codes, true);
  const ImageTexture texture(image, upsampler, 1.0f, false, {TextureFilter::trilinear, 8.0f});
  CHECK(texture.levels() == 3);
  CHECK(texture.texel_bytes() == (8 + 2 + 1) * 3);
  // Level 0: a lookup at a texel centre decodes its codes exactly as RgbImage::pixel does.
  const SampledWavelengths lambda{Float4(430.0f, 500.0f, 570.0f, 640.0f), Float4(1.0f / 470.0f)};
  const auto upsampled = [&](Rgb c) {
    return upsampler->basis().evaluate(upsampler->reflectance_coefficients(c), lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
  };
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const SampledSpectrum got = texture.evaluate({(x + 0.5f) / 4.0f, 1.0f - (y + 0.5f) / 2.0f}, lambda);
      const SampledSpectrum want = upsampled(image->pixel(x, y));
      for (int lane = 0; lane < 4; ++lane) CHECK(got[lane] == doctest::Approx(want[lane]).epsilon(1e-6));
    }
  // The coarsest level, stored as codes: each channel is the nearest code to the image's linear mean, so within
  // half a code step of it. Read back through a footprint wider than the image.
  const Rgb8Codec codec{table};
  Rgb mean;
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const Rgb p = image->pixel(x, y);
      mean.r += p.r / 8, mean.g += p.g / 8, mean.b += p.b / 8;
    }
  for (double m : {mean.r, mean.g, mean.b}) {
    const std::uint8_t code = codec.nearest(float(m));
    CHECK(std::abs(double(table[code]) - m) <=
          0.5 * double(table[std::min(255, code + 1)] - table[std::max(0, code - 1)]) + 1e-6);
  }
  // Level 1's two texels hold codes nearest their blocks' means, and level 2 their mean's nearest code: the
  // coarsest lookup is the upsampled colour of those codes.
  const auto block = [&](int x0) {
    Rgb m;
    for (int y = 0; y < 2; ++y)
      for (int x = x0; x < x0 + 2; ++x) {
        const Rgb p = image->pixel(x, y);
        m.r += p.r / 4, m.g += p.g / 4, m.b += p.b / 4;
      }
    return codec.decode(codec.encode({float(m.r), float(m.g), float(m.b)}));
  };
  const LinearRgbTexel left = block(0), right = block(2);
  const LinearRgbTexel top = codec.decode(codec.encode(
      {0.5f * (left.r + right.r), 0.5f * (left.g + right.g), 0.5f * (left.b + right.b)}));
  const SampledSpectrum coarsest = texture.evaluate_footprint({0.5f, 0.5f}, {4.0f, 0.0f}, {0.0f, 4.0f}, lambda);
  const SampledSpectrum want = upsampled({top.r, top.g, top.b});
  for (int lane = 0; lane < 4; ++lane) CHECK(coarsest[lane] == doctest::Approx(want[lane]).epsilon(1e-6));
}
