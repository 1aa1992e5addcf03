// Cylinder, disk, partial sphere and box meshes (render/scene/analytic_shapes.h) against pbrt-v4's definitions
// (pbrt-v4 book, "Shapes": areas r·φmax·(zmax − zmin), φmax/2·(r² − ri²), r·φmax·(zmax − zmin); u = φ/φmax; v of
// each shape; normals ∂p/∂u × ∂p/∂v), the stated error bounds, an emissive disk's power and irradiance, and the
// JSON shapes "box", "cylinder", "disk".
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "integration_support.h"
#include "pbrt_test_support.h"
#include "render/scene/analytic_shapes.h"
#include "render/scene/scene.h"
#include "test_support.h"
#include "transport/light_test_support.h"
#include "transport/lights/area_light.h"

using namespace rimu;
using nlohmann::json;

namespace {

using rimu::test::kPi;
// The bounds analytic_shapes.h states: area short by < 1e-3, every point within 1.1e-3 of the radius (5.4e-4 for a
// circle's chord).
constexpr double kAreaBound = 1e-3;

double mesh_area(const TriangleMesh& mesh) {
  double area = 0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const Vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]], c = mesh.positions[mesh.indices[t + 2]];
    area += 0.5 * double(length(cross(b - a, c - a)));
  }
  return area;
}

// Every triangle's winding agrees with its vertices' shading normals (the front is where the normals point).
void check_winding_follows_normals(const TriangleMesh& mesh) {
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const uint32_t i = mesh.indices[t], j = mesh.indices[t + 1], k = mesh.indices[t + 2];
    const Vec3 g = cross(mesh.positions[j] - mesh.positions[i], mesh.positions[k] - mesh.positions[i]);
    CHECK(dot(g, mesh.normals[i] + mesh.normals[j] + mesh.normals[k]) > 0.0f);
  }
}

// φ of a point in [0, 2π), taken as 2π at u = 1 (the repeated seam column).
double phi_of(const Vec3& p, double u) {
  double phi = std::atan2(double(p.y), double(p.x));
  if (phi < 0) phi += 2 * kPi;
  if (u > 0.5 && phi < 1e-4) phi = 2 * kPi;
  return phi;
}

std::unique_ptr<Scene> load_json(const json& shapes) {
  const json d = {{"camera", {{"from", {0, 0, 10}}, {"to", {0, 0, 0}}, {"up", {0, 1, 0}}, {"vertical_fov_deg", 30}}},
                  {"film", {{"resolution", {8, 8}}}},
                  {"integrator", {{"spp", 1}}},
                  {"materials", {{"m", {{"type", "diffuse"}, {"reflectance", 0.5}}}}},
                  {"shapes", shapes}};
  return load_scene(d, "shapes.json", test::test_data(""), test::library());
}

std::string load_error(const json& shapes) {
  try {
    load_json(shapes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::optional<float> hit_distance(const Scene& scene, Vec3 origin, Vec3 direction) {
  const auto hit = scene.geometry.intersect(test::ray_between(origin, origin + direction));
  return hit ? std::optional<float>(hit->t) : std::nullopt;
}

}  // namespace

TEST_CASE("cylinder mesh: pbrt's area, outward normals, u = φ/φmax, v = (z − zmin)/(zmax − zmin)") {
  for (const double phimax_deg : {360.0, 270.0, 10.0}) {
    CAPTURE(phimax_deg);
    const double r = 0.3, zmin = -0.5, zmax = 1.5, phimax = phimax_deg * kPi / 180;
    const TriangleMesh mesh = cylinder_mesh(r, zmin, zmax, phimax).to_triangle_mesh();
    const double exact = r * phimax * (zmax - zmin);
    CHECK(mesh_area(mesh) <= exact);
    CHECK(mesh_area(mesh) >= exact * (1 - kAreaBound));
    check_winding_follows_normals(mesh);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3 p = mesh.positions[i], n = mesh.normals[i];
      const Vec2 uv = mesh.uvs[i];
      CHECK(std::hypot(p.x, p.y) == doctest::Approx(r).epsilon(1e-6));
      // ∂p/∂u × ∂p/∂v = (φmax x, φmax y, 0)(zmax − zmin): away from the axis.
      CHECK(n.x == doctest::Approx(p.x / r).epsilon(1e-5));
      CHECK(n.y == doctest::Approx(p.y / r).epsilon(1e-5));
      CHECK(n.z == 0.0f);
      CHECK(uv.x == doctest::Approx(phi_of(p, uv.x) / phimax).epsilon(1e-5));
      CHECK(uv.y == doctest::Approx((p.z - zmin) / (zmax - zmin)).epsilon(1e-6));
    }
  }
  // The stated silhouette bound: a chord's midpoint sags by 1 − cos(Δ/2) with Δ ≤ 2π/96.
  const TriangleMesh mesh = cylinder_mesh(1.0, 0.0, 1.0, 2 * kPi).to_triangle_mesh();
  const Vec3 mid = 0.5f * (mesh.positions[0] + mesh.positions[2]);
  CHECK(1.0 - std::hypot(mid.x, mid.y) == doctest::Approx(1 - std::cos(kPi / 96)).epsilon(1e-3));
  CHECK(1.0 - std::hypot(mid.x, mid.y) < 5.4e-4);
}

TEST_CASE("disk mesh: pbrt's annulus area, normal +z, u = φ/φmax, v = (r − |p|)/(r − ri)") {
  for (const auto& [inner, phimax_deg] : {std::pair{0.0, 360.0}, std::pair{0.4, 360.0}, std::pair{0.25, 90.0}}) {
    CAPTURE(inner);
    CAPTURE(phimax_deg);
    const double r = 1.2, height = 0.7, phimax = phimax_deg * kPi / 180;
    const TriangleMesh mesh = disk_mesh(height, r, inner, phimax).to_triangle_mesh();
    const double exact = 0.5 * phimax * (r * r - inner * inner);
    CHECK(mesh_area(mesh) <= exact);
    CHECK(mesh_area(mesh) >= exact * (1 - kAreaBound));
    check_winding_follows_normals(mesh);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3 p = mesh.positions[i];
      const Vec2 uv = mesh.uvs[i];
      CHECK(p.z == doctest::Approx(height));
      CHECK(mesh.normals[i] == Vec3{0, 0, 1});
      const double radius = std::hypot(p.x, p.y);
      CHECK(uv.y == doctest::Approx((r - radius) / (r - inner)).epsilon(1e-5));
      if (radius > 0) CHECK(uv.x == doctest::Approx(phi_of(p, uv.x) / phimax).epsilon(1e-5));
    }
  }
}

TEST_CASE("sphere mesh: pbrt's partial-sphere area, outward normals, u = φ/φmax, v from θ(zmin) to θ(zmax)") {
  struct Case {
    double zmin, zmax, phimax_deg;
  };
  for (const Case c : {Case{-2, 2, 360}, Case{-0.5, 1.2, 360}, Case{-2, 0.3, 200}, Case{0.1, 0.9, 45}}) {
    CAPTURE(c.zmin);
    CAPTURE(c.zmax);
    CAPTURE(c.phimax_deg);
    const double r = 2.0, phimax = c.phimax_deg * kPi / 180;
    const TriangleMesh mesh = sphere_mesh(r, c.zmin, c.zmax, phimax).to_triangle_mesh();
    const double zmin = std::max(c.zmin, -r), zmax = std::min(c.zmax, r);
    const double exact = r * phimax * (zmax - zmin);
    CHECK(mesh_area(mesh) <= exact);
    CHECK(mesh_area(mesh) >= exact * (1 - kAreaBound));
    check_winding_follows_normals(mesh);
    const double theta_zmin = std::acos(zmin / r), theta_zmax = std::acos(zmax / r);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const Vec3 p = mesh.positions[i], n = mesh.normals[i];
      const Vec2 uv = mesh.uvs[i];
      CHECK(length(p) == doctest::Approx(r).epsilon(1e-6));
      CHECK(p.z >= zmin - 1e-5);
      CHECK(p.z <= zmax + 1e-5);
      CHECK(dot(n, p / r) == doctest::Approx(1.0).epsilon(1e-5));
      const double theta = std::acos(std::clamp(double(p.z) / r, -1.0, 1.0));
      CHECK(uv.y == doctest::Approx((theta - theta_zmin) / (theta_zmax - theta_zmin)).epsilon(1e-5));
      if (std::hypot(p.x, p.y) > 1e-4 * r) CHECK(uv.x == doctest::Approx(phi_of(p, uv.x) / phimax).epsilon(1e-4));
    }
    // The stated surface bound: every triangle's centroid within 1.1e-3 of the radius.
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      const Vec3 centroid =
          (mesh.positions[mesh.indices[t]] + mesh.positions[mesh.indices[t + 1]] + mesh.positions[mesh.indices[t + 2]]) / 3.0f;
      CHECK(length(centroid) >= r * (1 - 1.1e-3));
    }
  }
}

TEST_CASE("box mesh: six faces, area, outward normals, uv across each face with u × v the normal") {
  const Vec3 lo{-1, 0, 2}, hi{1, 0.5, 5};
  const TriangleMesh mesh = box_mesh(lo, hi).to_triangle_mesh();
  CHECK(mesh.triangle_count() == 12);
  CHECK(mesh_area(mesh) == doctest::Approx(2 * (2 * 0.5 + 2 * 3 + 0.5 * 3)).epsilon(1e-6));
  check_winding_follows_normals(mesh);
  const Vec3 centre = 0.5f * (lo + hi);
  for (size_t f = 0; f < 6; ++f) {
    const size_t a = 4 * f;
    const Vec3 n = mesh.normals[a];
    CHECK(dot(n, mesh.positions[a] - centre) > 0.0f);
    // Vertices (0,0), (1,0), (1,1), (0,1): ∂p/∂u × ∂p/∂v along the outward normal.
    const Vec3 dpdu = mesh.positions[a + 1] - mesh.positions[a], dpdv = mesh.positions[a + 3] - mesh.positions[a];
    CHECK(dot(normalize(cross(dpdu, dpdv)), n) == doctest::Approx(1.0));
    CHECK(mesh.uvs[a + 2].x == 1.0f);
    CHECK(mesh.uvs[a + 2].y == 1.0f);
  }
}

TEST_CASE("an emissive disk: power π·L·A and on-axis irradiance π·L·R²/(h² + R²) within the tessellation bound") {
  const double radius = 0.5, radiance = 2.0, h = 0.8;
  AnalyticMesh disk = disk_mesh(h, radius, 0.0, 2 * kPi);
  flip_mesh(disk);  // facing down, towards the origin
  const TriangleMesh mesh = disk.to_triangle_mesh();
  const AreaLight light(mesh.positions, mesh.indices, LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), radiance), false);
  // Power per side π·A·∫L dλ (a constant over 360-830 nm: 470 nm); the mesh is short by the stated area bound.
  const double exact_power = kPi * (kPi * radius * radius) * radiance * 470.0;
  CHECK(light.total_power_w(0) <= exact_power);
  CHECK(light.total_power_w(0) >= exact_power * (1 - kAreaBound));
  // Irradiance at the origin by light sampling: the view factor of a coaxial disk (Howell's catalogue).
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f / 470.0f));
  const LightReference ref{{0, 0, 0}, {0, 0, 1}};
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  test::MeanEstimate e;
  for (int i = 0; i < 40000; ++i) {
    const auto s = light.sample_li(ref, lambda, {u01(rng), u01(rng)});
    e.add(s ? s->radiance[0] * std::max(0.0f, dot(s->wi, ref.normal)) / s->pdf_solid_angle : 0.0);
  }
  const double exact = kPi * radiance * radius * radius / (h * h + radius * radius);
  CAPTURE(e.mean());
  CAPTURE(e.standard_error());
  CHECK(std::abs(e.mean() - exact) <= test::kMonteCarloSigmas * e.standard_error() + kAreaBound * exact);
}

TEST_CASE("JSON box, cylinder and disk shapes: placed by their transform, closed by caps, refused when malformed") {
  const json shapes = json::array(
      {{{"type", "box"}, {"min", {-1, -1, -1}}, {"max", {1, 1, 0}}, {"material", "m"}, {"transform", {{{"translate", {0, 0, -5}}}}}},
       {{"type", "cylinder"}, {"radius", 0.5}, {"zmin", 0}, {"zmax", 2}, {"caps", true}, {"material", "m"},
        {"transform", {{{"translate", {5, 0, 0}}}}}},
       {{"type", "disk"}, {"radius", 1}, {"inner_radius", 0.5}, {"height", 1}, {"phimax_deg", 180}, {"material", "m"},
        {"transform", {{{"translate", {-5, 0, 0}}}}}}});
  const auto scene = load_json(shapes);
  // The box's top face at z = −5, straight below.
  CHECK(hit_distance(*scene, {0, 0, 1}, {0, 0, -1}) == doctest::Approx(6.0));
  // The cylinder's top cap at z = 2 on its axis; its side from +x at x = 5.5.
  CHECK(hit_distance(*scene, {5, 0, 10}, {0, 0, -1}) == doctest::Approx(8.0));
  CHECK(hit_distance(*scene, {10, 0, 1}, {-1, 0, 0}) == doctest::Approx(4.5).epsilon(1e-3));
  // The half annulus (φ in [0, π]): y > 0 between the radii is hit, the hole and y < 0 are not.
  CHECK(hit_distance(*scene, {-5, 0.75, 10}, {0, 0, -1}) == doctest::Approx(9.0));
  CHECK_FALSE(hit_distance(*scene, {-5, 0.2, 10}, {0, 0, -1}));
  CHECK_FALSE(hit_distance(*scene, {-5, -0.75, 10}, {0, 0, -1}));

  const auto one = [](json shape) {
    shape["material"] = "m";
    return json::array({shape});
  };
  CHECK_CONTAINS(load_error(one({{"type", "cylinder"}, {"radius", 1}, {"zmin", 1}, {"zmax", 1}})), "/shapes/0/zmax",
                 "zmax must exceed zmin (the cylinder has a length)");
  CHECK_CONTAINS(load_error(one({{"type", "disk"}, {"radius", 1}, {"inner_radius", 1}})), "/shapes/0/inner_radius",
                 "inner_radius must be smaller than radius");
  CHECK_CONTAINS(load_error(one({{"type", "disk"}, {"radius", 1}, {"phimax_deg", 0}})), "/shapes/0/phimax_deg",
                 "the swept angle must be > 0 degrees (at most 360)");
  CHECK_CONTAINS(load_error(one({{"type", "box"}, {"min", {0, 0, 0}}, {"max", {1, 0, 1}}})), "/shapes/0/max",
                 "every coordinate of max must exceed min's (a box has volume)");
  CHECK_CONTAINS(load_error(one({{"type", "box"}, {"min", {0, 0, 0}}, {"max", {1, 1, 1}}, {"radius", 1}})), "radius");
  CHECK_CONTAINS(load_error(one({{"type", "cylinder"}, {"radius", -1}, {"zmin", 0}, {"zmax", 1}})), "/shapes/0/radius");
}

TEST_CASE("JSON emissive disk and cylinder are area lights with their mesh's area") {
  const json shapes = json::array({{{"type", "disk"}, {"radius", 0.5}, {"material", "m"}, {"emission", 1.0}},
                                   {{"type", "cylinder"}, {"radius", 0.1}, {"zmin", 1}, {"zmax", 3}, {"material", "m"},
                                    {"emission", 1.0}}});
  const auto scene = load_json(shapes);
  REQUIRE(scene->lights.size() == 2);
  const auto& disk = dynamic_cast<const AreaLight&>(*scene->lights[0]);
  const auto& tube = dynamic_cast<const AreaLight&>(*scene->lights[1]);
  CHECK(disk.area_m2() <= kPi * 0.25);
  CHECK(disk.area_m2() >= kPi * 0.25 * (1 - kAreaBound));
  CHECK(tube.area_m2() <= 2 * kPi * 0.1 * 2);
  CHECK(tube.area_m2() >= 2 * kPi * 0.1 * 2 * (1 - kAreaBound));
}
