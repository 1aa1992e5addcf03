// pbrt-v4's Shape "curve" → Rimu's "curves" shape (docs/pbrt-import.md, Shapes; render/scene/curve_set.h).
#include <string>
#include <vector>

#include "render/scene/pbrt/pbrt_converter.h"

namespace rimu {
namespace {

Vec3d mix(std::initializer_list<std::pair<double, const Vec3d*>> terms) {
  Vec3d out{0, 0, 0};
  for (const auto& [w, p] : terms)
    for (int k = 0; k < 3; ++k) out[k] += w * (*p)[k];
  return out;
}

// A uniform B-spline's points as the Bézier points of the same curve (degree kept), segment ends shared: pbrt-v4
// converts each segment so, and widths written per Bézier point can then follow pbrt's linear width exactly (a
// B-spline's per-point widths could not: its end points lie beyond the curve's ends, where a width tapering to 0
// would have to be negative).
std::vector<Vec3d> bspline_to_bezier(const std::vector<Vec3d>& p, int degree) {
  std::vector<Vec3d> out;
  const size_t segments = p.size() - size_t(degree);
  for (size_t k = 0; k < segments; ++k) {
    const Vec3d* s = &p[k];
    if (degree == 3) {
      if (k == 0) out.push_back(mix({{1.0 / 6, &s[0]}, {4.0 / 6, &s[1]}, {1.0 / 6, &s[2]}}));
      out.push_back(mix({{2.0 / 3, &s[1]}, {1.0 / 3, &s[2]}}));
      out.push_back(mix({{1.0 / 3, &s[1]}, {2.0 / 3, &s[2]}}));
      out.push_back(mix({{1.0 / 6, &s[1]}, {4.0 / 6, &s[2]}, {1.0 / 6, &s[3]}}));
    } else {
      if (k == 0) out.push_back(mix({{0.5, &s[0]}, {0.5, &s[1]}}));
      out.push_back(s[1]);
      out.push_back(mix({{0.5, &s[1]}, {0.5, &s[2]}}));
    }
  }
  return out;
}

// The members every curve of one "curves" shape shares: curves merge when these are equal.
bool same_curve_kind(const json& a, const json& b) {
  for (const char* key : {"type", "material", "curve_type", "degree", "transform", "alpha", "emission"})
    if (a.contains(key) != b.contains(key) || (a.contains(key) && a[key] != b[key])) return false;
  return true;
}

}  // namespace

void PbrtConverter::curve_shape(const PbrtStatement& s, const std::string& context, const std::vector<PbrtParam>* shape_defaults) {
  PbrtParams p(*this, s, context, shape_defaults);
  const double width = p.real("width", 1.0);
  const double width0 = p.real("width0", width), width1 = p.real("width1", width);
  const int degree = p.integer("degree", 3);
  const std::string basis = p.string("basis", "bezier");
  std::string type = p.string("type", "flat");
  p.integer("splitdepth", 3);  // pbrt splits segments for its own intersector; Embree's needs no splitting
  std::vector<Vec3d> points;
  {
    const std::vector<double> numbers = p.numbers("P", {PbrtParamType::point3});
    for (size_t i = 0; i + 2 < numbers.size(); i += 3) points.push_back({numbers[i], numbers[i + 1], numbers[i + 2]});
  }
  const std::vector<double> normal_numbers = p.numbers("N", {PbrtParamType::normal});
  if (!(width0 >= 0 && width1 >= 0))
    throw InputError(s.where, context + ": \"width\", \"width0\" and \"width1\" must be >= 0 (found " + std::to_string(width0) +
                                  ", " + std::to_string(width1) + ")");
  // pbrt-v4 reports these as errors and renders the rest of the scene without the curve: listed, left out.
  if (degree != 2 && degree != 3) {
    ignore(context + " of \"degree\" other than 2 or 3 (pbrt-v4 refuses it too)", s.where);
    return;
  }
  if (basis != "bezier" && basis != "bspline") {
    ignore(context + " of \"basis\" other than \"bezier\" or \"bspline\" (pbrt-v4 refuses it too)", s.where);
    return;
  }
  const size_t n = points.size(), d = size_t(degree);
  const size_t segments = basis == "bspline" ? (n >= d + 1 ? n - d : 0) : (n >= d + 1 && (n - 1) % d == 0 ? (n - 1) / d : 0);
  if (segments == 0) {
    ignore(context + " whose count of \"P\" makes no whole segments (pbrt-v4 refuses it too)", s.where);
    return;
  }
  if (type != "flat" && type != "cylinder" && type != "ribbon") {
    ignore(context + " of \"type\" \"" + type + "\" (read as \"cylinder\", as pbrt-v4 does)", s.where);
    type = "cylinder";
  }
  if (type == "ribbon" && normal_numbers.size() != 3 * (segments + 1)) {
    ignore(context + " \"ribbon\" without a normal \"N\" at each segment's ends (pbrt-v4 refuses it too)", s.where);
    return;
  }
  if (type != "ribbon" && !normal_numbers.empty()) ignore(context + " \"N\" on a curve that is not a \"ribbon\" (pbrt-v4 ignores it too)", s.where);
  if (object_) {
    ignore(context + " inside ObjectBegin (Rimu's instances hold triangle meshes; left out)", s.where);
    return;
  }
  if (basis == "bspline") points = bspline_to_bezier(points, degree);

  json flat_points = json::array(), widths = json::array();
  for (size_t i = 0; i < points.size(); ++i) {
    for (int k = 0; k < 3; ++k) flat_points.push_back(points[i][k]);
    // pbrt-v4's width runs linearly from width0 to width1 along the curve; Bézier point i of a curve of m points
    // sits at u = i/(m − 1), and a linear function's Bézier coefficients are its values there.
    const double u = double(i) / double(points.size() - 1);
    widths.push_back(width0 + (width1 - width0) * u);
  }
  json shape = {{"type", "curves"}, {"curve_type", type}, {"degree", degree}, {"points", std::move(flat_points)},
                {"widths", std::move(widths)}, {"counts", json::array({points.size()})}};
  if (type == "ribbon") shape["normals"] = normal_numbers;
  const size_t shapes_before = shapes_.size();
  emit_shape(std::move(shape), s.where, context, false, 0.0, 1.0);
  if (shapes_.size() == shapes_before) return;  // not emitted (its material was refused, and listed)

  // Merge into the curves shape before (one Embree geometry, one origin with a line per curve) when it is the last
  // shape and shares everything but the points.
  const size_t last = shapes_.size() - 1;
  if (curve_batch_ && curve_batch_->shape + 1 == last && curve_batch_->origin + 2 == origins_.size() &&
      origins_[curve_batch_->origin].where.file == s.where.file && same_curve_kind(shapes_[curve_batch_->shape], shapes_[last])) {
    json& batch = shapes_[curve_batch_->shape];
    json& one = shapes_[last];
    for (const char* key : {"points", "widths", "normals"})
      if (one.contains(key))
        for (json& v : one[key]) batch[key].push_back(std::move(v));
    batch["counts"].push_back(one["counts"][0]);
    shapes_.erase(last);
    origins_.pop_back();
    origins_[curve_batch_->origin].element_lines.push_back(s.where.line);
    return;
  }
  if (!shapes_.empty() && shapes_.back()["type"] == "curves") {
    curve_batch_ = CurveBatch{last, origins_.size() - 1};
    origins_.back().element_lines.push_back(s.where.line);
  }
}

}  // namespace rimu
