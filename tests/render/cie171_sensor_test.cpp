// Lighting-simulation validation in the manner of CIE 171:2006, "Test cases to assess the accuracy of lighting
// computer programs" (section 5: its analytic cases): a rectangular Lambertian area source parallel and
// perpendicular to the receiving plane, and the closed room with interreflections (the integrating-sphere
// relation). The reference values are computed here from the geometry, not copied from the report's tables
// (docs/lighting-validation.md lists the cases, the references and Rimu's readings). Every check is
// |Rimu − reference| ≤ 4.5 standard errors of Rimu's own reading, with the standard error itself under 2 % (the
// report's accuracy target for these cases).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <string>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

#include "render/scene/scene.h"
#include "render/scene/scene_sensors.h"
#include "render/sensors/sensor_measurement.h"
#include "sensor_test_support.h"
#include "test_support.h"

using namespace rimu;
using nlohmann::json;

namespace cie171_sensor_test {

using rimu::test::kPi;

using Point = std::array<double, 3>;

Point minus(Point a, Point b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point cross(Point a, Point b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(Point a, Point b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point normalized(Point a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}

// The configuration factor from a plane element at p (unit normal n) to a planar polygon wholly on its front side,
// by Lambert's contour formula: F = (1/2π) |Σᵢ γᵢ n·ĝᵢ|, γᵢ the angle edge i subtends at p and ĝᵢ the unit normal of
// the plane through p and that edge (Howell, "A Catalog of Radiation Heat Transfer Configuration Factors",
// the polygon factors of its section B).
double polygon_factor(Point p, Point n, const std::vector<Point>& polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Point a = normalized(minus(polygon[i], p)), b = normalized(minus(polygon[(i + 1) % polygon.size()], p));
    const Point c = cross(a, b);
    const double s = std::sqrt(dot(c, c));
    if (s == 0.0) continue;
    sum += std::atan2(s, dot(a, b)) * dot(n, c) / s;
  }
  return std::abs(sum) / (2.0 * kPi);
}

// Howell's closed form for a plane element under one corner of a parallel a × b rectangle at distance c.
double parallel_corner_factor(double a, double b, double c) {
  const double x = a / c, y = b / c, sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * kPi);
}

// The part of convex polygon `subject` inside convex polygon `clip` (both in the same plane, `normal` its normal, either
// winding): Sutherland–Hodgman clipping against each of clip's edges.
std::vector<Point> clip_convex(std::vector<Point> subject, const std::vector<Point>& clip, Point normal) {
  // Orient clip so that "inside" is to the left of each edge seen along `normal`.
  std::vector<Point> c = clip;
  if (dot(cross(minus(c[1], c[0]), minus(c[2], c[1])), normal) < 0) std::reverse(c.begin(), c.end());
  for (size_t e = 0; e < c.size() && !subject.empty(); ++e) {
    const Point a = c[e], b = c[(e + 1) % c.size()];
    const auto side = [&](Point p) { return dot(cross(minus(b, a), minus(p, a)), normal); };
    std::vector<Point> out;
    for (size_t i = 0; i < subject.size(); ++i) {
      const Point p = subject[i], q = subject[(i + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) out.push_back(p);
      if ((sp >= 0) != (sq >= 0)) {
        const double t = sp / (sp - sq);
        out.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])});
      }
    }
    subject = std::move(out);
  }
  return subject;
}

json base_scene(json shapes, json lights, json sensors, int max_depth = 16) {
  return json{{"camera", {{"from", {0, -5, 1}}, {"to", {0, 0, 0}}, {"up", {0, 0, 1}}}},
              {"integrator", {{"max_depth", max_depth}}},
              {"materials", {{"black", {{"type", "diffuse"}, {"reflectance", 0.0}}},
                             {"wall50", {{"type", "diffuse"}, {"reflectance", 0.5}}},
                             {"wall80", {{"type", "diffuse"}, {"reflectance", 0.8}}}}},
              {"lights", std::move(lights)},
              {"shapes", std::move(shapes)},
              {"sensors", std::move(sensors)}};
}

json upward_meter(Point p) {
  return {{"type", "illuminance"}, {"position", p}, {"normal", {0, 0, 1}}};
}

SensorReadings measure(const json& document) { return test::measure(test::load_sensors(document, "cie171.json"), 17); }

void check_case(const char* name, const MeterReading& r, double reference) {
  MESSAGE(std::string(name) << ": reference " << reference << " lx, Rimu " << r.value << " lx, standard error " << r.standard_error
               << " lx, difference " << 100.0 * (r.value - reference) / reference << " %");
  CHECK(r.standard_error < 0.02 * reference);
  CHECK(std::abs(r.value - reference) <= test::kSensorSigmas * r.standard_error);
}

TEST_CASE("CIE 171 area source: the polygon factor equals Howell's corner factor for a parallel rectangle") {
  const double a = 2.0, b = 1.0, c = 2.0;
  const std::vector<Point> rectangle = {{0, 0, c}, {0, b, c}, {a, b, c}, {a, 0, c}};
  CHECK(polygon_factor({0, 0, 0}, {0, 0, 1}, rectangle) == doctest::Approx(parallel_corner_factor(a, b, c)).epsilon(1e-12));
  // Four corner rectangles around a point under the centre add up to the whole rectangle's factor.
  const double centre = 4.0 * parallel_corner_factor(a / 2, b / 2, c);
  CHECK(polygon_factor({a / 2, b / 2, 0}, {0, 0, 1}, rectangle) == doctest::Approx(centre).epsilon(1e-12));
}

TEST_CASE("CIE 171 area source: a Lambertian rectangle parallel to the receiving plane gives E = π L F") {
  // A 2 m × 1 m panel of luminance 1000 nt facing down from 2 m; meters on the floor below a corner, below the
  // centre, beside the panel and far off to one side.
  const double luminance = 1000.0, height = 2.0;
  const std::vector<Point> panel = {{0, 0, height}, {0, 1, height}, {2, 1, height}, {2, 0, height}};
  json vertices = json::array();
  for (const Point& p : panel) vertices.push_back(p);
  const std::vector<Point> meters = {{0, 0, 0}, {1, 0.5, 0}, {3, 0.5, 0}, {-2, 2, 0}};
  json sensor_list = json::array();
  for (const Point& p : meters) sensor_list.push_back(upward_meter(p));
  const SensorReadings readings = measure(base_scene(
      json::array({{{"type", "quad"}, {"vertices", vertices}, {"material", "black"},
                    {"emission", {{"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", luminance}}}}}),
      json::array(), {{"samples", 2048}, {"meters", sensor_list}}));
  const char* names[] = {"parallel, below a corner", "parallel, below the centre", "parallel, beside",
                         "parallel, far off"};
  for (size_t i = 0; i < meters.size(); ++i)
    check_case(names[i], readings.meters[i], kPi * luminance * polygon_factor(meters[i], {0, 0, 1}, panel));
}

TEST_CASE("CIE 171 area source: a Lambertian rectangle perpendicular to the receiving plane gives E = π L F") {
  // A 1 m × 1 m wall panel of 1000 nt standing on the floor in the plane x = 2, facing −x; floor meters in front
  // of it at several distances and off its axis.
  const double luminance = 1000.0;
  const std::vector<Point> panel = {{2, -0.5, 0}, {2, -0.5, 1}, {2, 0.5, 1}, {2, 0.5, 0}};
  json vertices = json::array();
  for (const Point& p : panel) vertices.push_back(p);
  const std::vector<Point> meters = {{1.5, 0, 0}, {1, 0, 0}, {0, 0, 0}, {1, 1, 0}};
  json sensor_list = json::array();
  for (const Point& p : meters) sensor_list.push_back(upward_meter(p));
  const SensorReadings readings = measure(base_scene(
      json::array({{{"type", "quad"}, {"vertices", vertices}, {"material", "black"},
                    {"emission", {{"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", luminance}}}}}),
      json::array(), {{"samples", 2048}, {"meters", sensor_list}}));
  const char* names[] = {"perpendicular, 0.5 m", "perpendicular, 1 m", "perpendicular, 2 m",
                         "perpendicular, 1 m off axis"};
  for (size_t i = 0; i < meters.size(); ++i)
    check_case(names[i], readings.meters[i], kPi * luminance * polygon_factor(meters[i], {0, 0, 1}, panel));
}

TEST_CASE("CIE 171 closed room: the integrating-sphere relation E_r = Φ ρ / (A (1 − ρ))") {
  // A Lambertian sphere of radius 1 m (A = 4π m²) and reflectance ρ around an isotropic 1000 lm lamp at its centre:
  // every wall point receives Φ/(A(1 − ρ)) in all, so the wall's radiance is uniform and any receptor inside sees the
  // interreflected illuminance ρ Φ / (A (1 − ρ)) from its whole hemisphere, plus the lamp's Φ/(4π r²) if it faces it.
  // max_depth is raised so that truncation (ρ^depth of the flux) is far below the standard error.
  const double flux = 1000.0, radius = 1.0, area = 4.0 * kPi * radius * radius;
  for (double rho : {0.5, 0.8}) {
    CAPTURE(rho);
    const json meters = json::array({{{"name", "facing_lamp"}, {"type", "illuminance"}, {"position", {0, 0, -0.9}}, {"normal", {0, 0, 1}}},
                                     {{"name", "facing_wall"}, {"type", "illuminance"}, {"position", {0, 0, -0.9}}, {"normal", {0, 0, -1}}},
                                     {{"name", "sideways"}, {"type", "illuminance"}, {"position", {0.5, 0.2, 0.1}}, {"normal", {0, 1, 0}}}});
    const SensorReadings readings = measure(base_scene(
        json::array({{{"type", "sphere"}, {"center", {0, 0, 0}}, {"radius", radius}, {"material", rho == 0.5 ? "wall50" : "wall80"}}}),
        json::array({{{"type", "point"}, {"position", {0, 0, 0}}, {"spectrum", {{"illuminant", "D65"}}}, {"luminous_power_lm", flux}}}),
        {{"samples", 4096}, {"meters", meters}}, 400));
    const double interreflected = flux * rho / (area * (1.0 - rho));
    const double direct_at_09 = flux / (4.0 * kPi * 0.81);
    check_case(rho == 0.5 ? "sphere ρ 0.5, facing the lamp" : "sphere ρ 0.8, facing the lamp", readings.meters[0],
               interreflected + direct_at_09);
    check_case(rho == 0.5 ? "sphere ρ 0.5, facing the wall" : "sphere ρ 0.8, facing the wall", readings.meters[1],
               interreflected);
    // Sideways at (0.5, 0.2, 0.1) facing +y: the lamp (at the origin, along −p) is behind the receptor.
    check_case(rho == 0.5 ? "sphere ρ 0.5, sideways" : "sphere ρ 0.8, sideways", readings.meters[2], interreflected);
  }
}

TEST_CASE("CIE 171 internal obstruction: a plate between an area source and the floor hides its shadow's part of the source") {
  // The parallel 2 m × 1 m panel of 1000 nt at 3 m, and a black 0.6 m × 0.6 m plate at 1.5 m under its middle. From a
  // floor point p the plate hides the part of the panel inside the plate's central projection from p onto the
  // panel's plane, so E = π L (F(panel) − F(panel ∩ projected plate)): configuration factors add over disjoint parts
  // of one plane, and the intersection of the two convex polygons is found by clipping. Meters: under the plate's
  // centre (the plate's shadow covers part of the panel), under a panel corner, beside, and far enough off that the
  // plate hides nothing.
  const double luminance = 1000.0, height = 3.0, plate_height = 1.5;
  const std::vector<Point> panel = {{0, 0, height}, {0, 1, height}, {2, 1, height}, {2, 0, height}};
  const std::vector<Point> plate = {{0.7, 0.2, plate_height}, {1.3, 0.2, plate_height}, {1.3, 0.8, plate_height},
                                    {0.7, 0.8, plate_height}};
  json panel_vertices = json::array(), plate_vertices = json::array();
  for (const Point& p : panel) panel_vertices.push_back(p);
  for (const Point& p : plate) plate_vertices.push_back(p);
  const std::vector<Point> meters = {{1, 0.5, 0}, {0.3, 0.1, 0}, {2.2, 0.5, 0}, {-1.5, 3.0, 0}};
  json sensor_list = json::array();
  for (const Point& p : meters) sensor_list.push_back(upward_meter(p));
  const SensorReadings readings = measure(base_scene(
      json::array({{{"type", "quad"}, {"vertices", panel_vertices}, {"material", "black"},
                    {"emission", {{"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", luminance}}}},
                   {{"type", "quad"}, {"vertices", plate_vertices}, {"material", "black"}}}),
      json::array(), {{"samples", 4096}, {"meters", sensor_list}}));
  const char* names[] = {"obstruction, under the plate", "obstruction, under a corner", "obstruction, beside",
                         "obstruction, far off (nothing hidden)"};
  for (size_t i = 0; i < meters.size(); ++i) {
    const Point p = meters[i];
    std::vector<Point> shadow;
    for (const Point& q : plate) {
      const double t = (height - p[2]) / (q[2] - p[2]);
      shadow.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), height});
    }
    const std::vector<Point> hidden = clip_convex(shadow, panel, {0, 0, 1});
    const double visible_factor =
        polygon_factor(p, {0, 0, 1}, panel) - (hidden.size() >= 3 ? polygon_factor(p, {0, 0, 1}, hidden) : 0.0);
    if (i == 0) CHECK(hidden.size() >= 3);  // the case is one: the plate hides part of the panel
    if (i == 3) CHECK(hidden.size() < 3);
    check_case(names[i], readings.meters[i], kPi * luminance * visible_factor);
  }
}

TEST_CASE("Sensor standard errors are honest: a grid's errors over their standard errors have a t distribution's spread") {
  // The parallel panel (2 m × 1 m, 1000 nt, 2 m up) over a 20 × 10 floor grid reaching well beyond it: 200 readings
  // with exact references. A reading's standard error comes from the spread of its R = 16 independent replicates'
  // means (replicates_for), so z = (reading − reference)/SE has a Student t distribution of R − 1 = 15 degrees of
  // freedom if the replicate means are near normal: E[z²] = ν/(ν − 2) = 1.154, Var[z²] = 3ν²/((ν − 2)(ν − 4)) −
  // E[z²]² = 3.39, so the mean of 200 z² has standard deviation 0.13. The textbook s/√n of a Sobol' sequence's
  // samples, which this replaced, gave a mean z² under 0.1 (its errors 3–8× too large); errors too small would give
  // one far above. The bounds are E[z²] ± 4 standard deviations of the mean.
  const double luminance = 1000.0, height = 2.0;
  const std::vector<Point> panel = {{0, 0, height}, {0, 1, height}, {2, 1, height}, {2, 0, height}};
  json vertices = json::array();
  for (const Point& p : panel) vertices.push_back(p);
  const int nu = 20, nv = 10;
  const double x0 = -1.0, y0 = -1.5, size_u = 4.0, size_v = 4.0;
  const json grid = {{"origin", {x0, y0, 0}}, {"u", {1, 0, 0}}, {"v", {0, 1, 0}}, {"size", {size_u, size_v}}, {"counts", {nu, nv}}};
  const SensorReadings readings = measure(base_scene(
      json::array({{{"type", "quad"}, {"vertices", vertices}, {"material", "black"},
                    {"emission", {{"spectrum", {{"illuminant", "D65"}}}, {"luminance_nt", luminance}}}}}),
      json::array(), {{"samples", 256}, {"grids", json::array({grid})}}));
  REQUIRE(readings.grids.size() == 1);
  REQUIRE(readings.grids[0].points.size() == size_t(nu * nv));
  CHECK(replicates_for(256) == 16);
  double sum_z2 = 0.0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const Point p = {x0 + (i + 0.5) * size_u / nu, y0 + (j + 0.5) * size_v / nv, 0.0};
      const MeterReading& r = readings.grids[0].points[size_t(j * nu + i)];
      const double reference = kPi * luminance * polygon_factor(p, {0, 0, 1}, panel);
      REQUIRE(r.standard_error > 0.0);
      const double z = (r.value - reference) / r.standard_error;
      sum_z2 += z * z;
    }
  const double mean_z2 = sum_z2 / (nu * nv);
  MESSAGE("mean z² over " << nu * nv << " grid points: " << mean_z2 << " (t distribution of 15 degrees of freedom: 1.154)");
  CHECK(mean_z2 > 1.154 - 4 * 0.13);
  CHECK(mean_z2 < 1.154 + 4 * 0.13);
}

}  // namespace cie171_sensor_test
