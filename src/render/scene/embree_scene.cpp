#include "render/scene/embree_scene.h"
#include "render/scene/curve_self_hit.h"

#include <cmath>
#include <utility>
#include <limits>

#include "render/scene/ray_tally.h"

namespace rimu {
namespace {

void embree_error_callback(void* user, RTCError code, const char* message) {
  auto* last_error = static_cast<std::string*>(user);
  *last_error = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}

// Embree reports every allocation (bytes > 0) and release (bytes < 0) here; allowing all, it only counts.
bool embree_memory_monitor(void* user, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<int64_t>*>(user)->fetch_add(int64_t(bytes));
  return true;
}

// ∂p/∂u, ∂p/∂v of the triangle (a, b, c) in object space. With uvs, the 2×2 system p_i − p_c = (u_i − u_c)·∂p/∂u +
// (v_i − v_c)·∂p/∂v (as pbrt-v4's Triangle::InteractionFromIntersection); without, uv are the default ones
// (TriangleMesh::uv_at), p = a + b1(b − a) + b2(c − a) written in them: barycentrics give ∂p/∂u = b − a, ∂p/∂v = c − a;
// pbrt's (s, t) = (b1 + b2, b2) give p = a + s(b − a) + t(c − b); swapped, (b1 + b2, b1), p = a + s(c − a) + t(b − c).
// Degenerate uvs give zero tangents (MaterialContext: unknown).
std::pair<Vec3, Vec3> surface_tangents(const TriangleMesh& mesh, const uint32_t* tri, Vec3 a, Vec3 b, Vec3 c) {
  if (mesh.uvs.empty()) {
    switch (mesh.default_uvs) {
      case TriangleMesh::DefaultUvs::pbrt: return {b - a, c - b};
      case TriangleMesh::DefaultUvs::pbrt_swapped: return {c - a, b - c};
      case TriangleMesh::DefaultUvs::barycentric: break;
    }
    return {b - a, c - a};
  }
  const Vec2 ta = mesh.uvs[tri[0]], tb = mesh.uvs[tri[1]], tc = mesh.uvs[tri[2]];
  const float du02 = ta.x - tc.x, dv02 = ta.y - tc.y, du12 = tb.x - tc.x, dv12 = tb.y - tc.y;
  const float determinant = du02 * dv12 - dv02 * du12;
  if (!(std::fabs(determinant) > 1e-12f)) return {};
  const Vec3 dp02 = a - c, dp12 = b - c;
  const float inverse = 1.0f / determinant;
  return {(dp02 * dv12 - dp12 * dv02) * inverse, (dp12 * du02 - dp02 * du12) * inverse};
}

RTCRay to_embree(const Ray& ray) {
  RTCRay r;
  r.org_x = ray.origin.x;
  r.org_y = ray.origin.y;
  r.org_z = ray.origin.z;
  r.dir_x = ray.direction.x;
  r.dir_y = ray.direction.y;
  r.dir_z = ray.direction.z;
  r.tnear = ray.t_min;
  r.tfar = ray.t_max;
  r.time = ray.time;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  return r;
}

// Embree calls this for every candidate hit on a cut-out mesh, for intersect and occluded queries alike; clearing
// valid[i] makes Embree carry on past the hit as if the surface were not there.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* filter = static_cast<const EmbreeAlphaFilter*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec2 uv = filter->mesh->uv_at(RTCHitN_primID(args->hit, args->N, i), RTCHitN_u(args->hit, args->N, i),
                               RTCHitN_v(args->hit, args->N, i));
    const Vec3 origin{RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                      RTCRayN_org_z(args->ray, args->N, i)};
    const Vec3 direction{RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                         RTCRayN_dir_z(args->ray, args->N, i)};
    if (!alpha_keeps_hit(filter->alpha->evaluate(uv), origin, direction)) args->valid[i] = 0;
  }
}

// Embree calls this for every candidate hit on a curve set: a ray leaving a fibre must not stop on that fibre
// (is_self_hit: it starts on it, the hit is near; leaves_cylinder: it was transmitted into a tube).
void curve_self_hit_filter(const RTCFilterFunctionNArguments* args) {
  const auto* curves = static_cast<const CurveSet*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3 origin{RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
                      RTCRayN_org_z(args->ray, args->N, i)};
    const Vec3 direction{RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                         RTCRayN_dir_z(args->ray, args->N, i)};
    const uint32_t segment = RTCHitN_primID(args->hit, args->N, i);
    const float t = RTCHitN_u(args->hit, args->N, i), ray_t = RTCRayN_tfar(args->ray, args->N, i);
    if (is_self_hit(*curves, segment, t, origin, ray_t) || leaves_cylinder(*curves, segment, t, origin, direction, ray_t))
      args->valid[i] = 0;
  }
}

RTCGeometryType embree_curve_type(CurveKind kind) {
  switch (kind) {
    case CurveKind::flat: return RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE;
    case CurveKind::cylinder: return RTC_GEOMETRY_TYPE_ROUND_BEZIER_CURVE;
    case CurveKind::ribbon: return RTC_GEOMETRY_TYPE_NORMAL_ORIENTED_BEZIER_CURVE;
  }
  return RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE;
}

}  // namespace

EmbreeScene::EmbreeScene() {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw RenderError("cannot create an Embree device (rtcNewDevice failed)");
  rtcSetDeviceErrorFunction(device_, embree_error_callback, &last_error_);
  rtcSetDeviceMemoryMonitorFunction(device_, embree_memory_monitor, &embree_bytes_);
  scene_ = rtcNewScene(device_);
  // Robust mode: no missed hits at edges shared by triangles, which would leak light through closed meshes.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  check_error("creating the scene");
}

EmbreeScene::~EmbreeScene() {
  for (auto& p : prototypes_)
    if (p.scene) rtcReleaseScene(p.scene);
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeScene::check_error(const char* what) const {
  if (!last_error_.empty()) {
    const std::string message = last_error_ + " (while " + what + ")";
    last_error_.clear();
    throw RenderError(message);
  }
}

unsigned EmbreeScene::attach_mesh(RTCScene scene, TriangleMesh& mesh, std::shared_ptr<const AlphaMask> alpha) {
  // Embree reads the mesh's own arrays (shared buffers): the positions and indices exist once. Vec3 is three
  // packed floats, so the positions are RTC_FORMAT_FLOAT3 with a 12-byte stride. Embree may read a vertex with a
  // 16-byte load, so the last one needs 4 readable bytes after it: one spare element of capacity provides them.
  static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats for Embree's FLOAT3");
  if (mesh.positions.capacity() == mesh.positions.size()) mesh.positions.reserve(mesh.positions.size() + 1);
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.positions.data(), 0,
                             sizeof(Vec3), mesh.positions.size());
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.indices.data(), 0,
                             3 * sizeof(uint32_t), mesh.triangle_count());
  check_error("sharing mesh buffers with Embree");
  if (alpha) {
    alpha_filters_.push_back(std::make_unique<EmbreeAlphaFilter>(EmbreeAlphaFilter{&mesh, std::move(alpha)}));
    rtcSetGeometryUserData(geometry, alpha_filters_.back().get());
    rtcSetGeometryIntersectFilterFunction(geometry, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geometry, alpha_filter);
  }
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  check_error("adding a triangle mesh");
  return id;
}

unsigned EmbreeScene::add_mesh(TriangleMesh mesh, int material, int light, std::shared_ptr<const AlphaMask> alpha) {
  meshes_.push_back(std::make_unique<TriangleMesh>(std::move(mesh)));
  const unsigned id = attach_mesh(scene_, *meshes_.back(), std::move(alpha));
  set_slot(id, int(geometries_.size()));
  geometries_.push_back({GeometryInfo::Kind::mesh, material, light, meshes_.back().get(), Vec3{}, 0.0f});
  return id;
}

unsigned EmbreeScene::add_sphere(Vec3 centre, float radius, int material, const std::optional<std::array<Vec3, 3>>& uv_axes,
                                 int light) {
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* data = static_cast<float*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
  data[0] = centre.x;
  data[1] = centre.y;
  data[2] = centre.z;
  data[3] = radius;
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  check_error("adding a sphere");
  set_slot(id, int(geometries_.size()));
  geometries_.push_back({GeometryInfo::Kind::sphere, material, light, nullptr, centre, radius, uv_axes.has_value(),
                         uv_axes.value_or(std::array<Vec3, 3>{})});
  return id;
}

unsigned EmbreeScene::add_curves(CurveSet curves, int material) {
  curve_sets_.push_back(std::make_unique<CurveSet>(std::move(curves)));
  CurveSet& set = *curve_sets_.back();
  static_assert(sizeof(CurveControlPoint) == 4 * sizeof(float), "a control point must be Embree's FLOAT4 (x, y, z, r)");
  RTCGeometry geometry = rtcNewGeometry(device_, embree_curve_type(set.kind));
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, set.points.data(), 0,
                             sizeof(CurveControlPoint), set.points.size());
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, set.first_point.data(), 0,
                             sizeof(uint32_t), set.first_point.size());
  if (set.kind == CurveKind::ribbon) {
    // Normals are FLOAT3 read like positions (a 16-byte load may pass the last one): one spare element.
    if (set.normals.capacity() == set.normals.size()) set.normals.reserve(set.normals.size() + 1);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3, set.normals.data(), 0,
                               sizeof(Vec3), set.normals.size());
  }
  check_error("sharing curve buffers with Embree");
  // Embree cuts flat curves into linear pieces (4 per segment by default), which bends a long curve's outline away
  // from the Bézier by more than a pixel: pbrt-v4 intersects the curve itself.
  if (set.kind == CurveKind::flat) rtcSetGeometryTessellationRate(geometry, float(curve_tessellation_rate(set)));
  rtcSetGeometryUserData(geometry, &set);
  rtcSetGeometryIntersectFilterFunction(geometry, curve_self_hit_filter);
  rtcSetGeometryOccludedFilterFunction(geometry, curve_self_hit_filter);
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  check_error("adding curves");
  set_slot(id, int(geometries_.size()));
  GeometryInfo info;
  info.kind = GeometryInfo::Kind::curves;
  info.material = material;
  info.curves = &set;
  geometries_.push_back(info);
  return id;
}

int EmbreeScene::add_prototype(std::vector<std::pair<TriangleMesh, int>> meshes,
                               const std::vector<std::shared_ptr<const AlphaMask>>& alphas) {
  Prototype prototype;
  prototype.scene = rtcNewScene(device_);
  rtcSetSceneFlags(prototype.scene, RTC_SCENE_FLAG_ROBUST);
  for (size_t k = 0; k < meshes.size(); ++k) {
    auto& [mesh, material] = meshes[k];
    prototype.meshes.push_back(std::make_unique<TriangleMesh>(std::move(mesh)));
    const unsigned id = attach_mesh(prototype.scene, *prototype.meshes.back(), k < alphas.size() ? alphas[k] : nullptr);
    prototype.geometries.resize(id + 1);
    prototype.geometries[id] = {GeometryInfo::Kind::mesh, material, -1, prototype.meshes.back().get(), Vec3{}, 0.0f};
  }
  rtcCommitScene(prototype.scene);
  check_error("building a prototype's BVH");
  prototypes_.push_back(std::move(prototype));
  return int(prototypes_.size()) - 1;
}

void EmbreeScene::add_instance(int prototype, const Transform& object_to_world) {
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(geometry, prototypes_.at(prototype).scene);
  rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, object_to_world.rows().data());
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  check_error("adding an instance");
  set_slot(id, -1 - int(instances_.size()));
  instances_.push_back({prototype, object_to_world});
}

void EmbreeScene::add_instance(int prototype, const MotionTransform& motion) {
  std::vector<Transform> keys = motion.linear_keys(kMotionKeyAngle);
  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(geometry, prototypes_.at(prototype).scene);
  rtcSetGeometryTimeStepCount(geometry, unsigned(keys.size()));
  for (size_t k = 0; k < keys.size(); ++k)
    rtcSetGeometryTransform(geometry, unsigned(k), RTC_FORMAT_FLOAT3X4_ROW_MAJOR, keys[k].rows().data());
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  check_error("adding a moving instance");
  set_slot(id, -1 - int(instances_.size()));
  instances_.push_back({prototype, motion.start(), int(motion_keys_.size())});
  motion_keys_.push_back(std::move(keys));
}

void EmbreeScene::set_slot(unsigned geometry_id, int slot) {
  if (slot_of_geometry_.size() <= geometry_id) slot_of_geometry_.resize(geometry_id + 1, 0);
  slot_of_geometry_[geometry_id] = slot;
}

void EmbreeScene::commit() {
  rtcCommitScene(scene_);
  check_error("building the BVH");
  RTCBounds b;
  rtcGetSceneBounds(scene_, &b);
  bounds_min_ = {b.lower_x, b.lower_y, b.lower_z};
  bounds_max_ = {b.upper_x, b.upper_y, b.upper_z};
}

std::optional<SurfaceHit> EmbreeScene::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = to_embree(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  tally_traced_ray();
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return shade_hit(rh);
}

bool EmbreeScene::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = to_embree(ray);
  tally_traced_ray();
  rtcOccluded1(scene_, &context, &r);
  return r.tfar == -std::numeric_limits<float>::infinity();
}

SurfaceHit EmbreeScene::shade_hit(const RTCRayHit& rh) const {
  SurfaceHit hit;
  hit.t = rh.ray.tfar;
  const Vec3 origin{rh.ray.org_x, rh.ray.org_y, rh.ray.org_z};
  const Vec3 direction{rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z};
  hit.position = origin + direction * hit.t;
  hit.primitive = rh.hit.primID;

  const GeometryInfo* info = nullptr;
  const Transform* object_to_world = nullptr;
  std::optional<Transform> moved;  // a moving instance's placement at the ray's time, as Embree interpolated it
  if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
    const Instance& instance = instances_[size_t(-1 - slot_of_geometry_[rh.hit.instID[0]])];
    info = &prototypes_[size_t(instance.prototype)].geometries[rh.hit.geomID];
    object_to_world = &instance.object_to_world;
    if (instance.motion >= 0) {
      object_to_world = &moved.emplace(interpolate_keys(motion_keys_[size_t(instance.motion)], rh.ray.time));
    }
  } else {
    info = &geometries_[size_t(slot_of_geometry_[rh.hit.geomID])];
  }
  hit.material = info->material;
  hit.light = info->light;

  // Embree's Ng is unnormalised and, for triangles, is (v1−v0)×(v2−v0)... in object space for instances.
  Vec3 ng{rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
  if (object_to_world) ng = object_to_world->normal(ng);
  hit.geometric_normal = normalize(ng);
  hit.shading_normal = hit.geometric_normal;

  if (info->kind == GeometryInfo::Kind::curves) {
    // Curves are top-level only (no instance transform); their tangents are set whatever surface_tangents_ says,
    // since a fibre's BSDF is built around ∂p/∂u.
    curve_surface(*info->curves, rh.hit.primID, rh.hit.u, origin, direction, hit.t, ng, hit);
    return hit;
  }
  if (info->kind == GeometryInfo::Kind::sphere) {
    // o + t·d carries the rounding of the ray's origin, which can be far larger than the sphere: put the point
    // back on the sphere, so its error is that of the centre and radius.
    const Vec3 n = hit.geometric_normal;
    hit.position = info->centre + n * info->radius;
    hit.position_scale = max_component(abs(info->centre)) + info->radius;
    if (info->pbrt_uv) {
      // pbrt-v4's sphere: p = r·(sin θ cos φ, sin θ sin φ, cos θ) in its object axes, u = φ/2π with φ in [0, 2π),
      // v = (θ − π)/(0 − π) (θ_min = acos(z_min/r) = π, θ_max = 0 for a whole sphere).
      const auto& [ax, ay, az] = info->uv_axes;
      const float a = dot(n, ax), b = dot(n, ay), c = std::fmax(-1.0f, std::fmin(1.0f, dot(n, az)));
      double phi = std::atan2(double(b), double(a));
      if (phi < 0) phi += 2.0 * M_PI;
      hit.uv = {float(phi / (2.0 * M_PI)), float(1.0 - std::acos(c) / M_PI)};
      const float sin_theta = std::sqrt(a * a + b * b);
      if (surface_tangents_ && sin_theta > 1e-6f) {
        // pbrt's ∂p/∂u = 2π·(−y, x, 0), ∂p/∂v = −π·(z cos φ, z sin φ, −r sin θ), in world through the axes.
        const float r = info->radius;
        hit.dpdu = (ax * -b + ay * a) * float(2.0 * M_PI * r);
        hit.dpdv = (ax * (c * a / sin_theta) + ay * (c * b / sin_theta) - az * sin_theta) * float(-M_PI * r);
      }
      return hit;
    }
    // Spherical uv: u = azimuth/2π, v = polar angle/π about +y.
    hit.uv = {float(0.5 + std::atan2(n.z, n.x) / (2.0 * M_PI)), float(std::acos(std::fmax(-1.0f, std::fmin(1.0f, n.y))) / M_PI)};
    // p = c + r·(sin θ cos φ, cos θ, sin θ sin φ) with φ = 2π(u − ½), θ = πv: differentiate. At the poles
    // (sin θ = 0) both vanish or are undefined: left zero.
    const float sin_theta = std::sqrt(n.x * n.x + n.z * n.z);
    if (surface_tangents_ && sin_theta > 1e-6f) {
      const float r = info->radius;
      hit.dpdu = Vec3{-n.z, 0.0f, n.x} * float(2.0 * M_PI * r);
      hit.dpdv = Vec3{n.y * n.x / sin_theta, -sin_theta, n.y * n.z / sin_theta} * float(M_PI * r);
    }
    return hit;
  }
  const TriangleMesh& mesh = *info->mesh;
  const uint32_t* tri = &mesh.indices[3 * size_t(rh.hit.primID)];
  const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
  // The hit point from the triangle's own vertices, not o + t·d: a camera 10 m from a plane makes o + t·d wrong
  // by ~10·2⁻²⁴ m along the normal even where the plane passes through the origin, and continuation rays offset in
  // proportion to |p| would then start behind the plane (self-shadowing rings). Interpolated, the error is a few
  // ulps of the vertices' coordinates (position_scale), however far away the ray came from.
  const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
  Vec3 p = a * w + b * u + c * v;
  float scale = std::fmax(max_component(abs(a)), std::fmax(max_component(abs(b)), max_component(abs(c))));
  if (object_to_world) {
    p = object_to_world->point(p);
    // |M·p − fl(M·p)| ≤ (row sums of |M|)·|p| + |translation|, in units of rounding.
    const std::array<float, 12>& m = object_to_world->rows();
    float row_sum = 0, translation = 0;
    for (int r = 0; r < 3; ++r) {
      row_sum = std::fmax(row_sum, std::fabs(m[4 * r]) + std::fabs(m[4 * r + 1]) + std::fabs(m[4 * r + 2]));
      translation = std::fmax(translation, std::fabs(m[4 * r + 3]));
    }
    scale = row_sum * scale + translation;
  }
  // Degenerate or NaN vertices keep Embree's point (the scene loader refuses non-finite ones; this is a guard).
  if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
    hit.position = p;
    hit.position_scale = scale;
  }
  hit.uv = mesh.uv_at(rh.hit.primID, u, v);
  if (surface_tangents_) {
    const auto [dpdu, dpdv] = surface_tangents(mesh, tri, a, b, c);
    hit.dpdu = object_to_world ? object_to_world->vector(dpdu) : dpdu;
    hit.dpdv = object_to_world ? object_to_world->vector(dpdv) : dpdv;
  }
  const auto has_normal = [&](uint32_t vertex) { return length_squared(mesh.normals[vertex]) > 0.0f; };
  // A corner without a normal (TriangleMesh::normals) makes the triangle flat: pbrt-v4 interpolates the file's NaN
  // there, and a NaN normal falls back to the geometric one.
  if (!mesh.normals.empty() && has_normal(tri[0]) && has_normal(tri[1]) && has_normal(tri[2])) {
    Vec3 n = mesh.normals[tri[0]] * w + mesh.normals[tri[1]] * u + mesh.normals[tri[2]] * v;
    if (object_to_world) n = object_to_world->normal(n);
    const float len = length(n);
    // Interpolated normals can vanish between opposite vertex normals; fall back to the geometric one.
    if (len > 1e-12f && std::isfinite(len)) hit.shading_normal = face_forward(n / len, hit.geometric_normal);
  }
  return hit;
}

}  // namespace rimu
