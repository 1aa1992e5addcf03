#include "transport/textures/procedural_texture.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "spectral/error.h"
#include "transport/textures/perlin_noise.h"

namespace rimu {
namespace {

template <typename T>
void require(const T& t, const char* what) {
  if (!t) throw InputError({}, std::string(what) + " needs all of its input textures");
}

void check_octaves(const NoiseOctaves& n, const char* what) {
  if (n.octaves < 0 || n.octaves > 30)
    throw InputError({}, std::string(what) + ": octaves must be 0-30, not " + std::to_string(n.octaves));
  // |ω| ≤ 10 keeps ω^30 within a float.
  if (!(std::fabs(n.roughness) <= 10.0f)) throw InputError({}, std::string(what) + ": roughness must be within ±10");
}

// t clamped to [0, 1], NaN to 0 (a marble scale or variation large enough to overflow gives sin(∞)).
float unit_clamp(float t) { return t > 0.0f ? (t < 1.0f ? t : 1.0f) : 0.0f; }

}  // namespace

NoiseFloatTexture::NoiseFloatTexture(Kind kind, NoiseOctaves octaves, const Transform& texture_from_world)
    : kind_(kind), octaves_(octaves), texture_from_world_(texture_from_world) {
  check_octaves(octaves_, "a noise texture");
}

float NoiseFloatTexture::evaluate(const MaterialContext& context) const {
  const Vec3 p = texture_from_world_.point(context.position);
  switch (kind_) {
    case Kind::fbm: return fbm(p, octaves_.roughness, octaves_.octaves);
    case Kind::wrinkled: return turbulence(p, octaves_.roughness, octaves_.octaves);
    case Kind::windy: return std::fabs(fbm(0.1f * p, 0.5f, 3)) * fbm(p, 0.5f, 6);
  }
  return 0.0f;
}

DotsFloatTexture::DotsFloatTexture(FloatTexturePtr inside, FloatTexturePtr outside, TextureMapping mapping)
    : inside_(std::move(inside)), outside_(std::move(outside)), mapping_(mapping) {
  require(inside_, "a dots texture");
  require(outside_, "a dots texture");
}

float DotsFloatTexture::evaluate(const MaterialContext& context) const {
  return inside_polka_dot(mapping_.st(context)) ? inside_->evaluate(context) : outside_->evaluate(context);
}

DotsSpectralTexture::DotsSpectralTexture(SpectralTexturePtr inside, SpectralTexturePtr outside, TextureMapping mapping)
    : inside_(std::move(inside)), outside_(std::move(outside)), mapping_(mapping) {
  require(inside_, "a dots texture");
  require(outside_, "a dots texture");
}

SampledSpectrum DotsSpectralTexture::evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const {
  return inside_polka_dot(mapping_.st(context)) ? inside_->evaluate_at(context, lambda)
                                                 : outside_->evaluate_at(context, lambda);
}

float marble_ramp_position(Vec3 p, const MarbleParameters& parameters) {
  const Vec3 q = p * parameters.scale;
  const float marble = q.y + parameters.variation * fbm(q, parameters.noise.roughness, parameters.noise.octaves);
  return 0.5f + 0.5f * std::sin(marble);
}

Rgb marble_colour(float t) {
  // pbrt-v4's control colours (linear sRGB): mostly a light grey, one mid grey, a warm grey and a dark slate.
  static constexpr float kColours[9][3] = {{.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f},
                                           {.5f, .5f, .5f},   {.6f, .59f, .58f}, {.58f, .58f, .6f},
                                           {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};
  constexpr int kSegments = 9 - 3;
  t = unit_clamp(t);
  const int first = std::min(int(std::floor(t * kSegments)), kSegments - 1);
  const float u = t * kSegments - float(first), v = 1.0f - u;
  // Bernstein form of the cubic Bézier through colours first … first + 3.
  const float w[4] = {v * v * v, 3 * v * v * u, 3 * v * u * u, u * u * u};
  float c[3] = {0, 0, 0};
  for (int k = 0; k < 4; ++k)
    for (int ch = 0; ch < 3; ++ch) c[ch] += w[k] * kColours[first + k][ch];
  return {1.5 * c[0], 1.5 * c[1], 1.5 * c[2]};
}

MarbleSpectralTexture::MarbleSpectralTexture(MarbleParameters parameters, const Transform& texture_from_world,
                                             std::shared_ptr<const RgbUpsampler> upsampler)
    : parameters_(parameters), texture_from_world_(texture_from_world), upsampler_(std::move(upsampler)) {
  check_octaves(parameters_.noise, "a marble texture");
  if (!std::isfinite(parameters_.scale) || !std::isfinite(parameters_.variation))
    throw InputError({}, "a marble texture: scale and variation must be finite");
  for (int i = 0; i < kMarbleRampSize; ++i) {
    const Rgb c = marble_colour(float(i) / float(kMarbleRampSize - 1));
    if (upsampler_)
      ramp_.push_back(upsampler_->reflectance_coefficients(c));
    else
      ramp_rgb_.push_back(c);
  }
}

SampledSpectrum MarbleSpectralTexture::evaluate_at(const MaterialContext& context, const SampledWavelengths& lambda) const {
  const float t = marble_ramp_position(texture_from_world_.point(context.position), parameters_);
  const float x = unit_clamp(t) * float(kMarbleRampSize - 1);
  const int i = std::min(int(x), kMarbleRampSize - 2);
  const float f = x - float(i);
  if (!upsampler_) {
    const Rgb& a = ramp_rgb_[size_t(i)];
    const Rgb& b = ramp_rgb_[size_t(i) + 1];
    const auto mix = [f](double p, double q) { return float((1.0 - f) * p + f * q); };
    return SampledSpectrum(mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b), mix(a.g, b.g));
  }
  BasisCoefficients blend = ramp_[size_t(i)];
  const BasisCoefficients& next = ramp_[size_t(i) + 1];
  for (int k = 0; k < kUpsamplingBasisSize; ++k) blend.c[size_t(k)] = (1.0f - f) * blend.c[size_t(k)] + f * next.c[size_t(k)];
  return upsampler_->basis().evaluate(blend, lambda.lambda_nm(), Float4(0.0f), Float4(1.0f));
}

}  // namespace rimu
