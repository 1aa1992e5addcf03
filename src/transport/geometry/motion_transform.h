// A placement that changes while the shutter is open: motion blur of moving objects and cameras.
#pragma once

#include <array>
#include <vector>

#include "transport/geometry/transform.h"

namespace rimu {

/// The translation, rotation and stretch of an affine map M = T·R·S: T a translation, R a rotation (unit
/// quaternion x, y, z, w) and S symmetric (the polar decomposition of M's linear part; S is negative definite
/// where M mirrors, so that R stays a proper rotation).
struct TransformComponents {
  Vec3 translation;
  std::array<double, 4> rotation{0, 0, 0, 1};
  std::array<double, 9> stretch{1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< row-major 3 × 3
};

/// Splits `m` into its components (polar decomposition by Higham's iteration M ← ½(M + M⁻ᵀ), in double).
TransformComponents decompose(const Transform& m);

/// An object's placement from `start` (shutter open, time 0) to `end` (shutter close, time 1), interpolated as
/// pbrt-v4's AnimatedTransform does (Shoemake & Duff 1992, "Matrix animation and polar decomposition"): both ends
/// are decomposed (decompose()), the translations and stretches are interpolated linearly and the rotations along
/// the shorter great arc (slerp). So a spinning wheel keeps its size, which interpolating the matrices would not.
class MotionTransform {
 public:
  /// False in `valid` if one end mirrors and the other does not (the object would pass through a flat state).
  MotionTransform(const Transform& start, const Transform& end, bool& valid);

  const Transform& start() const { return start_; }
  const Transform& end() const { return end_; }
  /// The placement at `time` in [0, 1] (clamped): exactly start() at 0 and end() at 1.
  Transform at(float time) const;
  /// The angle the rotation turns through from start to end, radians (0 ≤ angle ≤ π).
  double rotation_angle() const { return rotation_angle_; }

  /// Keys for a renderer that interpolates matrices linearly between equally spaced times (Embree's motion blur):
  /// at() at i/n, i = 0…n, where n is the fewest segments that turn by at most `max_segment_angle` radians each
  /// (n = 1 without rotation: then the matrices' linear interpolation is at() exactly). Between keys a rotating
  /// point cuts the arc's chord: its distance from the axis is short by at most 1 − cos(angle/2).
  std::vector<Transform> linear_keys(double max_segment_angle) const;

 private:
  Transform start_, end_;
  TransformComponents from_, to_;
  double rotation_angle_ = 0;
};

/// The matrices' linear interpolation at `time` in [0, 1] between equally spaced `keys` (at least one), as Embree
/// interpolates an instance's transforms: the segment floor(time·(n − 1)), the fraction within it.
Transform interpolate_keys(const std::vector<Transform>& keys, float time);

}  // namespace rimu
