#include "transport/textures/perlin_noise.h"

#include <array>
#include <cmath>

namespace rimu {
namespace {

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

}  // namespace

float perlin_noise(Vec3 p) {
  constexpr float kWrap = float(1 << 30);
  // A non-finite coordinate (a degenerate transform) has no lattice cell; 0 is the lattice value.
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return 0.0f;
  const float x = std::fmod(p.x, kWrap), y = std::fmod(p.y, kWrap), z = std::fmod(p.z, kWrap);
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

float fbm(Vec3 p, float omega, int octaves) {
  float sum = 0.0f, frequency = 1.0f, weight = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    sum += weight * perlin_noise(p * frequency);
    frequency *= 1.99f;
    weight *= omega;
  }
  return sum;
}

float turbulence(Vec3 p, float omega, int octaves) {
  float sum = 0.0f, frequency = 1.0f, weight = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    sum += weight * std::fabs(perlin_noise(p * frequency));
    frequency *= 1.99f;
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
