// pbrt-v4 shapes → Rimu shapes: meshes inline or by file, spheres analytic where Rimu's sphere can stand for them,
// tessellated otherwise (partial spheres always); cylinders and disks tessellated (render/scene/analytic_shapes.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <utility>

#include "render/scene/analytic_shapes.h"
#include "render/scene/loop_subdivision.h"
#include "render/scene/pbrt/pbrt_converter.h"
#include "render/scene/ply_loader.h"
#include "render/scene/triangle_mesh.h"
#include "render/scene/pbrt/pbrt_vector_math.h"

namespace rimu {

namespace {

using pbrt_math::cross;
using pbrt_math::dot;
using pbrt_math::sub;

std::vector<Vec3d> triples(const std::vector<double>& v) {
  std::vector<Vec3d> out(v.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
  return out;
}

// True when the linear part is a rotation (or mirror) times one uniform scale, returned in `scale`.
bool is_similarity(const PbrtMatrix& m, double& scale) {
  Vec3d c[3];
  for (int j = 0; j < 3; ++j) c[j] = {m.m[0][j], m.m[1][j], m.m[2][j]};
  const double l0 = std::sqrt(dot(c[0], c[0]));
  if (!(l0 > 0)) return false;
  for (int j = 1; j < 3; ++j)
    if (std::abs(std::sqrt(dot(c[j], c[j])) - l0) > 1e-6 * l0) return false;
  if (std::abs(dot(c[0], c[1])) > 1e-6 * l0 * l0 || std::abs(dot(c[0], c[2])) > 1e-6 * l0 * l0 ||
      std::abs(dot(c[1], c[2])) > 1e-6 * l0 * l0)
    return false;
  scale = l0;
  return true;
}

}  // namespace

void PbrtConverter::shape(const PbrtStatement& s) {
  const std::string& type = s.strings[0];
  const std::string context = "Shape \"" + type + "\"";
  const auto defaults = state_.attributes.find("shape");
  const std::vector<PbrtParam>* shape_defaults = defaults == state_.attributes.end() ? nullptr : &defaults->second;
  // pbrt-v4 takes a singular CTM (exporters scale hidden objects by 0; transparent-machines has such transforms) and
  // renders what it flattens; Rimu's shapes need an invertible transform, so the shape is left out and listed.
  // Non-finite and projective transforms stay errors (transform_steps).
  if (const PbrtMatrix m = object_ ? state_.ctm : world_from_object();
      m.is_finite() && m.is_affine() && !(std::abs(m.determinant3()) > 1e-30)) {
    ignore(context + " under a singular transform (pbrt-v4 renders it flattened; left out)", s.where);
    return;
  }
  if (type == "trianglemesh" || type == "bilinearmesh" || type == "loopsubdiv") {
    PbrtParams p(*this, s, context, shape_defaults);
    const int levels = type == "loopsubdiv" ? p.integer("levels", 3) : 0;
    if (levels < 0 || levels > 10) throw InputError(s.where, context + ": \"levels\" must be 0-10, not " + std::to_string(levels));
    std::vector<Vec3d> positions = triples(p.numbers("P", {PbrtParamType::point3}));
    if (positions.empty()) throw InputError(s.where, context + ": needs \"point3 P\"");
    const std::vector<double> raw_indices = p.numbers("indices", {PbrtParamType::integer});
    const size_t corners = type == "bilinearmesh" ? 4 : 3;
    std::vector<uint32_t> indices;
    if (raw_indices.empty()) {
      if (positions.size() != corners)
        throw InputError(s.where, context + ": \"integer indices\" is required unless P holds exactly " + std::to_string(corners) + " points");
      for (uint32_t i = 0; i < corners; ++i) indices.push_back(i);
    } else {
      if (raw_indices.size() % corners != 0)
        throw InputError(s.where, context + ": \"indices\" must hold a multiple of " + std::to_string(corners) + " values, found " +
                                      std::to_string(raw_indices.size()));
      for (double v : raw_indices) {
        if (v < 0 || v >= double(positions.size()))
          throw InputError(s.where, context + ": index " + std::to_string(int64_t(v)) + " is out of range (P has " +
                                        std::to_string(positions.size()) + " points)");
        indices.push_back(uint32_t(v));
      }
    }
    if (corners == 4) {
      // A bilinear patch (p00, p10, p01, p11) becomes the triangles (p00, p10, p11) and (p00, p11, p01): exact for
      // planar patches, which is what exporters write; the front is pbrt's dp/du × dp/dv side.
      std::vector<uint32_t> triangles;
      for (size_t q = 0; q < indices.size(); q += 4)
        for (uint32_t k : {0u, 1u, 3u, 0u, 3u, 2u}) triangles.push_back(indices[q + k]);
      indices = std::move(triangles);
    }
    if (type == "loopsubdiv") {
      // pbrt-v4 reads only P, indices and levels here (N and uv would be listed as unused, as pbrt ignores them).
      count_generated_triangles(double(indices.size() / 3) * std::pow(4.0, levels), s.where, context);
      try {
        LoopMesh mesh = loop_subdivide(positions, indices, levels);
        shape_alpha_ = alpha_parameter(p, false);
        const int triangles = int(mesh.indices.size() / 3);
        emit_mesh(p, std::move(mesh.positions), std::move(mesh.indices), std::move(mesh.normals), {}, context, triangles,
                  true);
        return;
      } catch (const std::length_error& e) {
        throw InputError(s.where, context + ": " + e.what());
      } catch (const std::invalid_argument& e) {
        ignore(context + " that Loop's rules do not apply to, not subdivided: " + e.what() + " (the control mesh stands in)", s.where);
      }
    }
    std::vector<Vec3d> normals = triples(p.numbers("N", {PbrtParamType::normal}));
    if (!normals.empty() && normals.size() != positions.size())
      throw InputError(s.where, context + ": \"N\" has " + std::to_string(normals.size()) + " normals for " +
                                    std::to_string(positions.size()) + " points");
    const std::vector<double> uv_numbers = p.numbers("uv", {PbrtParamType::point2});
    std::vector<std::array<double, 2>> uvs(uv_numbers.size() / 2);
    for (size_t i = 0; i < uvs.size(); ++i) uvs[i] = {uv_numbers[2 * i], uv_numbers[2 * i + 1]};
    if (!uvs.empty() && uvs.size() != positions.size())
      throw InputError(s.where, context + ": \"uv\" has " + std::to_string(uvs.size()) + " pairs for " +
                                    std::to_string(positions.size()) + " points");
    if (uvs.empty() && corners == 4 && positions.size() == 4) {
      // pbrt's default (u, v) of a bilinear patch is (0,0), (1,0), (0,1), (1,1) at p00, p10, p01, p11: kept for the
      // single patch (the common quad), whose vertices no other patch shares.
      uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    }
    shape_alpha_ = alpha_parameter(p, !uvs.empty() || corners == 3);  // triangles without uv have pbrt's default
    const int shape_count = int(raw_indices.empty() ? 1 : raw_indices.size() / corners);
    // A bilinear patch's default uv is per patch, which its two triangles cannot both carry as pbrt's triangle default.
    emit_mesh(p, std::move(positions), std::move(indices), std::move(normals), std::move(uvs), context, shape_count,
              corners == 3);
  } else if (type == "plymesh") {
    PbrtParams p(*this, s, context, shape_defaults);
    const std::string filename = p.string("filename", "");
    if (filename.empty()) throw InputError(s.where, context + ": needs \"string filename\"");
    const std::filesystem::path path = std::filesystem::absolute(s.directory / filename);
    if (!std::filesystem::is_regular_file(path)) throw InputError(s.where, context + ": cannot find the PLY file '" + path.string() + "'");
    shape_alpha_ = alpha_parameter(p, true);  // PLY meshes with cut-outs (leaves) carry uvs
    if (state_.area_light || state_.reverse_orientation || medium_in_front_only(current_material())) {
      // An emitter's side (and a reversed surface's, or one turned to bound its front medium) follows pbrt's rule,
      // triangle by triangle: the mesh stays a file, with "front": "pbrt" for the loader to apply it
      // (TriangleMesh::turn_to_pbrt_front). It was written inline until 6 December 2026: pbrt-v3-scenes'
      // coffee-splash turned a 4 MiB PLY into 90 MB of JSON and a 365 MiB peak.
      TriangleMesh mesh = load_ply(path);
      std::vector<Vec3d> positions;
      positions.reserve(mesh.positions.size());
      for (const Vec3& v : mesh.positions) positions.push_back({v.x, v.y, v.z});
      const bool turned = turn_for_front_medium(positions, mesh.indices, p.where(), context);
      positions = {};
      const bool reversed = state_.reverse_orientation != turned;
      // The importer's own copy, oriented as the loader will orient it, for the in-plane normals check and the area.
      mesh.default_uvs = TriangleMesh::DefaultUvs::pbrt;
      mesh.turn_to_pbrt_front(reversed);
      if (mesh.normals_near_plane_area_share() >= TriangleMesh::kNormalsNearPlaneWarningShare) list_normals_near_plane(p.where(), context);
      double area_m2 = 0.0;
      if (state_.area_light && !object_) {
        const PbrtMatrix world = world_from_object();
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
          const uint32_t* tri = &mesh.indices[3 * t];
          const auto point = [&](uint32_t i) { return world.point({mesh.positions[i].x, mesh.positions[i].y, mesh.positions[i].z}); };
          const Vec3d a = point(tri[0]);
          const Vec3d g = cross(sub(point(tri[1]), a), sub(point(tri[2]), a));
          area_m2 += 0.5 * std::sqrt(dot(g, g));
        }
      }
      shape_turned_for_medium_ = turned;
      emit_shape({{"type", "mesh"}, {"file", path_for_document(path)}, {"uv_default", "pbrt"}, {"front", "pbrt"},
                  {"reversed", reversed}},
                 s.where, context, true, area_m2, int(mesh.triangle_count()));
      return;
    }
    // Without uv in the file, pbrt's per-triangle default (Rimu keeps the file's vertex order here).
    emit_shape({{"type", "mesh"}, {"file", path_for_document(path)}, {"uv_default", "pbrt"}}, s.where, context, false, 0.0, 1);
  } else if (type == "sphere") {
    PbrtParams p(*this, s, context, shape_defaults);
    const double radius = p.real("radius", 1.0);
    if (!(radius > 0)) throw InputError(s.where, context + ": \"radius\" must be > 0");
    // pbrt-v4 orders zmin/zmax, clamps them to ±radius and φmax to [0, 360].
    const double z0 = p.real("zmin", -radius), z1 = p.real("zmax", radius);
    const double zmin = std::clamp(std::min(z0, z1), -radius, radius), zmax = std::clamp(std::max(z0, z1), -radius, radius);
    const double phimax_rad = std::clamp(p.real("phimax", 360.0), 0.0, 360.0) * std::numbers::pi / 180.0;
    shape_alpha_ = alpha_parameter(p, true);  // an image alpha takes the mesh path below, which carries pbrt's uv
    if (!(zmin < zmax) || !(phimax_rad > 0)) {
      ignore(context + " of zero area (zmin = zmax or phimax = 0: pbrt-v4 renders nothing)", s.where);
      shape_alpha_ = nullptr;
      return;
    }
    const bool whole = zmin <= -radius && zmax >= radius && phimax_rad >= 2 * std::numbers::pi;
    double scale = 1.0;
    const PbrtMatrix world = world_from_object();
    // Rimu's analytic sphere has no cut-outs (a sphere with alpha takes the mesh path below), is not instanced, and
    // faces outwards. An emissive one is an analytic area light (transport/lights/sphere_light.h): pbrt-v4's sphere
    // faces outwards under a mirroring transform too (its normal flips only with ReverseOrientation). An area light
    // with an image takes the mesh path: Rimu's emission images are on meshes.
    const bool image_light = state_.area_light && state_.area_light->find("filename") != nullptr;
    // A moving sphere takes the mesh path too: Rimu's analytic spheres stay where they are.
    if (whole && shape_alpha_.is_null() && !object_ && !state_.reverse_orientation && !image_light && !ctm_moves() &&
        !medium_in_front_only(current_material()) && world.is_finite() && world.is_affine() && is_similarity(world, scale)) {
      // pbrt's sphere uv is about its object axes (pole +z, u = 0 along +x): carried as their world directions,
      // so textures land where pbrt puts them (a mirroring CTM flips the direction u runs, as in pbrt).
      json axes = json::array();
      for (const Vec3d& axis : {Vec3d{1, 0, 0}, Vec3d{0, 1, 0}, Vec3d{0, 0, 1}}) {
        const Vec3d d = world.vector(axis);
        axes.push_back({d[0] / scale, d[1] / scale, d[2] / scale});
      }
      // pbrt-v4 spreads "power" over the sphere's object-space area 4π radius², so under a scale s it emits s² times
      // "power"; Rimu spreads an amount over the world-space area, which is s² times larger.
      const double world_radius = radius * scale;
      emit_shape({{"type", "sphere"}, {"center", world.point({0, 0, 0})}, {"radius", world_radius}, {"uv_axes", axes}}, s.where,
                 context, true, 4.0 * std::numbers::pi * world_radius * world_radius, scale * scale);
      return;
    }
    // Rimu's sphere cannot be partial, instanced, have cut-outs, be turned inside out or be squashed: a fine mesh with the
    // sphere's own normals and pbrt's uv stands in (render/scene/analytic_shapes.h states its error).
    emit_analytic_mesh(p, sphere_mesh(radius, zmin, zmax, phimax_rad), s.where, context);
  } else if (type == "cylinder") {
    PbrtParams p(*this, s, context, shape_defaults);
    const double radius = p.real("radius", 1.0);
    const double z0 = p.real("zmin", -1.0), z1 = p.real("zmax", 1.0);
    const double phimax_rad = std::clamp(p.real("phimax", 360.0), 0.0, 360.0) * std::numbers::pi / 180.0;
    if (!(radius > 0)) throw InputError(s.where, context + ": \"radius\" must be > 0");
    shape_alpha_ = alpha_parameter(p, true);
    if (!(z0 != z1) || !(phimax_rad > 0)) {
      ignore(context + " of zero area (zmin = zmax or phimax = 0: pbrt-v4 renders nothing)", s.where);
      shape_alpha_ = nullptr;
      return;
    }
    emit_analytic_mesh(p, cylinder_mesh(radius, std::min(z0, z1), std::max(z0, z1), phimax_rad), s.where, context);
  } else if (type == "disk") {
    PbrtParams p(*this, s, context, shape_defaults);
    const double height = p.real("height", 0.0), radius = p.real("radius", 1.0), inner = p.real("innerradius", 0.0);
    const double phimax_rad = std::clamp(p.real("phimax", 360.0), 0.0, 360.0) * std::numbers::pi / 180.0;
    if (!(radius > 0) || inner < 0 || inner >= radius) throw InputError(s.where, context + ": needs 0 <= innerradius < radius");
    shape_alpha_ = alpha_parameter(p, true);
    if (!(phimax_rad > 0)) {
      ignore(context + " of zero area (phimax = 0: pbrt-v4 renders nothing)", s.where);
      shape_alpha_ = nullptr;
      return;
    }
    emit_analytic_mesh(p, disk_mesh(height, radius, inner, phimax_rad), s.where, context);
  } else if (type == "curve") {
    curve_shape(s, context, shape_defaults);
  } else {
    ignore(context, s.where);
  }
}

void PbrtConverter::emit_analytic_mesh(PbrtParams& p, AnalyticMesh mesh, const SourceLocation& where,
                                       const std::string& context) {
  count_generated_triangles(double(mesh.triangle_count()), where, context);
  emit_mesh(p, std::move(mesh.positions), std::move(mesh.indices), std::move(mesh.normals), std::move(mesh.uvs), context, 1);
}

void PbrtConverter::count_generated_triangles(double triangles, const SourceLocation& where, const std::string& context) {
  if (double(generated_triangles_) + triangles > double(max_generated_triangles_))
    throw InputError(where, context + ": would generate " + std::to_string(int64_t(triangles)) + " triangles after " +
                                std::to_string(generated_triangles_) + ", beyond the importer's limit of " +
                                std::to_string(max_generated_triangles_) +
                                " generated triangles per scene (Loop subdivision, sphere, cylinder and disk meshes; lower \"levels\"?)");
  generated_triangles_ += size_t(triangles);
}

void PbrtConverter::emit_mesh(PbrtParams& p, std::vector<Vec3d> positions, std::vector<uint32_t> indices,
                              std::vector<Vec3d> normals, std::vector<std::array<double, 2>> uvs, const std::string& context,
                              int shape_count, bool pbrt_default_uvs) {
  // pbrt's front: the side of the shading normals N where given (flipped by ReverseOrientation), else the
  // counter-clockwise side, flipped by ReverseOrientation. Rimu's front is always the counter-clockwise side, so
  // triangles are rewound to match; a mirroring transform is left to Rimu, which rewinds as pbrt flips.
  // A shape that bounds the medium in front of it is turned inside out (pbrt_media.cpp, turn_for_front_medium).
  const bool turned = turn_for_front_medium(positions, indices, p.where(), context);
  const bool reverse = state_.reverse_orientation != turned;
  if (reverse)
    for (Vec3d& n : normals) n = {-n[0], -n[1], -n[2]};
  std::vector<bool> flips(indices.size() / 3, false);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    bool flip = reverse;
    if (!normals.empty()) {
      const Vec3d g = cross(sub(positions[indices[t + 1]], positions[indices[t]]), sub(positions[indices[t + 2]], positions[indices[t]]));
      const Vec3d& a = normals[indices[t]];
      const Vec3d& b = normals[indices[t + 1]];
      const Vec3d& c = normals[indices[t + 2]];
      // A corner without a normal (a PLY file's zero or NaN, read as (0, 0, 0)) leaves pbrt's normal NaN, which
      // orients nothing: such a triangle keeps its winding's front.
      const bool all_normals = dot(a, a) > 0 && dot(b, b) > 0 && dot(c, c) > 0;
      if (all_normals) flip = dot(g, {a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]}) < 0;
    }
    flips[t / 3] = flip;
  }
  // pbrt-v4 gives a triangle without uv (0,0), (1,0), (1,1) at its vertices in the order read. Rewinding moves
  // vertices 1 and 2, so where any triangle is rewound the corners get their own vertices with explicit uvs.
  bool uv_default_pbrt = false;
  if (pbrt_default_uvs && uvs.empty()) {
    if (std::find(flips.begin(), flips.end(), true) == flips.end()) {
      uv_default_pbrt = true;
    } else {
      std::vector<Vec3d> corner_positions, corner_normals;
      std::vector<uint32_t> corner_indices;
      for (size_t t = 0; t + 2 < indices.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
          corner_indices.push_back(uint32_t(corner_positions.size()));
          corner_positions.push_back(positions[indices[t + k]]);
          if (!normals.empty()) corner_normals.push_back(normals[indices[t + k]]);
          uvs.push_back(k == 0 ? std::array<double, 2>{0, 0} : k == 1 ? std::array<double, 2>{1, 0} : std::array<double, 2>{1, 1});
        }
      positions = std::move(corner_positions);
      normals = std::move(corner_normals);
      indices = std::move(corner_indices);
    }
  }
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    if (flips[t / 3]) std::swap(indices[t + 1], indices[t + 2]);
  if (!normals.empty()) list_normals_near_plane(positions, indices, normals, p.where(), context);
  double area_m2 = 0.0;
  if (state_.area_light && !object_) {
    const PbrtMatrix world = world_from_object();
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
      const Vec3d a = world.point(positions[indices[t]]);
      const Vec3d g = cross(sub(world.point(positions[indices[t + 1]]), a), sub(world.point(positions[indices[t + 2]]), a));
      area_m2 += 0.5 * std::sqrt(dot(g, g));
    }
  }
  json shape = {{"type", "triangles"}, {"positions", positions}, {"indices", indices}};
  if (!normals.empty()) shape["normals"] = normals;
  if (!uvs.empty()) shape["uvs"] = uvs;
  if (uv_default_pbrt) shape["uv_default"] = "pbrt";
  shape_turned_for_medium_ = turned;
  emit_shape(std::move(shape), p.where(), context, true, area_m2, shape_count);
}

void PbrtConverter::list_normals_near_plane(const std::vector<Vec3d>& positions, const std::vector<uint32_t>& indices,
                                            const std::vector<Vec3d>& normals, const SourceLocation& where,
                                            const std::string& context) {
  TriangleMesh mesh;
  for (const Vec3d& v : positions) mesh.positions.push_back(Vec3{float(v[0]), float(v[1]), float(v[2])});
  for (const Vec3d& n : normals) mesh.normals.push_back(Vec3{float(n[0]), float(n[1]), float(n[2])});
  mesh.indices = indices;
  // A floor whose normals all point along it: pbrt-v3-scenes' buddha-fractal, docs/benchmarks.md "Real-scene corpus".
  if (mesh.normals_near_plane_area_share() < TriangleMesh::kNormalsNearPlaneWarningShare) return;
  list_normals_near_plane(where, context);
}

void PbrtConverter::list_normals_near_plane(const SourceLocation& where, const std::string& context) {
  ignore(context + " with shading normals \"N\" in (or across) the plane of 1 % or more of its area: on an opaque "
                   "surface Rimu ends the paths that leave it below that plane, pbrt-v4 follows them through the surface "
                   "(its image can be brighter there)",
         where);
}

void PbrtConverter::emit_shape(json shape, const SourceLocation& where, const std::string& context, bool emissive_capable,
                               double area_m2, double power_multiple) {
  json alpha = std::exchange(shape_alpha_, nullptr);  // taken first: no early return may leave it to the next shape
  const std::optional<std::string> material =
      boundary_material(state_.material.empty() ? default_material() : state_.material, where, context);
  if (!material) return;
  shape["material"] = *material;
  if (!alpha.is_null()) {
    if (state_.area_light && !object_ && emissive_capable) {
      // pbrt-v4 makes a constant alpha of 0 an invisible light that still emits (reached by light sampling only;
      // kroken's "sun" sphere); Rimu has no invisible emitters.
      if (alpha.is_number() && alpha.get<double>() <= 0.0)
        ignore("\"alpha\" 0 on an area light (in pbrt-v4 an invisible emitter; Rimu's is seen: left solid)", where);
      else
        ignore("\"alpha\" on an area light (Rimu's lights are not cut out: left solid)", where);
    } else {
      shape["alpha"] = std::move(alpha);
    }
  }
  if (shape["type"] != "sphere") {
    const PbrtMatrix placement = object_ ? state_.ctm : world_from_object();
    const bool emits = state_.area_light && !object_ && emissive_capable;
    const bool curves = shape["type"] == "curves";
    if (ctm_moves() && curves && !object_)
      ignore(context + " that moves (Rimu's curves do not: shown at the start placement)", where);
    if (ctm_moves() && object_)
      ignore(context + " moving inside ObjectBegin (shown at its start placement; an ObjectInstance can move)", where);
    if (ctm_moves() && emits)
      ignore("a moving area light (pbrt-v4 refuses it: \"Animated area lights are not supported\"); rendered at its "
             "start placement, still",
             where);
    if (ctm_moves() && !object_ && !emits && !curves) {
      // Motion blur: where the shape is at shutteropen and at shutterclose.
      const auto [open, close] = shutter_placements(placement, mirror_ * state_.ctm_end, where);
      shape["transform"] = json::array({{{"matrix", matrix_rows(open, where)}}});
      shape["transform_end"] = json::array({{{"matrix", matrix_rows(close, where)}}});
    } else {
      const json steps = transform_steps(placement, where);
      if (!steps.is_null()) shape["transform"] = steps;
    }
  }
  if (state_.area_light) {
    if (object_) {
      ignore("AreaLightSource on a shape inside ObjectBegin (instances do not emit)", where);
    } else if (!emissive_capable) {
      ignore("AreaLightSource on " + context + " (not emissive in Rimu)", where);
    } else {
      bool two_sided = false;
      shape["emission"] = area_emission(*state_.area_light, area_m2, power_multiple, two_sided, shape["type"] != "sphere");
      if (two_sided) shape["two_sided"] = true;
    }
  }
  if (object_) {
    origin("/prototypes/" + *object_ + "/" + std::to_string(prototypes_[*object_].size()), where, context);
    prototypes_[*object_].push_back(std::move(shape));
  } else {
    origin("/shapes/" + std::to_string(shapes_.size()), where, context);
    shapes_.push_back(std::move(shape));
  }
}

json PbrtConverter::alpha_parameter(PbrtParams& p, bool has_uvs) {
  const PbrtParam* param = p.get("alpha", {PbrtParamType::real, PbrtParamType::texture});
  if (!param) return nullptr;
  if (param->type == PbrtParamType::real) {
    const double alpha = param->numbers.empty() ? 1.0 : param->numbers[0];
    return alpha >= 1.0 ? json(nullptr) : json(std::clamp(alpha, 0.0, 1.0));
  }
  const std::string& name = param->strings.at(0);
  const auto it = textures_.find(name);
  if (it == textures_.end())
    throw InputError(param->where, p.context() + ": \"alpha\" names the texture \"" + name + "\", which is not defined");
  const PbrtTexture& texture = it->second;
  if (texture.kind != "float")
    throw InputError(param->where, p.context() + ": \"alpha\" needs a float texture; \"" + name + "\" is a " + texture.kind + " texture");
  const PbrtStatement& ts = texture.statement;
  if (texture.texture_class == "imagemap" && !has_uvs) {
    ignore("alpha image texture on a shape without texture coordinates (left solid)", p.where());
    return nullptr;
  }
  PbrtParams tp(*this, ts, "Texture \"" + name + "\"");
  if (texture.texture_class == "constant") {
    const double alpha = tp.real("value", 1.0);
    return alpha >= 1.0 ? json(nullptr) : json(std::clamp(alpha, 0.0, 1.0));
  }
  if (texture.texture_class != "imagemap") {
    ignore("alpha texture of class \"" + texture.texture_class + "\" (the shape is left solid)", ts.where);
    return nullptr;
  }
  const std::string filename = tp.string("filename", "");
  if (filename.empty()) throw InputError(ts.where, "Texture \"" + name + "\": needs \"string filename\"");
  const std::filesystem::path path = std::filesystem::absolute(ts.directory / filename);
  if (!std::filesystem::is_regular_file(path))
    throw InputError(ts.where, "Texture \"" + name + "\": cannot find the image '" + path.string() + "'");
  // A float imagemap reads the image's first channel (pbrt-v4's MIPMap texel for Float).
  json value = {{"texture", path_for_document(path)}, {"channel", "r"}, {"encoding", image_encoding(tp, path, ts.where)}};
  if (tp.boolean("invert", false)) value["invert"] = true;
  if (tp.real("scale", 1.0) != 1.0) ignore("\"scale\" of an alpha texture (alpha is used unscaled)", ts.where);
  if (tp.string("mapping", "uv") != "uv" || tp.real("uscale", 1) != 1 || tp.real("vscale", 1) != 1 || tp.real("udelta", 0) != 0 ||
      tp.real("vdelta", 0) != 0)
    ignore("texture mapping other than plain uv", ts.where);
  // An alpha test runs before the hit has a footprint: cut-outs are read bilinearly from the full-resolution image.
  tp.string("filter", "bilinear");
  tp.real("maxanisotropy", 8.0);
  tp.string("wrap", "repeat");
  return value;
}

}  // namespace rimu
