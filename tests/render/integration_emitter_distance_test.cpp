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
#include <string>
#include <vector>

#include "emitter_irradiance.h"

using namespace rimu;
using namespace rimu::test;
using namespace rimu::test::emitters;

namespace {

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


// A receiver far from the bulb and nearly in the plane of its base: the 2.8 cm bulb 2.2 cm above the plane, seen
// from 0.85 m, stands 1.5°–5.2° above the receiver's horizon (the top-left corner of the near-bulb image in
// docs/transport.md, where nee_only came out 16.9 "σ" above bsdf_only). Light sampling there passes through every
// grazing case at once: the light tree's cones and boxes at the receiver's horizon, cos θᵢ ≈ 0.06 at the receiver,
// the silhouette triangles' cos θ_l → 0 at the bulb, area sampling (the triangles are far). nee_only and MIS must
// give Lambert's exact value. BSDF sampling is unbiased here too but finds the bulb with probability Φ/π ≈ 6e-5 a
// ray: an image block of 64 pixels × 64 spp catches 0 or 1 hit, and a standard error from those samples is 0 or
// meaningless, which is what the 16.9 "σ" was (measured with an illuminance meter at such a point: 8 runs of 16 M
// independent BSDF samples, the standard error from the spread of the run means, 0.991 ± 0.006 of the exact value;
// nee_only 1.002 ± 0.002; docs/transport.md). It would need ~10⁷ rays for 5 %, so it is not run here.
TEST_CASE("emitter distance: a tessellated bulb just above a far receiver's horizon, NEE only and MIS are exact") {
  const double radius = 0.028, centre_height = 0.05, distance = 0.85;
  const Mesh sphere = tessellated_sphere({0, centre_height, 0}, radius);
  const Vec3d receiver{distance, 0, 0};
  const double phi = mesh_projected_solid_angle(sphere, receiver, {0, 1, 0});
  const double exact = kAlbedo / kPi * kRadiance * phi;
  for (const std::string sampler : {"bvh", "power"})
    for (const std::string mode : {"nee_only", "mis"}) {
      CAPTURE(sampler);
      CAPTURE(mode);
      check_estimate_at(receiver_scene(nlohmann::json::array({mesh_json(sphere)}), nullptr, mode, sampler), receiver,
                        0.01f, 16000, exact, 0.05);
    }
}
