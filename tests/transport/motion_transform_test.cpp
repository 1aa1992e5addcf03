// MotionTransform: pbrt-v4's interpolation of a moving placement (translation and stretch linear, rotation by slerp
// along the shorter arc), its ends exact, and the linear keys Embree interpolates between.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "spectral/math_constants.h"
#include "transport/geometry/motion_transform.h"

using namespace rimu;

namespace {

constexpr double kKeyAngle = 2.0 * kPi / 180.0;  // the renderer's (EmbreeScene::kMotionKeyAngle)

// |a − b| ≤ tolerance for every entry.
bool rows_near(const Transform& a, const Transform& b, float tolerance) {
  for (int k = 0; k < 12; ++k)
    if (!(std::fabs(a.rows()[size_t(k)] - b.rows()[size_t(k)]) <= tolerance)) return false;
  return true;
}

MotionTransform motion(const Transform& start, const Transform& end) {
  bool valid = false;
  MotionTransform m(start, end, valid);
  REQUIRE(valid);
  return m;
}

}  // namespace

TEST_CASE("motion: the ends are the given transforms exactly, times outside [0, 1] clamp") {
  const Transform start = Transform::translate({1, 2, 3}) * Transform::rotate(30, {1, 1, 0}) * Transform::scale({2, 1, 0.5f});
  const Transform end = Transform::translate({-4, 0, 1}) * Transform::rotate(-70, {0, 0, 1});
  const MotionTransform m = motion(start, end);
  CHECK(m.at(0.0f).rows() == start.rows());
  CHECK(m.at(1.0f).rows() == end.rows());
  CHECK(m.at(-3.0f).rows() == start.rows());
  CHECK(m.at(7.0f).rows() == end.rows());
  CHECK(m.at(std::nanf("")).rows() == start.rows());
}

TEST_CASE("motion: the decomposition puts a transform back together (rotation, non-uniform scale, shear, mirror)") {
  bool ok = false;
  const Transform shear = Transform::from_rows({1, 0.4f, 0, 0, 0, 1, 0.2f, 0, 0, 0, 1, 0}, ok);
  REQUIRE(ok);
  for (const Transform& m : {Transform::rotate(123, {0.3f, -1, 0.5f}) * Transform::scale({3, 0.2f, 1.5f}),
                             Transform::scale({3, 0.2f, 1.5f}) * Transform::rotate(40, {1, 0, 0}),
                             Transform::translate({5, -6, 7}) * shear * Transform::rotate(200, {0, 1, 0}),
                             Transform::scale({-1, 1, 1}) * Transform::rotate(10, {0, 0, 1}),
                             Transform::rotate(180, {0, 0, 1})}) {
    const TransformComponents c = decompose(m);
    // The stretch is symmetric and the rotation a unit quaternion.
    CHECK(c.stretch[1] == doctest::Approx(c.stretch[3]));
    CHECK(c.stretch[2] == doctest::Approx(c.stretch[6]));
    CHECK(c.stretch[5] == doctest::Approx(c.stretch[7]));
    const auto& q = c.rotation;
    CHECK(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] == doctest::Approx(1.0).epsilon(1e-12));
    // A motion that starts and ends at m is m throughout: at() rebuilds it from the components.
    const MotionTransform still = motion(m, m);
    CHECK(still.rotation_angle() == doctest::Approx(0.0).scale(1).epsilon(1e-6));
    CHECK(rows_near(still.at(0.5f), m, 2e-6f));
  }
}

TEST_CASE("motion: translation and scale move linearly, one segment suffices without rotation") {
  const Transform start = Transform::translate({0, 0, 0}) * Transform::scale({1, 2, 1});
  const Transform end = Transform::translate({4, -2, 8}) * Transform::scale({3, 2, 1});
  const MotionTransform m = motion(start, end);
  CHECK(m.rotation_angle() == doctest::Approx(0.0).scale(1).epsilon(1e-7));
  const Transform half = m.at(0.25f);
  CHECK(rows_near(half, Transform::translate({1, -0.5f, 2}) * Transform::scale({1.5f, 2, 1}), 1e-6f));
  const auto keys = m.linear_keys(kKeyAngle);
  CHECK(keys.size() == 2);
  for (float t : {0.1f, 0.5f, 0.9f}) CHECK(rows_near(interpolate_keys(keys, t), m.at(t), 2e-6f));
}

TEST_CASE("motion: a rotation turns along the arc, keeping lengths (where interpolating matrices would shrink)") {
  // A quarter turn about z with a uniform scale 2: half-way, a 45° turn at scale 2. The matrices' average would
  // scale the x-axis to length 2·cos 45° = 1.41.
  const MotionTransform m = motion(Transform::scale({2, 2, 2}), Transform::rotate(90, {0, 0, 1}) * Transform::scale({2, 2, 2}));
  CHECK(m.rotation_angle() == doctest::Approx(kPi / 2).epsilon(1e-6));
  CHECK(rows_near(m.at(0.5f), Transform::rotate(45, {0, 0, 1}) * Transform::scale({2, 2, 2}), 2e-6f));
  CHECK(length(m.at(0.3f).vector({1, 0, 0})) == doctest::Approx(2.0).epsilon(1e-6));
  // The shorter way round: from 0° to 270° is a quarter turn backwards.
  const MotionTransform back = motion(Transform(), Transform::rotate(270, {0, 0, 1}));
  CHECK(back.rotation_angle() == doctest::Approx(kPi / 2).epsilon(1e-6));
  CHECK(rows_near(back.at(0.5f), Transform::rotate(-45, {0, 0, 1}), 2e-6f));
  // Rotation and stretch together (a squashed wheel turning): pbrt-v4's T·R·S, each part interpolated on its own.
  const Transform squash = Transform::scale({1, 0.5f, 1});
  const MotionTransform wheel = motion(squash, Transform::translate({2, 0, 0}) * Transform::rotate(60, {0, 0, 1}) * squash);
  CHECK(rows_near(wheel.at(0.5f), Transform::translate({1, 0, 0}) * Transform::rotate(30, {0, 0, 1}) * squash, 2e-6f));
}

TEST_CASE("motion: linear keys follow the arc to within the chord of a key interval") {
  const MotionTransform m = motion(Transform(), Transform::translate({0, 0, 3}) * Transform::rotate(150, {0, 1, 0}));
  const std::vector<Transform> keys = m.linear_keys(kKeyAngle);
  CHECK(keys.size() == 76);  // 150° in 75 segments of 2°
  CHECK(keys.front().rows() == m.start().rows());
  CHECK(keys.back().rows() == m.end().rows());
  for (size_t i = 0; i < keys.size(); ++i) {
    const float t = float(i) / float(keys.size() - 1);
    CHECK(rows_near(interpolate_keys(keys, t), m.at(t), 2e-6f));
  }
  // Between keys a point 1 from the axis is inside its arc by at most 1 − cos(1°) = 1.5e-4, never outside it.
  double worst = 0;
  for (int k = 0; k <= 1000; ++k) {
    const float t = float(k) / 1000.0f;
    const Vec3 exact = m.at(t).point({1, 0, 0}), keyed = interpolate_keys(keys, t).point({1, 0, 0});
    // Distances from the axis, which moves along z by 3t.
    const double r_exact = std::hypot(exact.x, exact.z - 3.0 * t), r_keyed = std::hypot(keyed.x, keyed.z - 3.0 * t);
    CHECK(r_keyed <= r_exact + 1e-6);
    worst = std::max(worst, r_exact - r_keyed);
  }
  CHECK(worst <= 1.0 - std::cos(kKeyAngle / 2) + 1e-6);
  CHECK(worst > 0.5 * (1.0 - std::cos(kKeyAngle / 2)));  // the bound is reached, so the test sees the keys
  // A half turn takes the most keys Embree allows at most (129).
  CHECK(motion(Transform(), Transform::rotate(180, {1, 0, 0})).linear_keys(0.001).size() == 129);
}

TEST_CASE("motion: a mirror at one end only is refused, mirrored at both ends it interpolates") {
  bool valid = true;
  MotionTransform(Transform(), Transform::scale({-1, 1, 1}), valid);
  CHECK_FALSE(valid);
  const Transform mirror = Transform::scale({-1, 1, 1});
  const MotionTransform m = motion(mirror, Transform::rotate(90, {0, 0, 1}) * mirror);
  CHECK(m.at(0.5f).determinant() == doctest::Approx(-1.0).epsilon(1e-5));
  CHECK(rows_near(m.at(0.5f), Transform::rotate(45, {0, 0, 1}) * mirror, 2e-6f));
}
