// Light sampling only, BSDF sampling only and their MIS combination converge to the same radiance for every kind
// of emitter, from a receiver almost touching it (a gap of 0.01× its size) to one far away (100×), and that
// radiance is the exact one. The receiver is a Lambertian plane point x (albedo ρ) with the emitter's centre
// straight above it; the direct-lighting radiance it reflects is L_out = ρ/π · E, E its irradiance:
//   - an emitting polygon mesh of uniform radiance L: E = L · Σ Φ_f over the faces x sees, Φ_f the projected solid
//     angle of face f, exact by Lambert's formula Φ = ½ Σᵢ Θᵢ (n · Γᵢ) (Θᵢ the angle its edge i subtends at x, Γᵢ
//     the unit normal of the plane through x and that edge; Arvo 1995, "Applications of irradiance tensors");
//   - a tessellated sphere of radius r whose centre is at distance d: the same sum, which approaches the sphere's
//     π L (r/d)² as the tessellation is refined (checked too, within the tessellation's own error);
//   - a point light of intensity I at height h: E = I/h²; a spot on its axis: the same with its axial intensity.
// Delta lights are reached by light sampling only (BSDF sampling cannot hit them), so for them nee_only and mis
// are checked against the exact E and bsdf_only is not run.
//
// Every check: N camera rays all ending at x (integration_support.h lane_radiance, an independent sampler), whose
// per-ray estimates are i.i.d., |mean − exact| ≤ kSigmas·SE, and the test asserts that kSigmas·SE is small enough
// (a few % of the exact value) to see a bias of that size. max_depth 1 keeps only the direct light.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "integration_support.h"

using namespace rimu;
using namespace rimu::test;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kAlbedo = 0.5;
constexpr double kRadiance = 1.0;  // constant spectral radiance of the emitters (every lane sees the same)

struct Vec3d {
  double x, y, z;
};
Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot3(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d cross3(Vec3d a, Vec3d b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
Vec3d unit(Vec3d a) {
  const double l = std::sqrt(dot3(a, a));
  return {a.x / l, a.y / l, a.z / l};
}

struct Mesh {
  std::vector<Vec3d> positions;
  std::vector<uint32_t> indices;
};

// A UV sphere (the importer's tessellation of pbrt's sphere: 48 × 96, 9024 triangles), pole along z so that the
// point below it (along −y) sees a generic patch of its equator, wound counter-clockwise seen from outside.
Mesh tessellated_sphere(Vec3d centre, double radius, int rows = 48, int columns = 96) {
  Mesh m;
  m.positions.push_back({centre.x, centre.y, centre.z + radius});
  for (int i = 1; i < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      const double theta = kPi * i / rows, phi = 2 * kPi * j / columns;
      m.positions.push_back({centre.x + radius * std::sin(theta) * std::cos(phi),
                             centre.y + radius * std::sin(theta) * std::sin(phi), centre.z + radius * std::cos(theta)});
    }
  m.positions.push_back({centre.x, centre.y, centre.z - radius});
  const uint32_t south = uint32_t(m.positions.size() - 1);
  const auto at = [&](int i, int j) { return uint32_t(1 + (i - 1) * columns + (j % columns)); };
  for (int j = 0; j < columns; ++j) {
    m.indices.insert(m.indices.end(), {0u, at(1, j), at(1, j + 1)});
    for (int i = 1; i + 1 < rows; ++i)
      m.indices.insert(m.indices.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    m.indices.insert(m.indices.end(), {at(rows - 1, j), south, at(rows - 1, j + 1)});
  }
  return m;
}

// Lambert's projected solid angle of the polygon `corners` (as seen from x with normal n), for a polygon wholly
// above x's tangent plane: ½ |Σᵢ Θᵢ (n · Γᵢ)|.
double projected_solid_angle(const std::vector<Vec3d>& corners, Vec3d x, Vec3d n) {
  double sum = 0.0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3d a = unit(corners[i] - x), b = unit(corners[(i + 1) % corners.size()] - x);
    const double theta = std::acos(std::clamp(dot3(a, b), -1.0, 1.0));
    sum += theta * dot3(n, unit(cross3(a, b)));
  }
  return 0.5 * std::abs(sum);
}

// Σ Φ over the (one-sided, front = counter-clockwise) faces of `mesh` whose front x sees; the mesh is convex, so
// those are exactly the faces x sees.
double mesh_projected_solid_angle(const Mesh& mesh, Vec3d x, Vec3d n) {
  double sum = 0.0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3d a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                c = mesh.positions[mesh.indices[t + 2]];
    if (dot3(cross3(b - a, c - a), x - a) > 0.0) sum += projected_solid_angle({a, b, c}, x, n);
  }
  return sum;
}

nlohmann::json mesh_json(const Mesh& mesh) {
  nlohmann::json positions = nlohmann::json::array();
  for (const Vec3d& p : mesh.positions) positions.push_back({p.x, p.y, p.z});
  return {{"type", "triangles"}, {"material", "black"}, {"emission", kRadiance}, {"positions", positions},
          {"indices", mesh.indices}};
}

// A Lambertian plane y = 0 (albedo ρ, 2 m across: only its point under the emitter is seen) and the given shapes and lights.
nlohmann::json receiver_scene(const nlohmann::json& shapes, const nlohmann::json& lights, const std::string& mode,
                              const std::string& light_sampler) {
  nlohmann::json scene = nlohmann::json::parse(R"({
    "camera": {"from": [0, 2, -2], "to": [0, 0, 0], "vertical_fov_deg": 20},
    "film": {"resolution": [8, 8], "filter": {"type": "box"}},
    "materials": {"black": {"type": "diffuse", "reflectance": 0}}
  })");
  scene["materials"]["plane"] = {{"type", "diffuse"}, {"reflectance", kAlbedo}};
  scene["integrator"] = {{"max_depth", 1}, {"direct_lighting", mode}, {"light_sampler", light_sampler}};
  scene["shapes"] = shapes;
  scene["shapes"].push_back({{"type", "quad"}, {"material", "plane"},
                             {"vertices", {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}}});
  if (!lights.is_null()) scene["lights"] = lights;
  return scene;
}

// The direct radiance at the origin of the plane by `count` rays from just above it (below the emitter), lane 0
// (every lane is the same: constant spectra), checked against `exact`.
void check_estimate(const nlohmann::json& scene_json, double gap_m, int count, double exact, double resolution) {
  const auto scene = scene_from_json(scene_json);
  const float height = float(std::min(0.5 * gap_m, 0.01));
  const auto lanes = lane_radiance(*scene, [&](int) { return ray_between({0.0f, height, 0.0f}, {0, 0, 0}); }, count, 17);
  for (int j = 0; j < 4; ++j) {
    CAPTURE(j);
    CAPTURE(lanes[size_t(j)].mean);
    CAPTURE(lanes[size_t(j)].standard_error);
    CHECK(std::abs(lanes[size_t(j)].mean - exact) <= kSigmas * lanes[size_t(j)].standard_error);
    CHECK(kSigmas * lanes[size_t(j)].standard_error <= resolution * exact);
  }
}

// Gaps from 0.01× to 100× the emitter's size D.
constexpr double kGapsInSizes[] = {0.01, 0.1, 1.0, 10.0, 100.0};

}  // namespace

TEST_CASE("emitter distance: a tessellated emissive sphere, NEE only, BSDF only and MIS give the exact irradiance") {
  const double radius = 0.028;  // the bathroom's bulbs (issue 29): 2.8 cm, 9024 triangles
  for (const std::string sampler : {"bvh", "power"}) {
    for (double gap_in_sizes : kGapsInSizes) {
      const double gap = gap_in_sizes * 2 * radius, d = radius + gap;
      const Mesh sphere = tessellated_sphere({0, d, 0}, radius);
      const double phi = mesh_projected_solid_angle(sphere, {0, 0, 0}, {0, 1, 0});
      // The tessellation's projected solid angle is the sphere's π(r/d)² to within its area deficit (~0.2 %).
      CHECK(phi == doctest::Approx(kPi * (radius / d) * (radius / d)).epsilon(0.005));
      const double exact = kAlbedo / kPi * kRadiance * phi;
      for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
        // BSDF sampling finds the sphere with probability ≈ (r/d)²: beyond a gap of 1× its size the samples a
        // fast test can afford do not resolve it (MIS, which includes it, is checked at every gap).
        if (mode == "bsdf_only" && (gap_in_sizes > 1.0 || sampler != "bvh")) continue;  // no light choice there
        // The power sampler picks a triangle by area over the whole mesh (half of them facing away), so near the
        // sphere a few triangles carry all the light and are rarely picked: its variance there is too high for a
        // test of this size to resolve 5 %; it is checked from a gap of 1× on.
        if (sampler == "power" && gap_in_sizes < 1.0) continue;
        CAPTURE(sampler);
        CAPTURE(gap_in_sizes);
        CAPTURE(mode);
        const int count = mode == "bsdf_only" ? 100000 : sampler == "power" ? 40000 : 16000;
        check_estimate(receiver_scene(nlohmann::json::array({mesh_json(sphere)}), nullptr, mode, sampler), gap, count,
                       exact, 0.05);
      }
    }
  }
}

TEST_CASE("emitter distance: a square area light facing a plane, NEE only, BSDF only and MIS give the exact irradiance") {
  const double side = 0.2;  // D
  for (double gap_in_sizes : kGapsInSizes) {
    const double gap = gap_in_sizes * side, h = 0.5 * side;
    // Counter-clockwise seen from below: its front faces the plane.
    const std::vector<Vec3d> corners = {{-h, gap, -h}, {h, gap, -h}, {h, gap, h}, {-h, gap, h}};
    const double exact = kAlbedo / kPi * kRadiance * projected_solid_angle(corners, {0, 0, 0}, {0, 1, 0});
    nlohmann::json vertices = nlohmann::json::array();
    for (const Vec3d& c : corners) vertices.push_back({c.x, c.y, c.z});
    const nlohmann::json quad = {{"type", "quad"}, {"material", "black"}, {"emission", kRadiance}, {"vertices", vertices}};
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      if (mode == "bsdf_only" && gap_in_sizes > 1.0) continue;  // as for the sphere
      CAPTURE(gap_in_sizes);
      CAPTURE(mode);
      const int count = mode == "bsdf_only" ? 40000 : 4000;
      check_estimate(receiver_scene(nlohmann::json::array({quad}), nullptr, mode, "bvh"), gap, count, exact, 0.05);
    }
  }
}

TEST_CASE("emitter distance: point and spot lights (delta: light sampling only) give I/h^2 at every height") {
  const double intensity = 2.0, size = 0.05;  // a "size" for the heights only: delta lights have none
  for (double gap_in_sizes : kGapsInSizes) {
    const double h = gap_in_sizes * size;
    const double exact = kAlbedo / kPi * intensity / (h * h);
    const nlohmann::json point = {{"type", "point"}, {"position", {0, h, 0}}, {"intensity", intensity}};
    const nlohmann::json spot = {{"type", "spot"}, {"position", {0, h, 0}}, {"direction", {0, -1, 0}},
                                 {"cone_angle_deg", 60}, {"intensity", intensity}};
    for (const nlohmann::json& light : {point, spot})
      for (const std::string mode : {"nee_only", "mis"}) {
        CAPTURE(gap_in_sizes);
        CAPTURE(mode);
        CAPTURE(light.dump());
        const auto scene = scene_from_json(receiver_scene(nlohmann::json::array(), nlohmann::json::array({light}), mode, "bvh"));
        const float from = float(std::min(0.5 * h, 0.01));
        const auto lanes = lane_radiance(*scene, [&](int) { return ray_between({0.0f, from, 0.0f}, {0, 0, 0}); }, 16);
        for (int j = 0; j < 4; ++j) CHECK(lanes[size_t(j)].mean == doctest::Approx(exact).epsilon(1e-5));
      }
  }
}

