// The "curves" shape of the JSON scene format: thin curves (hair, fur) as Embree's native curves (curve_set.h).
#include <cmath>
#include <stdexcept>

#include "render/scene/coordinate_limit.h"
#include "render/scene/curve_set.h"
#include "render/scene/scene_load_context.h"

namespace rimu::scene_loading {
namespace {

// The numbers of a flat array, read from the JSON value directly (a hair shape holds hundreds of thousands: a
// cursor apiece would copy its key path each time); the first non-finite or out-of-range one fails at its index.
std::vector<float> numbers_of(const JsonCursor& array, double min) {
  if (!array.is_array()) array.fail("expected an array of numbers");
  std::vector<float> out;
  out.reserve(array.size());
  for (const auto& v : array.value()) {
    const double x = v.is_number() ? v.get<double>() : std::nan("");
    if (!(x >= min && x <= 1e30 && float(x) <= 3.4e38f)) array.at(out.size()).number(min, 1e30);  // fails, naming it
    out.push_back(float(x));
  }
  return out;
}

std::vector<Vec3> triples_of(const JsonCursor& array, const char* what) {
  const std::vector<float> numbers = numbers_of(array, -1e30);
  if (numbers.size() % 3 != 0)
    array.fail(std::string("expected x, y, z per ") + what + ": " + std::to_string(numbers.size()) + " numbers is not a multiple of 3");
  std::vector<Vec3> out(numbers.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {numbers[3 * i], numbers[3 * i + 1], numbers[3 * i + 2]};
  return out;
}

}  // namespace

void load_curves(const JsonCursor& shape, int material, LoadContext& context) {
  if (shape.has("emission"))
    shape.at("emission").fail("curves cannot emit (they are not area lights); use a mesh");
  shape.only_keys({"type", "name", "material", "curve_type", "basis", "degree", "points", "widths", "width", "counts",
                   "normals", "transform"});
  CurveSet set;
  const std::string kind = shape.has("curve_type") ? shape.at("curve_type").choice({"flat", "cylinder", "ribbon"}) : "flat";
  set.kind = kind == "cylinder" ? CurveKind::cylinder : kind == "ribbon" ? CurveKind::ribbon : CurveKind::flat;
  const CurveBasis basis =
      shape.has("basis") && shape.at("basis").choice({"bezier", "bspline"}) == "bspline" ? CurveBasis::bspline : CurveBasis::bezier;
  const int degree = shape.has("degree") ? shape.at("degree").integer(2, 3) : 3;

  const Transform transform = parse_transform(shape);
  std::vector<Vec3> points = triples_of(shape.at("points"), "point");
  // Widths (full widths, diameters, in scene units) become radii; a transform scales them by its mean scale
  // factor |det|^(1/3), exact for rotations with one uniform scale (a curve has one width, not an ellipse).
  const float width_scale = std::cbrt(std::fabs(transform.determinant()));
  std::vector<float> radii;
  if (shape.has("widths") == shape.has("width")) shape.fail("give \"widths\" (one per point) or \"width\" (for all), not both or neither");
  if (shape.has("widths")) {
    radii = numbers_of(shape.at("widths"), 0.0);
    if (radii.size() != points.size())
      shape.at("widths").fail("expected one width per point: " + std::to_string(radii.size()) + " widths for " +
                              std::to_string(points.size()) + " points");
  } else {
    radii.assign(points.size(), float(shape.at("width").number(0.0, 1e30)));
  }
  for (float& r : radii) r *= 0.5f * width_scale;
  for (size_t i = 0; i < points.size(); ++i) {
    points[i] = transform.point(points[i]);
    if (!(max_component(abs(points[i])) <= float(kMaxCoordinate_m)))  // the message is built only for a bad point
      check_coordinates(points[i], shape.at("points"), "curve point " + std::to_string(i));
  }

  std::vector<size_t> counts;
  if (const auto c = shape.find("counts")) {
    if (!c->is_array() || c->size() == 0) c->fail("expected an array of point counts, one per curve");
    size_t total = 0;
    for (size_t i = 0; i < c->size(); ++i) {
      counts.push_back(size_t(c->at(i).integer(1, 1 << 30)));
      total += counts.back();
    }
    if (total != points.size())
      c->fail("the counts add up to " + std::to_string(total) + " points, but \"points\" holds " + std::to_string(points.size()));
  } else {
    counts.push_back(points.size());
  }
  std::vector<Vec3> normals;
  if (set.kind == CurveKind::ribbon) {
    normals = triples_of(shape.at("normals"), "normal");
    for (Vec3& n : normals) {
      n = transform.normal(n);
      if (!(length_squared(n) > 0.0f)) shape.at("normals").fail("a ribbon's normals must not be zero");
      n = normalize(n);
    }
  } else if (shape.has("normals")) {
    shape.at("normals").fail("normals orient a \"ribbon\" only (curve_type)");
  }

  const std::string expected = basis == CurveBasis::bspline
                                   ? "a B-spline of degree " + std::to_string(degree) + " has n + " + std::to_string(degree) +
                                         " points for n >= 1 segments"
                                   : "a Bezier curve of degree " + std::to_string(degree) + " has " + std::to_string(degree) +
                                         "n + 1 points for n >= 1 segments";
  size_t first = 0, first_normal = 0, dropped = 0;
  for (size_t k = 0; k < counts.size(); ++k) {
    const size_t segments = curve_segment_count(counts[k], basis, degree);
    const JsonCursor where = shape.has("counts") ? shape.at("counts").at(k) : shape.at("points");
    if (segments == 0) where.fail("curve " + std::to_string(k) + " has " + std::to_string(counts[k]) + " points: " + expected);
    std::span<const Vec3> curve_normals;
    if (set.kind == CurveKind::ribbon) {
      if (first_normal + segments + 1 > normals.size())
        shape.at("normals").fail("a ribbon needs a normal at each segment's ends (segments + 1 per curve): " +
                                 std::to_string(normals.size()) + " normals are too few");
      curve_normals = std::span<const Vec3>(normals).subspan(first_normal, segments + 1);
      first_normal += segments + 1;
    }
    dropped += append_curve(set, std::span<const Vec3>(points).subspan(first, counts[k]),
                            std::span<const float>(radii).subspan(first, counts[k]), basis, degree, curve_normals);
    first += counts[k];
  }
  if (set.kind == CurveKind::ribbon && first_normal != normals.size())
    shape.at("normals").fail("a ribbon needs a normal at each segment's ends (segments + 1 per curve): expected " +
                             std::to_string(first_normal) + ", found " + std::to_string(normals.size()));
  // Segments of zero width, or of one point, can never be hit: left out, and said so (like degenerate triangles).
  if (dropped > 0)
    context.scene.warnings.push_back(shape.path() + ": " + std::to_string(dropped) +
                                     " curve segments of zero width or a single point were left out");
  if (set.segments() > 0) context.scene.geometry.add_curves(std::move(set), material);
}

}  // namespace rimu::scene_loading
