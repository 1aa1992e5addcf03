// Perlin's improved gradient noise (Perlin 2002) and the sums pbrt-v4's procedural textures build from it.
#pragma once

#include "spectral/wavelengths/lanes.h"
#include "transport/geometry/vector.h"

namespace rimu {

/// Gradient noise at p: zero at every integer lattice point, continuous with continuous first and second
/// derivatives (the quintic fade 6t⁵ − 15t⁴ + 10t³), |value| ≤ 2 (a convex blend of corner terms ±dᵢ ± dⱼ with
/// |dᵢ| ≤ 1; in practice it stays near ±1). Ken Perlin's published permutation table and pbrt-v4's twelve-plus-four gradient
/// choice (its `Grad`), so a texture built on it matches pbrt-v4's pixel for pixel. Coordinates are taken modulo
/// 2³⁰ first (pbrt-v4's guard against int overflow). ~10 ns.
float perlin_noise(Vec3 p);
inline float perlin_noise(float x, float y, float z = 0.5f) { return perlin_noise(Vec3{x, y, z}); }
/// The noise at four points at once, lane i at (x[i], y[i], z[i]): every lane bit for bit what perlin_noise gives
/// (the same operations in the same order, on SSE lanes; the lattice hashes stay scalar lookups). For what needs
/// several values at a time, like the cloud medium's gradients and octaves: about 2.5 scalar calls' cost for four.
Float4 perlin_noise4(Float4 x, Float4 y, Float4 z);

/// The most octaves perlin_octaves, fbm and turbulence evaluate (the textures allow 30).
inline constexpr int kMaxNoiseOctaves = 32;
/// noise(1.99ⁱ·p) for i < octaves (at most kMaxNoiseOctaves) into `values`, four octaves per perlin_noise4 call:
/// each value bit for bit perlin_noise(p·1.99ⁱ), the frequency being the same running product. Returns the count.
int perlin_octaves(Vec3 p, int octaves, float* values);

/// Fractional Brownian motion: Σᵢ ωⁱ·noise(λᵢ·p), λᵢ = 1.99ⁱ, i < octaves (pbrt-v4's FBm with every octave
/// present: Rimu's procedural textures do not use the ray differentials to drop the octaves a pixel cannot resolve).
float fbm(Vec3 p, float omega, int octaves);

/// Turbulence: Σᵢ ωⁱ·|noise(λᵢ·p)| over the octaves, plus pbrt-v4's 0.2·ω^octaves for the octaves beyond the last
/// (its average |noise|, what pbrt adds for octaves it clamps away; at full resolution only this last term remains).
float turbulence(Vec3 p, float omega, int octaves);

/// pbrt-v4's polka dots: inside a dot of radius 0.35 centred near the unit cell's centre (shifted by up to 0.15 by
/// noise) in cells whose noise is positive (about half of them). st is the 2D texture coordinate.
bool inside_polka_dot(Vec2 st);

}  // namespace rimu
