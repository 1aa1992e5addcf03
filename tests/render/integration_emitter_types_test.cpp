// Light sampling only, BSDF sampling only and their MIS give the exact direct irradiance for every kind of emitter
// (the tessellated sphere, the square and the point and spot lights are in integration_emitter_distance_test.cpp):
//   - emissive analytic shapes, which are tessellated meshes (render/scene/analytic_shapes.h): a `disk`, a
//     `cylinder` and the tessellated sphere (the pbrt importer's mesh for partial or reversed spheres), at gaps of
//     0.01× to 100× their size; the exact value is Lambert's formula summed over the very mesh the loader builds
//     (analytic_shapes.h's functions, transformed here as the scene's `matrix` does); the disk also agrees with the
//     on-axis disk's π L r²/(r² + h²) to the tessellation's 1e-3, the sphere with π L (r/d)² to 0.5 %;
//   - the analytic emissive `sphere` (a light of its own, sampled by cone): π L sin²θmax cos β exactly, head-on at the
//     same gaps, at d = 1.05 r, and grazing (its edge 1° above the horizon);
//   - one triangle seen almost edge-on (its normal 87° from the receiver), at the same gaps;
//   - a quad with an emission image (radiance varying over it), at the same gaps, against quadrature;
//   - a `distant` light: delta (E cos θ, light sampling only), the sun's 0.53° disc (E cos θ: BSDF sampling would
//     need ~4·10⁸ rays) and a 60° disc (all three), E being the irradiance normal to the disc's centre, so that a
//     tilted plane wholly below the disc receives E cos θ exactly (∫ ω dω over a cone is its axis times π sin²α);
//   - a constant `environment` of radiance L over an unoccluded plane: E = π L;
//   - the same environment seen only through a square skylight of a closed room, with and without a portal on it:
//     E = L Φ(skylight); and an environment image, constant above the horizon, in both settings;
//   - CIE standard skies (overcast, clear) calibrated by their horizontal illuminance, which is then E;
//   - an `ies` and a `goniometric` light, which BSDF sampling cannot hit: nee_only gives ρ/π · I(γ) cos θ/d² (the
//     candela over K_m ∫V dλ for a flat spectrum) and mis the same (light sampling with MIS weight 1), to float
//     precision.
// Each statistical check is the distance test's: N i.i.d. per-ray estimates, |mean − exact| ≤ kSigmas (4.5) SE
// (a false alarm once in ~1.5e5 checks for Gaussian means; there are ~80 independent ones here, the four lanes of
// one run sharing their rays), and kSigmas·SE ≤ 5 % of the exact value, so a bias of that size cannot hide in the
// noise. Where BSDF sampling hits the emitter with probability p per ray, its relative SE is √((1 − p)/(pN)): the
// counts below are chosen from that and from the measured deviations noted beside them.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "emitter_irradiance.h"
#include "render/scene/analytic_shapes.h"
#include "test_image_files.h"

using namespace rimu;
using namespace rimu::test;
using namespace rimu::test::emitters;
using nlohmann::json;

namespace {

double rad(double deg) { return deg * kPi / 180.0; }

// The mesh `analytic` after the affine map x' = M x + t (M row-major 3 × 3), as the scene's {"matrix": ...} step.
Mesh transformed(const AnalyticMesh& analytic, const std::array<double, 12>& m) {
  Mesh out;
  for (const auto& p : analytic.positions)
    out.positions.push_back({m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3], m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7],
                             m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11]});
  out.indices = analytic.indices;
  return out;
}

json matrix_step(const std::array<double, 12>& m) { return json::array({{{"matrix", m}}}); }

// One emitter at every gap and mode: `exact_of(gap)` the exact outgoing radiance, `shape_of(gap)` its JSON; rays:
// `light_count` for nee_only and mis, `near_nee_count` for nee_only at gaps under 1× the size, `bsdf_count`.
template <class Shape, class Exact>
void check_over_gaps(double size, Shape shape_of, Exact exact_of, int light_count, int near_nee_count, int bsdf_count,
                     double bsdf_max_gap_in_sizes) {
  for (double gap_in_sizes : kGapsInSizes) {
    const double gap = gap_in_sizes * size, exact = exact_of(gap);
    const json shape = shape_of(gap);
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      // BSDF sampling finds a small far emitter with probability ≈ Φ/π ≪ 1: beyond this gap a fast test cannot
      // resolve 5 % with it (MIS, which includes it, is checked at every gap).
      if (mode == "bsdf_only" && gap_in_sizes > bsdf_max_gap_in_sizes) continue;
      CAPTURE(gap_in_sizes);
      CAPTURE(mode);
      const int count = mode == "bsdf_only"                       ? bsdf_count
                        : mode == "nee_only" && gap_in_sizes < 1.0 ? near_nee_count
                                                                   : light_count;
      check_estimate(receiver_scene(json::array({shape}), nullptr, mode, "bvh"), gap, count, exact, 0.05);
    }
  }
}

}  // namespace

TEST_CASE("emitter types: an emissive disk facing the plane, the three strategies give the exact irradiance") {
  const double radius = 0.1;  // size D = 0.2
  // The disk (normal +z) turned to face −y and lifted to height `gap`: (x, y, z) → (x, gap − z, y).
  const auto matrix = [](double gap) { return std::array<double, 12>{1, 0, 0, 0, 0, 0, -1, gap, 0, 1, 0, 0}; };
  const AnalyticMesh disk = disk_mesh(0.0, radius, 0.0, 2 * kPi);
  const auto exact = [&](double gap) {
    const double phi = mesh_projected_solid_angle(transformed(disk, matrix(gap)), {0, 0, 0}, {0, 1, 0});
    // The round disk's π r²/(r² + h²), to the tessellation's area deficit (< 1e-3).
    CHECK(phi == doctest::Approx(kPi * radius * radius / (radius * radius + gap * gap)).epsilon(1e-3));
    return kAlbedo / kPi * kRadiance * phi;
  };
  const auto shape = [&](double gap) {
    return json{{"type", "disk"}, {"radius", radius}, {"material", "black"}, {"emission", kRadiance},
                {"transform", matrix_step(matrix(gap))}};
  };
  check_over_gaps(2 * radius, shape, exact, 4000, 4000, 40000, 1.0);
}

TEST_CASE("emitter types: an emissive cylinder lying above the plane, the three strategies give the exact irradiance") {
  const double radius = 0.05, half_length = 0.1;  // size D = 2r = 0.1; its axis along z, its lowest line `gap` up
  const auto matrix = [&](double gap) { return std::array<double, 12>{1, 0, 0, 0, 0, 1, 0, radius + gap, 0, 0, 1, 0}; };
  // Open: from below, the faces x sees hide no others, and its inside (one-sided, facing the axis) is hidden.
  const AnalyticMesh cylinder = cylinder_mesh(radius, -half_length, half_length, 2 * kPi);
  const auto exact = [&](double gap) {
    return kAlbedo / kPi * kRadiance * mesh_projected_solid_angle(transformed(cylinder, matrix(gap)), {0, 0, 0}, {0, 1, 0});
  };
  const auto shape = [&](double gap) {
    return json{{"type", "cylinder"}, {"radius", radius}, {"zmin", -half_length}, {"zmax", half_length},
                {"material", "black"}, {"emission", kRadiance}, {"transform", matrix_step(matrix(gap))}};
  };
  // Its triangles are slivers 3.3 mm × 0.2 m, a few of which fill half the sky of a receiver 1 mm below:
  // nee_only's relative standard deviation per ray is 2.4 there (the disk's 0.6; 10.8 with the power sampler), so
  // it takes 80 000 rays (MIS: 0.3 per ray).
  check_over_gaps(2 * radius, shape, exact, 4000, 80000, 40000, 1.0);
}

TEST_CASE("emitter types: a tessellated emissive sphere, the three strategies agree") {
  // sphere_mesh's triangles (poles with one vertex per column), what a pbrt scene's partial, cut-out or reversed
  // emissive sphere becomes. Size D = 2r.
  const double radius = 0.05;
  const AnalyticMesh sphere = sphere_mesh(radius, -radius, radius, 2 * kPi);
  const auto matrix = [&](double gap) { return std::array<double, 12>{1, 0, 0, 0, 0, 1, 0, radius + gap, 0, 0, 1, 0}; };
  const auto exact = [&](double gap) {
    const double phi = mesh_projected_solid_angle(transformed(sphere, matrix(gap)), {0, 0, 0}, {0, 1, 0});
    const double d = radius + gap;
    CHECK(phi == doctest::Approx(kPi * (radius / d) * (radius / d)).epsilon(0.005));  // the round sphere's
    return kAlbedo / kPi * kRadiance * phi;
  };
  const auto shape = [&](double gap) { return mesh_json(transformed(sphere, matrix(gap))); };
  check_over_gaps(2 * radius, shape, exact, 8000, 8000, 40000, 0.1);
}

TEST_CASE("emitter types: an analytic emissive sphere, the three strategies give pi L sin^2(theta_max) cos(beta)") {
  // The JSON `sphere` with "emission" (transport/lights/sphere_light.h): light sampling draws the cone it subtends.
  // A sphere wholly above the receiver's tangent plane sends E = π L sin²θmax cos β (β from the normal to the
  // centre; exact for a uniform Lambertian sphere), so L_out = ρ L (r/d)² cos β. Size D = 2r.
  const double radius = 0.05;
  const auto sphere = [&](Vec3d centre) {
    return json{{"type", "sphere"}, {"center", {centre.x, centre.y, centre.z}}, {"radius", radius}, {"material", "black"},
                {"emission", kRadiance}};
  };
  SUBCASE("head-on, at gaps of 0.01x to 100x its size") {
    const auto exact = [&](double gap) {
      const double d = radius + gap;
      return kAlbedo * kRadiance * (radius / d) * (radius / d);
    };
    const auto shape = [&](double gap) { return sphere({0, radius + gap, 0}); };
    // BSDF sampling hits it with probability (r/d)²: 0.69 at a gap of 0.1×, 0.11 at 1× (which 40 000 rays resolve to
    // only 6 %).
    check_over_gaps(2 * radius, shape, exact, 4000, 4000, 40000, 0.1);
  }
  SUBCASE("very close: d = 1.05 r") {
    const double d = 1.05 * radius;
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      CAPTURE(mode);
      check_estimate(receiver_scene(json::array({sphere({0, d, 0})}), nullptr, mode, "bvh"), d - radius, 4000,
                     kAlbedo * kRadiance * (radius / d) * (radius / d), 0.05);
    }
  }
  SUBCASE("grazing: its edge 1 degree above the horizon, d = 1.5 r") {
    // sin θmax = 1/1.5 (θmax = 41.8°), β = 89° − θmax: the sphere's lowest point is 0.9 mm above the plane, 5.5 cm
    // to the side of the receiver. BSDF sampling hits it with probability sin²θmax cos β = 0.30.
    const double d = 1.5 * radius, theta_max = std::asin(radius / d), beta = rad(89.0) - theta_max;
    const Vec3d centre{d * std::sin(beta), d * std::cos(beta), 0};
    const double exact = kAlbedo * kRadiance * (radius / d) * (radius / d) * std::cos(beta);
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      CAPTURE(mode);
      // From 1 cm above the receiver the camera ray passes 1.9 cm clear of the sphere.
      check_estimate_at(receiver_scene(json::array({sphere(centre)}), nullptr, mode, "bvh"), {0, 0, 0}, 0.01f,
                        mode == "bsdf_only" ? 40000 : 8000, exact, 0.05);
    }
  }
  SUBCASE("the power light sampler, and a two-sided sphere seen from outside, agree") {
    const double d = 3.0 * radius;
    json two_sided = sphere({0, d, 0});
    two_sided["two_sided"] = true;
    for (const std::string mode : {"nee_only", "mis"}) {
      CAPTURE(mode);
      check_estimate(receiver_scene(json::array({sphere({0, d, 0})}), nullptr, mode, "power"), d - radius, 4000,
                     kAlbedo * kRadiance / 9.0, 0.05);
      check_estimate(receiver_scene(json::array({two_sided}), nullptr, mode, "bvh"), d - radius, 4000,
                     kAlbedo * kRadiance / 9.0, 0.05);
    }
  }
}

TEST_CASE("emitter types: one emissive triangle seen almost edge-on, the three strategies give the exact irradiance") {
  const double side = 0.2, circumradius = side / std::sqrt(3.0);
  // Its normal n is 87° from the straight-down direction to the receiver; t1, t2 span its plane (t2 mostly vertical).
  const double tilt = rad(87.0);
  const Vec3d n{std::sin(tilt), -std::cos(tilt), 0}, t1{0, 0, 1}, t2 = cross3(n, t1);
  const auto corners = [&](double gap) {
    // The lowest corner (along −t2's vertical part) at height `gap`.
    const Vec3d centre{0, gap + circumradius * -t2.y, 0};
    std::vector<Vec3d> c;
    for (int k = 0; k < 3; ++k) {
      const double a = rad(90.0 + 120.0 * k);
      c.push_back(centre + circumradius * (std::cos(a) * t1 + std::sin(a) * t2));
    }
    if (dot3(cross3(c[1] - c[0], c[2] - c[0]), n) < 0.0) std::swap(c[1], c[2]);  // counter-clockwise about n
    return c;
  };
  const auto exact = [&](double gap) {
    return kAlbedo / kPi * kRadiance * projected_solid_angle(corners(gap), {0, 0, 0}, {0, 1, 0});
  };
  const auto shape = [&](double gap) {
    json positions = json::array();
    for (const Vec3d& p : corners(gap)) positions.push_back({p.x, p.y, p.z});
    return json{{"type", "triangles"}, {"material", "black"}, {"emission", kRadiance}, {"positions", positions},
                {"indices", {0, 1, 2}}};
  };
  // BSDF sampling: the triangle's projected solid angle is 0.13 sr at a gap of 0.01×, 2.5e-3 sr at 0.1×.
  check_over_gaps(side, shape, exact, 4000, 4000, 40000, 0.01);
}

TEST_CASE("emitter types: distant lights, delta and with a disc, give E cos theta") {
  const double irradiance = 2.0;
  const auto distant = [&](double tilt_deg, double diameter_deg) {
    return json{{"type", "distant"}, {"direction", {std::sin(rad(tilt_deg)), std::cos(rad(tilt_deg)), 0.0}},
                {"irradiance", irradiance}, {"angular_diameter_deg", diameter_deg}};
  };
  SUBCASE("delta: light sampling only, deterministic") {
    for (const std::string mode : {"nee_only", "mis"}) {
      CAPTURE(mode);
      const auto scene = scene_from_json(receiver_scene(nullptr, json::array({distant(60.0, 0.0)}), mode, "bvh"));
      const auto lanes = lane_radiance(*scene, [](int) { return ray_between({0, 0.01f, 0}, {0, 0, 0}); }, 16);
      for (int j = 0; j < 4; ++j)
        CHECK(lanes[size_t(j)].mean == doctest::Approx(kAlbedo / kPi * irradiance * std::cos(rad(60.0))).epsilon(1e-5));
    }
  }
  SUBCASE("the sun's 0.53 degree disc 30 degrees from the zenith: light sampling and MIS") {
    const double exact = kAlbedo / kPi * irradiance * std::cos(rad(30.0));
    for (const std::string mode : {"nee_only", "mis"}) {
      CAPTURE(mode);
      check_estimate(receiver_scene(nullptr, json::array({distant(30.0, 0.53)}), mode, "bvh"), 1.0, 4000, exact, 0.05);
    }
  }
  SUBCASE("a 60 degree disc 20 degrees from the zenith (wholly above the horizon): all three") {
    // BSDF sampling hits it with probability sin²30° cos 20° = 0.23: 40000 rays resolve 4 %.
    const double exact = kAlbedo / kPi * irradiance * std::cos(rad(20.0));
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      CAPTURE(mode);
      check_estimate(receiver_scene(nullptr, json::array({distant(20.0, 60.0)}), mode, "bvh"), 1.0,
                     mode == "bsdf_only" ? 40000 : 4000, exact, 0.05);
    }
  }
}

TEST_CASE("emitter types: a constant environment over an open plane gives E = pi L") {
  const json sky = json::array({{{"type", "environment"}, {"radiance", kRadiance}}});
  for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
    CAPTURE(mode);
    // Light sampling draws the whole sphere (half of it below the plane): 1.3 relative deviation per ray.
    check_estimate(receiver_scene(nullptr, sky, mode, "bvh"), 1.0, mode == "nee_only" ? 40000 : 4000,
                   kAlbedo * kRadiance, 0.05);
  }
}

namespace {

// A closed 2 m × 1 m × 2 m room (black walls and ceiling) whose ceiling has a 1 m square opening above the origin:
// its shapes, and the opening's corners.
struct SkylightRoom {
  json shapes = json::array();
  std::vector<Vec3d> opening;
};
SkylightRoom skylight_room() {
  SkylightRoom room;
  const auto quad = [&](std::vector<Vec3d> v) {
    json vertices = json::array();
    for (const Vec3d& p : v) vertices.push_back({p.x, p.y, p.z});
    room.shapes.push_back({{"type", "quad"}, {"material", "black"}, {"vertices", vertices}});
  };
  const double H = 1.0, a = 0.5;
  quad({{-1, 0, -1}, {1, 0, -1}, {1, H, -1}, {-1, H, -1}});
  quad({{-1, 0, 1}, {1, 0, 1}, {1, H, 1}, {-1, H, 1}});
  quad({{-1, 0, -1}, {-1, 0, 1}, {-1, H, 1}, {-1, H, -1}});
  quad({{1, 0, -1}, {1, 0, 1}, {1, H, 1}, {1, H, -1}});
  quad({{-1, H, -1}, {1, H, -1}, {1, H, -a}, {-1, H, -a}});  // the ceiling around the opening
  quad({{-1, H, a}, {1, H, a}, {1, H, 1}, {-1, H, 1}});
  quad({{-1, H, -a}, {-a, H, -a}, {-a, H, a}, {-1, H, a}});
  quad({{a, H, -a}, {1, H, -a}, {1, H, a}, {a, H, a}});
  room.opening = {{-a, H, -a}, {a, H, -a}, {a, H, a}, {-a, H, a}};
  return room;
}

json portal_of(const std::vector<Vec3d>& corners) {
  json portal = json::array();
  for (const Vec3d& p : corners) portal.push_back({p.x, p.y, p.z});
  return json::array({portal});
}

}  // namespace

TEST_CASE("emitter types: a constant environment through a skylight, with and without a portal, gives L Phi(skylight)") {
  const SkylightRoom room = skylight_room();
  const double exact = kAlbedo / kPi * kRadiance * projected_solid_angle(room.opening, {0, 0, 0}, {0, 1, 0});
  for (const bool with_portal : {false, true})
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      CAPTURE(with_portal);
      CAPTURE(mode);
      json sky = {{"type", "environment"}, {"radiance", kRadiance}};
      if (with_portal) sky["portals"] = portal_of(room.opening);
      // Without a portal, light sampling spends most samples on the walls (3.8 relative deviation per ray for
      // nee_only, 1.7 for MIS); BSDF sampling passes the opening with probability Φ/π ≈ 0.24 either way.
      const int count = mode == "nee_only" && !with_portal ? 160000 : mode == "bsdf_only" || !with_portal ? 40000 : 8000;
      check_estimate(receiver_scene(room.shapes, json::array({sky}), mode, "bvh"), 1.0, count, exact, 0.05);
    }
}

TEST_CASE("emitter types: an environment image, open and through a skylight with and without a portal, is exact") {
  // A 16 × 8 equirectangular image (top row +y): grey 0.3 down to 112.5° from the zenith, 1.2 below, so importance
  // sampling by luminance sends most samples below the horizon, and the filtered lookup is 0.3 everywhere above it
  // (the rows blend only between 101° and 124°). Each lane's exact value is then ρ L_j over an open plane and
  // ρ/π L_j Φ(opening) in the room (the opening is within 35° of the zenith), L_j the image's radiance above the
  // horizon at lane j's wavelength.
  std::vector<float> pixels(16 * 8 * 3, 0.3f);
  for (size_t i = 5 * 16 * 3; i < pixels.size(); ++i) pixels[i] = 1.2f;
  const std::filesystem::path image = write_pfm("emitter_types_environment", 16, 8, pixels);
  const SkylightRoom room = skylight_room();
  const double phi = projected_solid_angle(room.opening, {0, 0, 0}, {0, 1, 0});
  for (const int setting : {0, 1, 2}) {  // open plane; room without a portal; room with one
    json sky = {{"type", "environment"}, {"image", image.string()}};
    if (setting == 2) sky["portals"] = portal_of(room.opening);
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      CAPTURE(setting);
      CAPTURE(mode);
      const auto scene = scene_from_json(receiver_scene(setting == 0 ? json() : room.shapes, json::array({sky}), mode, "bvh"));
      const SampledSpectrum above = scene->lights[0]->radiance_escaped({0, 1, 0}, fixed_wavelengths());
      std::array<double, 4> exact;
      for (int j = 0; j < 4; ++j) exact[size_t(j)] = kAlbedo * above[j] * (setting == 0 ? 1.0 : phi / kPi);
      // Light sampling without a portal in the room: 1 sample in ~10 passes the opening (5.7 relative deviation per
      // ray for nee_only).
      const int count = mode == "bsdf_only"                      ? (setting == 0 ? 4000 : 40000)
                        : setting == 2                           ? 8000
                        : setting == 1 && mode == "nee_only"     ? 400000
                                                                 : 160000;
      check_lanes_at(*scene, {0, 0, 0}, 0.01f, count, exact, 0.05);
    }
  }
  std::filesystem::remove(image);
}

TEST_CASE("emitter types: an emissive quad with an emission image, the three strategies give the exact irradiance") {
  // A 2 × 2 image, white top-left, black elsewhere, on a square of side D = 2a facing the plane from height `gap`,
  // u along +x and v along +z: the radiance is L_w · w(u) · w(1 − v), w(s) = 1 − clamp(2s − ½, 0, 1) (bilinear
  // between the pixel centres at ¼ and ¾, clamped beyond; v = 1 is the top row). A receiver under the bright corner
  // (−a/2, +a/2) at gaps of 0.01× to 100× D, and one under the opposite corner (+a/2, −a/2) at 0.25× and 1× D: there
  // the two differ 15.8× and 1.9×, so a lookup mirrored in u, in v or in both fails. The exact irradiance is the
  // midpoint rule on a 1000² grid over the square (cells of D/1000, a tenth of the smallest gap: relative error
  // < 1e-3 there, < 1e-5 from 0.25× D on).
  const double a = 0.1, size = 2 * a;
  const std::filesystem::path image = write_pfm("emitter_types_area_image", 2, 2, {1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  const auto w = [](double s) { return 1.0 - std::clamp(2.0 * s - 0.5, 0.0, 1.0); };
  std::vector<std::pair<double, double>> settings;  // (gap in sizes, receiver x; its z is −x)
  for (const double gap_in_sizes : kGapsInSizes) settings.emplace_back(gap_in_sizes, -0.5 * a);
  for (const double gap_in_sizes : {0.25, 1.0}) settings.emplace_back(gap_in_sizes, 0.5 * a);
  for (const auto& [gap_in_sizes, x] : settings) {
    const double gap = gap_in_sizes * size, z = -x;
    const json quad = {{"type", "quad"}, {"material", "black"},
                       {"vertices", {{-a, gap, -a}, {a, gap, -a}, {a, gap, a}, {-a, gap, a}}},  // normal −y
                       {"uvs", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}},
                       {"emission", {{"image", image.string()}}}};
    const int n = 1000;
    double phi = 0.0;  // ∫ w(u) w(1 − v) cos θ_r cos θ_l / d² dA
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) {
        const double u = (i + 0.5) / n, v = (k + 0.5) / n, px = -a + 2 * a * u, pz = -a + 2 * a * v;
        const double d2 = (px - x) * (px - x) + gap * gap + (pz - z) * (pz - z);
        phi += w(u) * w(1.0 - v) * gap * gap / (d2 * d2);
      }
    phi *= (2 * a / n) * (2 * a / n);
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      // BSDF sampling finds the far square with probability ~ its projected solid angle (check_over_gaps' rule).
      if (mode == "bsdf_only" && gap_in_sizes > 1.0) continue;
      CAPTURE(gap_in_sizes);
      CAPTURE(x);
      CAPTURE(mode);
      const auto scene = scene_from_json(receiver_scene(json::array({quad}), nullptr, mode, "bvh"));
      SurfaceHit white;  // a point of the image's top-left pixel: L_w per lane
      white.primitive = 1;
      white.uv = {0.1f, 0.9f};
      const SampledSpectrum l_white = scene->lights[0]->radiance(white, {0, -1, 0}, fixed_wavelengths());
      std::array<double, 4> exact;
      for (int j = 0; j < 4; ++j) exact[size_t(j)] = kAlbedo / kPi * l_white[j] * phi;
      // Rays for 5 SE ≤ 5 %, from the relative deviations per ray measured at the worst setting (the dark corner at
      // 0.25× D: nee_only 4.0, mis 1.3; bsdf_only 4.0 there at 1× D).
      const int count = mode == "mis" ? 24000 : 160000;
      check_lanes_at(*scene, {x, 0, z}, float(std::min(0.5 * gap, 0.01)), count, exact, 0.05);
    }
  }
  std::filesystem::remove(image);
}

TEST_CASE("emitter types: ies and goniometric lights (delta: BSDF sampling cannot hit them), NEE only and MIS give I cos theta / d^2") {
  namespace fs = std::filesystem;
  const fs::path folder = fs::temp_directory_path() / ("rimu-emitter-types-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  // An axially symmetric downlight: 1000 cd to 30°, linear to 0 at 60°; and a goniometric light of 1000 cd
  // everywhere (a uniform 16 × 16 image × candela_scale; its mapping is checked elsewhere, the transport here).
  std::ofstream(folder / "down.ies") << "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 4 1 1 2 0.1 0.1 0\n1.0 1.0 15\n"
                                        "0 30 60 90\n0\n1000 1000 0 0\n";
  const fs::path image = write_pfm("emitter_types_goniometric", 16, 16, std::vector<float>(16 * 16 * 3, 1.0f));
  const json ies = {{"type", "ies"}, {"file", "down.ies"}, {"position", {0.3, 1.0, 0}}, {"spectrum", 1.0}};
  const json goniometric = {{"type", "goniometric"}, {"image", image.string()}, {"position", {0.3, 1.0, 0}},
                            {"spectrum", 1.0}, {"candela_scale", 1000.0}};
  // 1000 cd towards the receiver (γ = 16.7° < 30° for the downlight) of a flat spectrum: I(λ) = 1000 / (K_m ∫V dλ)
  // W/(sr·nm).
  double v_integral = 0.0;
  for (double l = 360.0; l <= 830.0; l += 1.0) v_integral += library().photopic_v().value(l);
  const double intensity = 1000.0 / (683.0 * v_integral), d2 = 0.3 * 0.3 + 1.0;
  const double exact = kAlbedo / kPi * intensity * (1.0 / std::sqrt(d2)) / d2;
  for (const json& light : {ies, goniometric})
    for (const std::string mode : {"nee_only", "mis"}) {
      CAPTURE(light.dump());
      CAPTURE(mode);
      const auto scene = load_scene(receiver_scene(nullptr, json::array({light}), mode, "bvh"), "lights.json", folder, library());
      const auto lanes = lane_radiance(*scene, [](int) { return ray_between({0, 0.01f, 0}, {0, 0, 0}); }, 16);
      for (int j = 0; j < 4; ++j) {
        CAPTURE(j);
        CHECK(lanes[size_t(j)].mean == doctest::Approx(exact).epsilon(1e-5));  // float radiance
      }
    }
  fs::remove_all(folder);
  fs::remove(image);
}

TEST_CASE("emitter types: CIE skies calibrated by their horizontal illuminance, the three strategies give it") {
  // `diffuse_horizontal_illuminance_lx` is the sky's illuminance on an open horizontal plane (integrated at load to
  // 2.3e-6): with a flat spectrum, E(λ) = E_v / (K_m ∫V dλ) at every wavelength, so L_out = ρ/π · E(λ).
  const double illuminance_lx = 10000.0;
  double v_integral = 0.0;
  for (double l = 360.0; l <= 830.0; l += 1.0) v_integral += library().photopic_v().value(l);
  const double exact = kAlbedo / kPi * illuminance_lx / (683.0 * v_integral);
  for (const int sky_type : {1, 12}) {  // overcast; clear with its circumsolar peak (the sun 40° up)
    json sky = {{"type", "cie_sky"}, {"sky_type", sky_type}, {"diffuse_horizontal_illuminance_lx", illuminance_lx},
                {"spectrum", 1.0}};
    if (sky_type == 12) sky["sun_position"] = {{"azimuth_deg", 135.0}, {"elevation_deg", 40.0}};
    for (const std::string mode : {"nee_only", "mis", "bsdf_only"}) {
      CAPTURE(sky_type);
      CAPTURE(mode);
      check_estimate(receiver_scene(nullptr, json::array({sky}), mode, "bvh"), 1.0, 8000, exact, 0.05);
    }
  }
}
