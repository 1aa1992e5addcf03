// Exact direct irradiance of emitters on a Lambertian receiver, and the check of the path integrator against it
// (shared by integration_emitter_distance_test.cpp and integration_emitter_types_test.cpp).
//
// A Lambertian receiver point x (albedo ρ) reflects the direct radiance L_out = ρ/π · E, E its irradiance. For an
// emitting polygon mesh of uniform radiance L, E = L · Σ Φ_f over the faces x sees, Φ_f the projected solid angle
// of face f, exact by Lambert's formula Φ = ½ Σᵢ Θᵢ (n · Γᵢ) (Θᵢ the angle its edge i subtends at x, Γᵢ the unit
// normal of the plane through x and that edge; Arvo 1995, "Applications of irradiance tensors").
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "integration_support.h"
#include "test_support.h"

namespace rimu::test::emitters {

using rimu::test::kPi;
inline constexpr double kAlbedo = 0.5;
inline constexpr double kRadiance = 1.0;  // constant spectral radiance of the emitters (every lane sees the same)

struct Vec3d {
  double x, y, z;
};
inline Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3d operator+(Vec3d a, Vec3d b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3d operator*(double s, Vec3d a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot3(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d cross3(Vec3d a, Vec3d b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline Vec3d unit(Vec3d a) {
  const double l = std::sqrt(dot3(a, a));
  return {a.x / l, a.y / l, a.z / l};
}

struct Mesh {
  std::vector<Vec3d> positions;
  std::vector<uint32_t> indices;
};

/// Lambert's projected solid angle of the polygon `corners` (as seen from x with normal n), for a polygon wholly
/// above x's tangent plane: ½ |Σᵢ Θᵢ (n · Γᵢ)|.
inline double projected_solid_angle(const std::vector<Vec3d>& corners, Vec3d x, Vec3d n) {
  double sum = 0.0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3d a = unit(corners[i] - x), b = unit(corners[(i + 1) % corners.size()] - x);
    const double theta = std::acos(std::clamp(dot3(a, b), -1.0, 1.0));
    sum += theta * dot3(n, unit(cross3(a, b)));
  }
  return 0.5 * std::abs(sum);
}

/// Σ Φ over the (one-sided, front = counter-clockwise) faces of `mesh` whose front x sees; for a mesh that x sees
/// without one face hiding another (convex, or an open cylinder seen from outside), those are exactly the faces
/// that light x.
inline double mesh_projected_solid_angle(const Mesh& mesh, Vec3d x, Vec3d n) {
  double sum = 0.0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3d a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                c = mesh.positions[mesh.indices[t + 2]];
    if (dot3(cross3(b - a, c - a), x - a) > 0.0) sum += projected_solid_angle({a, b, c}, x, n);
  }
  return sum;
}

inline nlohmann::json mesh_json(const Mesh& mesh) {
  nlohmann::json positions = nlohmann::json::array();
  for (const Vec3d& p : mesh.positions) positions.push_back({p.x, p.y, p.z});
  return {{"type", "triangles"}, {"material", "black"}, {"emission", kRadiance}, {"positions", positions},
          {"indices", mesh.indices}};
}

/// A Lambertian plane y = 0 (albedo ρ, `plane_half_size` m each way from the origin) and the given shapes and lights.
inline nlohmann::json receiver_scene(const nlohmann::json& shapes, const nlohmann::json& lights, const std::string& mode,
                                     const std::string& light_sampler, double plane_half_size = 1.0) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 2, -2], "to": [0, 0, 0], "vertical_fov_deg": 20},
    "film": {"resolution": [8, 8], "filter": {"type": "box"}},
    "materials": {"black": {"type": "diffuse", "reflectance": 0}}
  })");
  scene["materials"]["plane"] = {{"type", "diffuse"}, {"reflectance", kAlbedo}};
  scene["integrator"] = {{"max_depth", 1}, {"direct_lighting", mode}, {"light_sampler", light_sampler}};
  scene["shapes"] = shapes.is_null() ? nlohmann::json::array() : shapes;
  const double h = plane_half_size;
  scene["shapes"].push_back({{"type", "quad"}, {"material", "plane"},
                             {"vertices", {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}}}});
  if (!lights.is_null()) scene["lights"] = lights;
  return scene;
}

/// The direct radiance of the plane at `receiver` (y = 0) by `count` rays from `height` above it, lane by lane,
/// checked against `exact` (per lane): |mean − exact| ≤ kSigmas·SE, and kSigmas·SE ≤ `resolution`·exact (the check
/// can see a bias of that size). A zero-variance estimator (BSDF sampling of a constant environment) still rounds:
/// the mean may differ from `exact` by 1e-6 of it (float radiance, ~10 operations).
inline void check_lanes_at(const Scene& scene, Vec3d receiver, float height, int count,
                           const std::array<double, 4>& exact, double resolution, uint64_t seed = 17) {
  const Vec3 at(float(receiver.x), 0.0f, float(receiver.z));
  const auto lanes = lane_radiance(scene, [&](int) { return ray_between(at + Vec3(0.0f, height, 0.0f), at); }, count, seed);
  for (int j = 0; j < 4; ++j) {
    const double e = exact[size_t(j)];
    CAPTURE(j);
    CAPTURE(lanes[size_t(j)].mean);
    CAPTURE(lanes[size_t(j)].standard_error);
    CAPTURE(e);
    CHECK(std::abs(lanes[size_t(j)].mean - e) <= std::max(kSigmas * lanes[size_t(j)].standard_error, 1e-6 * e));
    CHECK(kSigmas * lanes[size_t(j)].standard_error <= resolution * e);
  }
}

/// The same with constant spectra: every lane has the same exact value.
inline void check_estimate_at(const nlohmann::json& scene_json, Vec3d receiver, float height, int count, double exact,
                              double resolution, uint64_t seed = 17) {
  check_lanes_at(*scene_from_json(scene_json), receiver, height, count, {exact, exact, exact, exact}, resolution, seed);
}

/// The same at the origin, from just above it (half the gap to the emitter, at most 1 cm).
inline void check_estimate(const nlohmann::json& scene_json, double gap_m, int count, double exact, double resolution) {
  check_estimate_at(scene_json, {0, 0, 0}, float(std::min(0.5 * gap_m, 0.01)), count, exact, resolution);
}

/// Gaps from 0.01× to 100× the emitter's size D.
inline constexpr double kGapsInSizes[] = {0.01, 0.1, 1.0, 10.0, 100.0};

}  // namespace rimu::test::emitters
