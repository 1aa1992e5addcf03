// Shapes, transforms and instancing of the JSON scene format.
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "render/image/alpha_mask.h"
#include "render/scene/analytic_shapes.h"
#include "render/scene/mesh_loader.h"
#include "render/image/rgb_image.h"
#include "transport/lights/area_light.h"
#include "transport/lights/sphere_light.h"
#include "transport/lights/light_spectrum.h"
#include "render/scene/scene_load_context.h"
#include "transport/geometry/motion_transform.h"
#include "render/scene/scene_light_emission.h"
#include "render/scene/scene_light_groups.h"

namespace rimu::scene_loading {
namespace {

int material_of(const JsonCursor& shape, const LoadContext& context) {
  const JsonCursor m = shape.at("material");
  const std::string name = m.string();
  const auto it = context.material_index.find(name);
  if (it == context.material_index.end()) {
    std::string known;
    for (const auto& [n, i] : context.material_index) known += (known.empty() ? "" : ", ") + n;
    m.fail("unknown material '" + name + "'" + (known.empty() ? "; the scene defines none" : "; defined: " + known));
  }
  return it->second;
}

std::vector<Vec3> vec3_array(const JsonCursor& c) {
  std::vector<Vec3> out;
  for (size_t i = 0; i < c.size(); ++i) out.push_back(c.at(i).vec3());
  return out;
}

// Rejects keys that belong to another triangle shape type (a "file" on a quad would otherwise be silently ignored).
// Emissive keys are allowed only outside prototypes: area lights are not instanced.
void check_triangle_shape_keys(const JsonCursor& shape, const std::string& type, bool in_prototype) {
  if (in_prototype) {
    for (const char* key : {"emission", "light_group", "two_sided"})
      if (shape.has(key))
        shape.at(key).fail("prototypes cannot hold emissive geometry (area lights are not instanced); put the "
                           "emitter in \"shapes\"");
    if (shape.has("transform_end"))
      shape.at("transform_end").fail("a prototype's shapes cannot move on their own: give the instance that places "
                                     "it a transform_end");
  }
  if (type == "mesh") {
    shape.only_keys({"type", "name", "file", "object", "material", "transform", "transform_end", "emission",
                     "light_group", "two_sided", "alpha", "uv_default", "front", "reversed"});
  } else if (type == "quad") {
    shape.only_keys({"type", "name", "vertices", "uvs", "uv_default", "material", "transform", "transform_end",
                     "emission", "light_group", "two_sided", "alpha"});
  } else if (type == "box") {
    shape.only_keys({"type", "name", "min", "max", "material", "transform", "transform_end", "emission", "light_group",
                     "two_sided", "alpha"});
  } else if (type == "cylinder") {
    shape.only_keys({"type", "name", "radius", "zmin", "zmax", "phimax_deg", "caps", "material", "transform",
                     "transform_end", "emission", "light_group", "two_sided", "alpha"});
  } else if (type == "disk") {
    shape.only_keys({"type", "name", "radius", "inner_radius", "height", "phimax_deg", "material", "transform",
                     "transform_end", "emission", "light_group", "two_sided", "alpha"});
  } else {
    shape.only_keys({"type", "name", "positions", "indices", "normals", "uvs", "uv_default", "material", "transform",
                     "transform_end", "emission", "light_group", "two_sided", "alpha"});
  }
}

// How messages name an emissive shape's light: its "name" and key path, else its key path.
std::string emissive_shape_name(const JsonCursor& shape) {
  // Appended rather than built with operator+: GCC 12 warns falsely (-Wrestrict) on "'" + std::string.
  std::string light_name;
  if (shape.has("name"))
    light_name.append("'").append(shape.at("name").string()).append("' (").append(shape.path()).append(")");
  else
    light_name.append("the emissive shape ").append(shape.path());
  return light_name;
}

// The swept angle of a cylinder or disk in radians: "phimax_deg" in (0, 360], default 360.
double phimax_of(const JsonCursor& shape) {
  if (!shape.has("phimax_deg")) return 2.0 * std::numbers::pi;
  const JsonCursor phimax = shape.at("phimax_deg");
  const double degrees = phimax.number(0.0, 360.0);
  if (!(degrees > 0.0)) phimax.fail("the swept angle must be > 0 degrees (at most 360)");
  return degrees * std::numbers::pi / 180.0;
}

// A "box", "cylinder" or "disk" shape as its mesh in object space (render/scene/analytic_shapes.h).
TriangleMesh analytic_mesh_of(const JsonCursor& shape, const std::string& type) {
  if (type == "box") {
    const Vec3 lo = shape.at("min").vec3(), hi = shape.at("max").vec3();
    for (int axis = 0; axis < 3; ++axis)
      if (!(lo[axis] < hi[axis])) shape.at("max").fail("every coordinate of max must exceed min's (a box has volume)");
    return box_mesh(lo, hi).to_triangle_mesh();
  }
  const double radius = shape.at("radius").number(0.0, 1e30);
  if (!(radius > 0.0)) shape.at("radius").fail("the radius must be > 0");
  const double phimax = phimax_of(shape);
  if (type == "disk") {
    const double inner = shape.has("inner_radius") ? shape.at("inner_radius").number(0.0, 1e30) : 0.0;
    if (!(inner < radius)) shape.at("inner_radius").fail("inner_radius must be smaller than radius");
    const double height = shape.has("height") ? shape.at("height").number(-1e30, 1e30) : 0.0;
    return disk_mesh(height, radius, inner, phimax).to_triangle_mesh();
  }
  const double zmin = shape.at("zmin").number(-1e30, 1e30), zmax = shape.at("zmax").number(-1e30, 1e30);
  if (!(zmin < zmax)) shape.at("zmax").fail("zmax must exceed zmin (the cylinder has a length)");
  AnalyticMesh mesh = cylinder_mesh(radius, zmin, zmax, phimax);
  if (shape.boolean_or("caps", false)) {
    // The ends closed by disks facing away from the cylinder: +z at zmax, −z at zmin (a wedge's cut faces stay open).
    append_mesh(mesh, disk_mesh(zmax, radius, 0.0, phimax));
    AnalyticMesh bottom = disk_mesh(zmin, radius, 0.0, phimax);
    flip_mesh(bottom);
    append_mesh(mesh, bottom);
  }
  return mesh.to_triangle_mesh();
}

// The mesh a shape describes, in object space (before its transform).
TriangleMesh mesh_of(const JsonCursor& shape, const std::string& type, LoadContext& context) {
  TriangleMesh mesh;
  if (type == "mesh") {
    const JsonCursor file = shape.at("file");
    const std::filesystem::path path = context.spectra.scene_directory() / file.string();
    try {
      mesh = load_mesh(path, shape.string_or("object", ""));
    } catch (const InputError& e) {
      SourceLocation where = e.where();
      if (where.key.empty()) where.key = file.path();
      throw InputError(where, e.explanation());
    }
  } else if (type == "quad") {
    const JsonCursor v = shape.at("vertices");
    if (v.size() != 4) v.fail("a quad has 4 vertices, counter-clockwise seen from its front");
    mesh.positions = vec3_array(v);
    mesh.indices = {0, 1, 2, 0, 2, 3};
    // Without "uvs" a quad's texture coordinates are per triangle ("uv_default" below), which no texture can follow.
    if (const auto uvs = shape.find("uvs"))
      for (size_t i = 0; i < uvs->size(); ++i) mesh.uvs.push_back(uvs->at(i).vec2());
  } else if (type == "box" || type == "cylinder" || type == "disk") {
    mesh = analytic_mesh_of(shape, type);
  } else {  // triangles
    mesh.positions = vec3_array(shape.at("positions"));
    const JsonCursor indices = shape.at("indices");
    for (size_t i = 0; i < indices.size(); ++i) mesh.indices.push_back(uint32_t(indices.at(i).integer(0, 1 << 30)));
    if (const auto normals = shape.find("normals")) mesh.normals = vec3_array(*normals);
    if (const auto uvs = shape.find("uvs"))
      for (size_t i = 0; i < uvs->size(); ++i) mesh.uvs.push_back(uvs->at(i).vec2());
  }
  // Without uvs: every triangle's vertices get (0,0), (1,0), (0,1) (the barycentrics), or pbrt-v4's (0,0), (1,0),
  // (1,1) (what the pbrt importer asks for, so that textures on uv-less pbrt meshes land where pbrt puts them).
  if (const auto convention = shape.find("uv_default"); convention && convention->choice({"barycentric", "pbrt"}) == "pbrt")
    mesh.default_uvs = TriangleMesh::DefaultUvs::pbrt;
  // A mesh file's front: its counter-clockwise side (Rimu's), or pbrt-v4's rule (the side of its shading normals),
  // either one flipped by "reversed". The pbrt importer sets these instead of writing the mesh inline.
  const bool pbrt_front = shape.has("front") && shape.at("front").choice({"counter_clockwise", "pbrt"}) == "pbrt";
  const bool reversed = shape.boolean_or("reversed", false);
  if (pbrt_front) {
    mesh.turn_to_pbrt_front(reversed);
  } else if (reversed) {
    for (Vec3& n : mesh.normals) n = -n;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
    if (mesh.uvs.empty() && mesh.default_uvs == TriangleMesh::DefaultUvs::pbrt)
      mesh.default_uvs = TriangleMesh::DefaultUvs::pbrt_swapped;
  }
  if (const std::string problem = mesh.validate(); !problem.empty()) shape.fail("invalid mesh: " + problem);
  return mesh;
}

// A shape's cut-out: a number in [0, 1], or {"texture": "mask.png", "channel": "r"|"g"|"b"|"a", "encoding":
// "srgb"|"linear", "invert": bool}. Null when the shape is solid (no key, or alpha 1).
std::shared_ptr<const AlphaMask> alpha_of(const JsonCursor& shape, LoadContext& context) {
  const auto value = shape.find("alpha");
  if (!value) return nullptr;
  if (shape.has("emission"))
    value->fail("an emissive shape cannot have an alpha (cut-out lights are not supported); give the light its own shape");
  if (value->is_number()) {
    const float alpha = float(value->number(0.0, 1.0));
    return alpha >= 1.0f ? nullptr : std::make_shared<const AlphaMask>(AlphaMask::constant(alpha));
  }
  if (!value->is_object() || !value->has("texture"))
    value->fail("expected a number in [0, 1] or {\"texture\": \"mask.png\", \"channel\": \"a\"}");
  value->only_keys({"texture", "channel", "encoding", "invert"});
  const std::string channel_name = value->has("channel") ? value->at("channel").choice({"r", "g", "b", "a"}) : "r";
  const int channel = channel_name == "r" ? 0 : channel_name == "g" ? 1 : channel_name == "b" ? 2 : 3;
  const JsonCursor file = value->at("texture");
  const std::filesystem::path path = context.spectra.scene_directory() / file.string();
  try {
    // An alpha channel is linear coverage; colour channels of 8/16-bit files carry the sRGB curve unless told.
    bool srgb = channel != 3 && default_encoding_for(path).srgb_transfer;
    if (value->has("encoding")) srgb = value->at("encoding").choice({"srgb", "linear"}) == "srgb";
    return std::make_shared<const AlphaMask>(AlphaMask::read(path, channel, srgb, value->boolean_or("invert", false)));
  } catch (const InputError& e) {
    if (!e.where().key.empty()) throw;
    SourceLocation where = e.where();
    where.key = file.path();
    throw InputError(where, e.explanation());
  }
}

void count_normals_near_plane(const TriangleMesh& mesh, Scene& scene) {
  if (mesh.normals_near_plane_area_share() >= TriangleMesh::kNormalsNearPlaneWarningShare)
    ++scene.meshes_with_normals_near_plane;
  scene.vertices_without_normal += mesh.vertices_without_normal();
}

// A "matrix": 12 numbers, three rows of a 3 × 4 matrix; InputError if singular.
Transform matrix_transform(const JsonCursor& m) {
  if (!m.is_array() || m.size() != 12) m.fail("expected 12 numbers: three rows of a 3x4 matrix");
  std::array<float, 12> rows{};
  for (size_t k = 0; k < 12; ++k) rows[k] = float(m.at(k).number());
  bool invertible = false;
  const Transform step = Transform::from_rows(rows, invertible);
  if (!invertible) m.fail("the matrix is singular (it flattens the shape)");
  return step;
}

// Transform inverts only matrices whose determinant exceeds 1e-30 in magnitude (below, its inverse would be left
// as the identity while Embree inverts the matrix itself): nearer-singular ones are refused as singular.
void check_placement(const Transform& t, const JsonCursor& where, const char* what) {
  if (!t.is_finite() || !std::isfinite(t.determinant()) || !(std::fabs(t.determinant()) > 1e-30f)) {
    std::ostringstream msg;
    msg << "the " << what << " is singular or not finite (determinant " << t.determinant()
        << "; it must be finite and exceed 1e-30 in magnitude)";
    where.fail(msg.str());
  }
}

int prototype_of(const JsonCursor& shape, const LoadContext& context) {
  const JsonCursor p = shape.at("prototype");
  const auto it = context.prototype_index.find(p.string());
  if (it == context.prototype_index.end()) p.fail("unknown prototype '" + p.string() + "'");
  return it->second;
}

// An instance of `prototype` placed by `object_to_world`, whose key is `where`.
void place_instance(int prototype, const Transform& object_to_world, const JsonCursor& where, LoadContext& context,
                    InstanceKey key) {
  check_instance_coordinates(context.prototype_bounds[prototype], object_to_world, where);
  context.scene.geometry.add_instance(prototype, object_to_world);
  context.instance_keys.push_back(key);
}

// A shape's motion while the shutter is open: from its "transform" to its "transform_end" (MotionTransform), or
// nothing for a shape without "transform_end" or one that ends where it started.
std::optional<MotionTransform> motion_of(const JsonCursor& shape) {
  if (!shape.has("transform_end")) return std::nullopt;
  const Transform start = parse_transform(shape), end = parse_transform(shape, "transform_end");
  if (start.rows() == end.rows()) return std::nullopt;
  bool valid = false;
  MotionTransform motion(start, end, valid);
  if (!valid)
    shape.at("transform_end").fail("one of transform and transform_end mirrors the shape and the other does not: "
                                   "the shape would pass through flat on its way");
  return motion;
}

// A moving instance: every key of its motion is checked as a static placement would be.
void place_moving_instance(int prototype, const MotionTransform& motion, const JsonCursor& shape, LoadContext& context,
                           InstanceKey key) {
  // Checked after adding, on the keys the scene keeps (a failed check discards the whole scene).
  EmbreeScene& geometry = context.scene.geometry;
  geometry.add_instance(prototype, motion);
  const JsonCursor where = shape.at("transform_end");
  for (const Transform& placement : *geometry.instance_motion_keys(context.instance_keys.size()))
    check_instance_coordinates(context.prototype_bounds[prototype], placement, where);
  context.instance_keys.push_back(key);
}

// What a prototype is built from: its shapes' meshes in its own space, their materials and cut-outs, and the box
// of their vertices (which every placement of the prototype is checked with).
struct PrototypeParts {
  std::vector<std::pair<TriangleMesh, int /*material*/>> meshes;
  std::vector<std::shared_ptr<const AlphaMask>> alphas;
  BoundsD bounds;
};

// Adds `shape`'s mesh (already in the prototype's space) to `parts`, checked as a scene's mesh is; a mesh of only
// degenerate triangles is counted and left out.
void add_prototype_part(const JsonCursor& shape, TriangleMesh mesh, LoadContext& context, PrototypeParts& parts) {
  const int material = material_of(shape, context);
  std::shared_ptr<const AlphaMask> alpha = alpha_of(shape, context);
  check_mesh_coordinates(mesh, shape);  // the prototype's own space is a scene too (Embree checks it alike)
  context.scene.degenerate_triangles_removed += mesh.remove_degenerate_triangles();
  count_normals_near_plane(mesh, context.scene);
  for (const Vec3& p : mesh.positions) parts.bounds.extend(p);
  if (mesh.triangle_count() > 0) {
    parts.meshes.emplace_back(std::move(mesh), material);
    parts.alphas.push_back(std::move(alpha));
  }
}

// Builds the prototype (its BVH) and records its box; returns its index.
int add_prototype(PrototypeParts parts, LoadContext& context) {
  const int index = context.scene.geometry.add_prototype(std::move(parts.meshes), parts.alphas);
  context.prototype_bounds[index] = parts.bounds;
  return index;
}

// A triangle shape that moves while the shutter is open: its mesh in object space becomes a prototype of its own,
// placed by a moving instance (the path every moving object takes through Embree). Emitters cannot move: their
// light would have to be sampled where the shape is at each ray's time (pbrt-v4 refuses moving area lights too).
void load_moving_shape(const JsonCursor& shape, const std::string& type, const MotionTransform& motion, InstanceKey key,
                       LoadContext& context) {
  for (const char* emissive : {"emission", "light_group", "two_sided"})
    if (shape.has(emissive))
      shape.at("transform_end").fail("an emissive shape cannot move (area lights are sampled where they are at "
                                     "shutter open); give it no transform_end");
  // No rewinding for a mirroring motion: an instance's normals go through the inverse transpose, which already
  // gives the normal a transformed, rewound mesh would have.
  PrototypeParts parts;
  add_prototype_part(shape, mesh_of(shape, type, context), context, parts);
  if (parts.meshes.empty()) return;  // only degenerate triangles (counted)
  const int prototype = add_prototype(std::move(parts), context);
  place_moving_instance(prototype, motion, shape, context, key);
}

}  // namespace

JsonCursor instance_cursor(const JsonCursor& shapes, InstanceKey key) {
  const JsonCursor shape = shapes.at(size_t(key.shape));
  if (key.matrix != InstanceKey::kNoMatrix) return shape.at("matrices").at(size_t(key.matrix));
  return shape.has("transform") ? shape.at("transform") : shape;
}

Transform parse_transform(const JsonCursor& shape, const char* key) {
  Transform t;
  const auto ops = shape.find(key);
  if (!ops) return t;
  if (!ops->is_array()) ops->fail("expected an array of steps, e.g. [{\"scale\": 2}, {\"translate\": [0, 1, 0]}]");
  for (size_t i = 0; i < ops->size(); ++i) {
    const JsonCursor op = ops->at(i);
    op.only_keys({"translate", "scale", "rotate", "matrix"});
    if (op.size() != 1) op.fail("each transform step has exactly one of translate, scale, rotate, matrix");
    Transform step;
    if (op.has("translate")) {
      step = Transform::translate(op.at("translate").vec3());
    } else if (op.has("scale")) {
      const JsonCursor s = op.at("scale");
      const Vec3 v = s.is_number() ? Vec3{float(s.number()), float(s.number()), float(s.number())} : s.vec3();
      if (v.x == 0.0f || v.y == 0.0f || v.z == 0.0f) s.fail("a scale of 0 collapses the shape");
      step = Transform::scale(v);
    } else if (op.has("rotate")) {
      const JsonCursor r = op.at("rotate");
      r.only_keys({"angle_deg", "axis"});
      const Vec3 axis = r.at("axis").vec3();
      if (length(axis) == 0.0f) r.at("axis").fail("the rotation axis is zero");
      step = Transform::rotate(float(r.at("angle_deg").number()), axis);
    } else {
      step = matrix_transform(op.at("matrix"));
    }
    t = step * t;  // later steps apply after earlier ones
  }
  check_placement(t, *ops, "combined transform");
  return t;
}

void load_shapes(const JsonCursor& section, LoadContext& context) {
  Scene& scene = context.scene;
  for (size_t i = 0; i < section.size(); ++i) {
    const JsonCursor shape = section.at(i);
    const std::string type =
        shape.at("type").choice({"mesh", "triangles", "quad", "box", "cylinder", "disk", "sphere", "instance", "instances", "curves"});
    if (type == "curves") {
      load_curves(shape, material_of(shape, context), context);
      continue;
    }
    if (type == "sphere") {
      shape.only_keys({"type", "name", "center", "radius", "material", "transform", "uv_axes", "emission", "light_group",
                       "two_sided"});
      if (shape.has("transform")) shape.at("transform").fail("spheres take center and radius, not a transform");
      const Vec3 centre = shape.at("center").vec3();
      const float radius = float(shape.at("radius").number(1e-30, 1e30));
      check_coordinates(centre, shape.at("center"), "the sphere's centre");
      for (const float sign : {-1.0f, 1.0f})
        check_coordinates(centre + Vec3{sign * radius, sign * radius, sign * radius}, shape.at("radius"),
                          "a corner of the sphere's bounding box (centre ± radius)");
      std::optional<std::array<Vec3, 3>> uv_axes;
      if (shape.has("uv_axes")) {
        // pbrt-v4's sphere uv about three orthonormal directions (the importer's sphere object axes in world).
        const JsonCursor axes = shape.at("uv_axes");
        if (!axes.is_array() || axes.size() != 3) axes.fail("expected three directions [[x], [y], [z]] (orthonormal)");
        uv_axes.emplace();
        for (size_t k = 0; k < 3; ++k) (*uv_axes)[k] = axes.at(k).vec3();
        for (size_t k = 0; k < 3; ++k)
          for (size_t l = k; l < 3; ++l)
            if (std::abs(dot((*uv_axes)[k], (*uv_axes)[l]) - (k == l ? 1.0f : 0.0f)) > 1e-4f)
              axes.fail("the three directions must be orthonormal (unit length, at right angles) to within 1e-4");
      }
      const int material = material_of(shape, context);
      int light = -1;
      if (const auto emission = shape.find("emission")) {
        if (is_emission_image(*emission))
          emission->at("image").fail("an emissive sphere's emission cannot be an image (a mesh's can: tessellate the "
                                     "sphere, e.g. as a \"mesh\")");
        // An analytic area light (transport/lights/sphere_light.h): sampled in the cone it subtends, one light tree
        // leaf; an amount in lm is spread over its 4πr² (per side).
        const bool two_sided = shape.boolean_or("two_sided", false);
        const double area_m2 = 4.0 * std::numbers::pi * double(radius) * double(radius);
        const LightSpectrum radiance = area_light_emission(*emission, area_m2, two_sided, context);
        scene.lights.push_back(std::make_unique<SphereLight>(centre, radius, radiance, two_sided));
        read_light_group(shape, scene);
        scene.light_names.push_back(emissive_shape_name(shape));
        light = int(scene.lights.size()) - 1;
      } else {
        if (shape.has("two_sided")) shape.at("two_sided").fail("two_sided applies to emissive shapes only");
        if (shape.has("light_group"))
          shape.at("light_group").fail("light_group applies to emissive shapes (and lights) only");
      }
      scene.geometry.add_sphere(centre, radius, material, uv_axes, light);
      continue;
    }
    if (type == "instance") {
      shape.only_keys({"type", "name", "prototype", "transform", "transform_end"});
      const int prototype = prototype_of(shape, context);
      if (const auto motion = motion_of(shape))
        place_moving_instance(prototype, *motion, shape, context, {uint32_t(i), InstanceKey::kNoMatrix});
      else
        place_instance(prototype, parse_transform(shape), shape.has("transform") ? shape.at("transform") : shape,
                       context, {uint32_t(i), InstanceKey::kNoMatrix});
      continue;
    }
    if (type == "instances") {
      // Many placements of one prototype, a matrix each: what the pbrt importer writes for ObjectInstances.
      shape.only_keys({"type", "name", "prototype", "matrices"});
      const int prototype = prototype_of(shape, context);
      const JsonCursor matrices = shape.at("matrices");
      if (!matrices.is_array()) matrices.fail("expected an array of matrices (12 numbers each: three rows of a 3x4 matrix)");
      for (size_t k = 0; k < matrices.size(); ++k) {
        const JsonCursor m = matrices.at(k);
        const Transform object_to_world = matrix_transform(m);
        check_placement(object_to_world, m, "matrix");
        place_instance(prototype, object_to_world, m, context, {uint32_t(i), uint32_t(k)});
      }
      continue;
    }
    check_triangle_shape_keys(shape, type, false);
    if (const auto motion = motion_of(shape)) {
      load_moving_shape(shape, type, *motion, InstanceKey{uint32_t(i), InstanceKey::kNoMatrix}, context);
      continue;
    }
    TriangleMesh mesh = mesh_of(shape, type, context);
    mesh.transform(parse_transform(shape));
    check_mesh_coordinates(mesh, shape);
    // Every key is checked before a shape of only degenerate triangles is dropped, so such a shape cannot hide a
    // typo in its material or emission.
    const int material = material_of(shape, context);
    const auto emission = shape.find("emission");
    const bool two_sided = emission ? shape.boolean_or("two_sided", false) : false;
    // An amount in lm is spread over the area after the transform (scene_light_emission.h).
    std::optional<LightSpectrum> radiance;
    std::optional<EmissionImage> image;
    if (emission && is_emission_image(*emission)) image = area_emission_image(*emission, context);
    else if (emission) radiance.emplace(area_light_emission(*emission, mesh, two_sided, context));
    if (!emission && shape.has("two_sided")) shape.at("two_sided").fail("two_sided applies to emissive shapes only");
    if (!emission && shape.has("light_group"))
      shape.at("light_group").fail("light_group applies to emissive shapes (and lights) only");
    const std::shared_ptr<const AlphaMask> alpha = alpha_of(shape, context);
    scene.degenerate_triangles_removed += mesh.remove_degenerate_triangles();
    if (mesh.triangle_count() == 0) continue;  // only degenerate triangles (counted above)
    count_normals_near_plane(mesh, scene);
    if (emission) {
      // Lights were loaded first, so area lights take the indices after them, in the order of the shapes.
      std::unique_ptr<AreaLight> light;
      if (image) {
        // Each triangle's uvs at its corners, after the degenerate ones went: the map a hit's uv comes from.
        std::vector<std::array<Vec2, 3>> corners(mesh.triangle_count());
        for (size_t k = 0; k < corners.size(); ++k)
          corners[k] = {mesh.uv_at(k, 0.0f, 0.0f), mesh.uv_at(k, 1.0f, 0.0f), mesh.uv_at(k, 0.0f, 1.0f)};
        light = std::make_unique<AreaLight>(mesh.positions, mesh.indices,
                                            TexturedEmission(image->pixels, image->scale, std::move(corners)), two_sided);
      } else {
        light = std::make_unique<AreaLight>(mesh.positions, mesh.indices, *radiance, two_sided);
      }
      scene.lights.push_back(std::move(light));
      read_light_group(shape, scene);
      scene.light_names.push_back(emissive_shape_name(shape));
      scene.geometry.add_mesh(std::move(mesh), material, int(scene.lights.size()) - 1);
    } else {
      scene.geometry.add_mesh(std::move(mesh), material, -1, alpha);
    }
  }
}

void load_prototypes(const JsonCursor& section, LoadContext& context) {
  if (!section.is_object()) section.fail("expected an object of name → array of shapes");
  for (const auto& [name, unused] : section.value().items()) {
    const JsonCursor shapes = section.at(name);
    PrototypeParts parts;
    for (size_t i = 0; i < shapes.size(); ++i) {
      const JsonCursor shape = shapes.at(i);
      const std::string type = shape.at("type").choice({"mesh", "triangles", "quad", "box", "cylinder", "disk"});
      check_triangle_shape_keys(shape, type, true);
      TriangleMesh mesh = mesh_of(shape, type, context);
      mesh.transform(parse_transform(shape));
      add_prototype_part(shape, std::move(mesh), context, parts);
    }
    context.prototype_index[name] = add_prototype(std::move(parts), context);
  }
}

}  // namespace rimu::scene_loading
