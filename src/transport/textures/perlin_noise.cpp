#include "transport/textures/perlin_noise.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rimu {
namespace {

// pbrt-v4 takes coordinates modulo 2³⁰ (its guard against int overflow); below that fmod is the identity.
constexpr float kWrap = float(1 << 30);

// Ken Perlin's permutation of 0-255 (the reference implementation of "Improving Noise", SIGGRAPH 2002), repeated
// once so that p[p[p[x] + y] + z] never needs a wrap (x, y, z ≤ 256).
constexpr std::array<unsigned char, 256> kPermutation = {
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225,
    140, 36, 103, 30, 69, 142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148,
    247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219, 203, 117, 35, 11, 32,
    57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122,
    60, 211, 133, 230, 220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54,
    65, 25, 63, 161, 1, 216, 80, 73, 209, 76, 132, 187, 208, 89, 18, 169,
    200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186, 3, 64,
    52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212,
    207, 206, 59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213,
    119, 248, 152, 2, 44, 154, 163, 70, 221, 153, 101, 155, 167, 43, 172, 9,
    129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178, 185, 112, 104,
    218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241,
    81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157,
    184, 84, 204, 176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93,
    222, 114, 67, 29, 24, 72, 243, 141, 128, 195, 78, 66, 215, 61, 156, 180,
};

constexpr std::array<unsigned char, 512> doubled() {
  std::array<unsigned char, 512> p{};
  for (int i = 0; i < 512; ++i) p[size_t(i)] = kPermutation[size_t(i & 255)];
  return p;
}
constexpr std::array<unsigned char, 512> kP = doubled();

// The gradient of lattice point (x, y, z) dotted with the offset (dx, dy, dz): one of twelve edge directions of the
// cube (±1, ±1, 0) and permutations, with four of the sixteen hash values repeating (±1, ±1, 0) and (0, ±1, ±1)
// as pbrt-v4 assigns them (hash 12 and 13 use (dx, dy); Perlin's reference uses (dy, dx) for 12, (dy, dz) for 13).
float gradient(int x, int y, int z, float dx, float dy, float dz) {
  const int h = kP[size_t(kP[size_t(kP[size_t(x)] + y)] + z)] & 15;
  const float u = (h < 8 || h == 12 || h == 13) ? dx : dy;
  const float v = (h < 4 || h == 12 || h == 13) ? dy : dz;
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// 6t⁵ − 15t⁴ + 10t³: zero first and second derivatives at t = 0 and 1.
float fade(float t) {
  const float t3 = t * t * t;
  return t3 * (t * (t * 6.0f - 15.0f) + 10.0f);
}

float lerp(float t, float a, float b) { return (1.0f - t) * a + t * b; }

// The lane-wise forms of the three above, with the scalar forms' operations in the same order (so the same bits:
// Rimu builds for SSE4.1 without FMA, so neither form is contracted).
Float4 gradient4(__m128i h, Float4 dx, Float4 dy, Float4 dz) {
  const auto is = [h](int value) { return Mask4(_mm_castsi128_ps(_mm_cmpeq_epi32(h, _mm_set1_epi32(value)))); };
  const auto below = [h](int value) { return Mask4(_mm_castsi128_ps(_mm_cmplt_epi32(h, _mm_set1_epi32(value)))); };
  const Mask4 twelve_or_thirteen = is(12) | is(13);
  const Float4 u = select(below(8) | twelve_or_thirteen, dx, dy);
  const Float4 v = select(below(4) | twelve_or_thirteen, dy, dz);
  // Negation flips the sign bit, as the scalar unary minus does: bit 0 of h for u, bit 1 for v.
  const __m128i one = _mm_set1_epi32(1);
  const Float4 sign_u(_mm_castsi128_ps(_mm_slli_epi32(_mm_and_si128(h, one), 31)));
  const Float4 sign_v(_mm_castsi128_ps(_mm_slli_epi32(_mm_and_si128(_mm_srli_epi32(h, 1), one), 31)));
  return Float4(_mm_xor_ps(u.v, sign_u.v)) + Float4(_mm_xor_ps(v.v, sign_v.v));
}
Float4 fade4(Float4 t) {
  const Float4 t3 = t * t * t;
  return t3 * (t * (t * Float4(6.0f) - Float4(15.0f)) + Float4(10.0f));
}
Float4 lerp4(Float4 t, Float4 a, Float4 b) { return (Float4(1.0f) - t) * a + t * b; }

}  // namespace

float perlin_noise(Vec3 p) {
  // A non-finite coordinate (a degenerate transform) has no lattice cell; 0 is the lattice value.
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return 0.0f;
  // fmod by 2³⁰ is the identity below 2³⁰ in magnitude, and a library call (tens of ns) that cost more than the
  // rest of the noise: taken only where it changes something.
  const auto wrap = [](float v) { return std::fabs(v) < kWrap ? v : std::fmod(v, kWrap); };
  const float x = wrap(p.x), y = wrap(p.y), z = wrap(p.z);
  const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const float dx = x - fx, dy = y - fy, dz = z - fz;
  const int ix = int(fx) & 255, iy = int(fy) & 255, iz = int(fz) & 255;
  const float w000 = gradient(ix, iy, iz, dx, dy, dz);
  const float w100 = gradient(ix + 1, iy, iz, dx - 1, dy, dz);
  const float w010 = gradient(ix, iy + 1, iz, dx, dy - 1, dz);
  const float w110 = gradient(ix + 1, iy + 1, iz, dx - 1, dy - 1, dz);
  const float w001 = gradient(ix, iy, iz + 1, dx, dy, dz - 1);
  const float w101 = gradient(ix + 1, iy, iz + 1, dx - 1, dy, dz - 1);
  const float w011 = gradient(ix, iy + 1, iz + 1, dx, dy - 1, dz - 1);
  const float w111 = gradient(ix + 1, iy + 1, iz + 1, dx - 1, dy - 1, dz - 1);
  const float wx = fade(dx), wy = fade(dy), wz = fade(dz);
  const float y0 = lerp(wy, lerp(wx, w000, w100), lerp(wx, w010, w110));
  const float y1 = lerp(wy, lerp(wx, w001, w101), lerp(wx, w011, w111));
  return lerp(wz, y0, y1);
}

Float4 perlin_noise4(Float4 x, Float4 y, Float4 z) {
  // Below 2³⁰ in magnitude fmod by 2³⁰ is the identity; a lane beyond it, or not finite, takes the scalar path
  // (never in practice: the cloud's and the textures' points are a few hundred units at most).
  if (!(max(max(abs(x), abs(y)), abs(z)) < Float4(kWrap)).all())
    return {perlin_noise(Vec3{x[0], y[0], z[0]}), perlin_noise(Vec3{x[1], y[1], z[1]}),
            perlin_noise(Vec3{x[2], y[2], z[2]}), perlin_noise(Vec3{x[3], y[3], z[3]})};
  const Float4 fx = floor(x), fy = floor(y), fz = floor(z);
  const Float4 dx = x - fx, dy = y - fy, dz = z - fz;
  const __m128i byte = _mm_set1_epi32(255);
  alignas(16) int ix[4], iy[4], iz[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(ix), _mm_and_si128(_mm_cvttps_epi32(fx.v), byte));
  _mm_store_si128(reinterpret_cast<__m128i*>(iy), _mm_and_si128(_mm_cvttps_epi32(fy.v), byte));
  _mm_store_si128(reinterpret_cast<__m128i*>(iz), _mm_and_si128(_mm_cvttps_epi32(fz.v), byte));
  // The eight corners' hashes kP[kP[kP[x] + y] + z] & 15 per lane, sharing the inner lookups; corner c = (x, y, z)
  // offsets in bits 0, 1, 2.
  alignas(16) int h[8][4];
  for (int lane = 0; lane < 4; ++lane) {
    const int a = kP[size_t(ix[lane])] + iy[lane], b = kP[size_t(ix[lane] + 1)] + iy[lane];
    const int row[4] = {kP[size_t(a)] + iz[lane], kP[size_t(b)] + iz[lane], kP[size_t(a + 1)] + iz[lane],
                        kP[size_t(b + 1)] + iz[lane]};  // (x, y) = (0,0), (1,0), (0,1), (1,1)
    for (int c = 0; c < 4; ++c) {
      h[c][lane] = kP[size_t(row[c])] & 15;
      h[c + 4][lane] = kP[size_t(row[c] + 1)] & 15;
    }
  }
  const auto corner = [&h](int c) { return _mm_load_si128(reinterpret_cast<const __m128i*>(h[c])); };
  const Float4 one(1.0f);
  const Float4 w000 = gradient4(corner(0), dx, dy, dz);
  const Float4 w100 = gradient4(corner(1), dx - one, dy, dz);
  const Float4 w010 = gradient4(corner(2), dx, dy - one, dz);
  const Float4 w110 = gradient4(corner(3), dx - one, dy - one, dz);
  const Float4 w001 = gradient4(corner(4), dx, dy, dz - one);
  const Float4 w101 = gradient4(corner(5), dx - one, dy, dz - one);
  const Float4 w011 = gradient4(corner(6), dx, dy - one, dz - one);
  const Float4 w111 = gradient4(corner(7), dx - one, dy - one, dz - one);
  const Float4 wx = fade4(dx), wy = fade4(dy), wz = fade4(dz);
  const Float4 y0 = lerp4(wy, lerp4(wx, w000, w100), lerp4(wx, w010, w110));
  const Float4 y1 = lerp4(wy, lerp4(wx, w001, w101), lerp4(wx, w011, w111));
  return lerp4(wz, y0, y1);
}

int perlin_octaves(Vec3 p, int octaves, float* values) {
  octaves = std::clamp(octaves, 0, kMaxNoiseOctaves);
  alignas(16) float frequencies[kMaxNoiseOctaves];
  float frequency = 1.0f;
  for (int i = 0; i < octaves; ++i, frequency *= 1.99f) frequencies[i] = frequency;
  int i = 0;
  for (; i + 4 <= octaves; i += 4) {
    const Float4 f = Float4::load(frequencies + i);
    const auto n = perlin_noise4(Float4(p.x) * f, Float4(p.y) * f, Float4(p.z) * f).to_array();
    for (int k = 0; k < 4; ++k) values[i + k] = n[size_t(k)];
  }
  for (; i < octaves; ++i) values[i] = perlin_noise(p * frequencies[i]);
  return octaves;
}

float fbm(Vec3 p, float omega, int octaves) {
  float values[kMaxNoiseOctaves];
  const int n = perlin_octaves(p, octaves, values);
  float sum = 0.0f, weight = 1.0f;
  for (int i = 0; i < n; ++i) {
    sum += weight * values[i];
    weight *= omega;
  }
  return sum;
}

float turbulence(Vec3 p, float omega, int octaves) {
  float values[kMaxNoiseOctaves];
  const int n = perlin_octaves(p, octaves, values);
  float sum = 0.0f, weight = 1.0f;
  for (int i = 0; i < n; ++i) {
    sum += weight * std::fabs(values[i]);
    weight *= omega;
  }
  return sum + weight * 0.2f;
}

bool inside_polka_dot(Vec2 st) {
  const float s_cell = std::floor(st.x + 0.5f), t_cell = std::floor(st.y + 0.5f);
  if (!(perlin_noise(s_cell + 0.5f, t_cell + 0.5f) > 0.0f)) return false;
  constexpr float kRadius = 0.35f, kMaxShift = 0.5f - kRadius;
  const float s_centre = s_cell + kMaxShift * perlin_noise(s_cell + 1.5f, t_cell + 2.8f);
  const float t_centre = t_cell + kMaxShift * perlin_noise(s_cell + 4.5f, t_cell + 9.8f);
  const float ds = st.x - s_centre, dt = st.y - t_centre;
  return ds * ds + dt * dt < kRadius * kRadius;
}

}  // namespace rimu
