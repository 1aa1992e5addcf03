// The scene's geometry in Embree 3: one BVH, built once, queried with the single-ray API.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/image/alpha_mask.h"
#include "render/scene/curve_set.h"
#include "spectral/error.h"
#include "transport/geometry/surface_hit.h"
#include "render/scene/triangle_mesh.h"
#include "transport/geometry/motion_transform.h"
#include "transport/geometry/ray.h"
#include "transport/integrators/ray_queries.h"

namespace rimu {

/// What the alpha filter function needs of a cut-out geometry (EmbreeScene's internals; Embree holds a pointer).
struct EmbreeAlphaFilter {
  const TriangleMesh* mesh;
  std::shared_ptr<const AlphaMask> alpha;
};

/// Owns an Embree device and scene. Errors reported by Embree's callback become exceptions (RenderError) at the
/// call that caused them, so the rest of Rimu sees one error style.
///
/// Usage: add meshes, spheres and instances; commit(); then intersect()/occluded() from any number of threads.
class EmbreeScene final : public RayQueries {
 public:
  EmbreeScene();
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// A world-space triangle mesh. `light` is the emitter index (or -1). Returns the geometry id.
  /// The scene keeps the mesh and Embree reads its positions and indices in place (shared buffers, no copy):
  /// move a mesh in to hold it once.
  /// `alpha`, if given, cuts holes: rays pass where alpha_keeps_hit says so (camera and shadow rays alike, through
  /// Embree's intersection and occlusion filter functions).
  unsigned add_mesh(TriangleMesh mesh, int material, int light, std::shared_ptr<const AlphaMask> alpha = nullptr);
  /// A sphere (Embree's native sphere primitive). Its uv: without `uv_axes`, Rimu's (u = ½ + atan2(n.z, n.x)/2π,
  /// v = polar angle from +y / π); with orthonormal world directions {x, y, z} of the sphere's object axes,
  /// pbrt-v4's (u = φ/2π, φ = atan2(n·y, n·x) in [0, 2π); v = 1 − θ/π, θ the polar angle from z: v = 1 at +z).
  /// `light`: the emitter index of an emissive sphere (transport/lights/sphere_light.h), or -1.
  unsigned add_sphere(Vec3 centre, float radius, int material, const std::optional<std::array<Vec3, 3>>& uv_axes = std::nullopt,
                      int light = -1);

  /// World-space curves (Embree's native Bézier curves of the set's kind; not instanced, not emissive). Hits follow
  /// curve_surface's contract (uv, h across the fibre, ∂p/∂u always set); a ray leaving a fibre passes through it
  /// (is_self_hit, applied by Embree filter functions to camera and shadow rays alike). Move the set in: Embree
  /// reads its points in place. Returns the geometry id.
  unsigned add_curves(CurveSet curves, int material);

  /// A prototype: meshes in object space, shared by instances (no lights inside prototypes). Held once however
  /// many instances refer to it; move the meshes in.
  /// `alphas`: empty, or one cut-out mask (or null) per mesh.
  int add_prototype(std::vector<std::pair<TriangleMesh, int /*material*/>> meshes,
                    const std::vector<std::shared_ptr<const AlphaMask>>& alphas = {});
  /// An instance of a prototype placed by `object_to_world`. Costs ≈ 0.5 KB (Embree's instance geometry and its
  /// share of the top-level BVH, and this scene's record of it), however large the prototype.
  void add_instance(int prototype, const Transform& object_to_world);
  /// An instance that moves while the shutter is open (motion blur): placed by motion.at(ray time). Embree
  /// interpolates matrices linearly between keys, so a rotation is given as keys at most kMotionKeyAngle apart
  /// (MotionTransform::linear_keys), and hits are shaded with the same interpolation of the same keys.
  void add_instance(int prototype, const MotionTransform& motion);
  /// The placement of the instance added `instance`-th (0-based); for a moving one, at shutter open.
  const Transform& instance_to_world(size_t instance) const { return instances_.at(instance).object_to_world; }
  /// A moving instance's placements at equally spaced times from shutter open to close (at least two); nullptr for
  /// an instance that stays put.
  const std::vector<Transform>* instance_motion_keys(size_t instance) const {
    const int m = instances_.at(instance).motion;
    return m < 0 ? nullptr : &motion_keys_[size_t(m)];
  }
  /// Whether anything moves while the shutter is open: only then do camera samples draw a time.
  bool has_motion() const { return !motion_keys_.empty(); }
  /// The largest turn between two keys of a rotating instance, radians (2°): a point 1 m from the axis strays at
  /// most 0.15 mm inside its arc between keys.
  static constexpr double kMotionKeyAngle = 2.0 * 3.14159265358979323846 / 180.0;

  /// Builds the BVH. No geometry may be added afterwards.
  void commit();

  /// Whether hits carry ∂p/∂u, ∂p/∂v (SurfaceHit::dpdu/dpdv; on by default). They cost ≈ 45 instructions per
  /// triangle hit (the uv system's solve), 1.5 % of a Cornell-box sample: a scene whose materials do not read them
  /// turns them off (they are then zero, "unknown").
  void set_surface_tangents(bool on) { surface_tangents_ = on; }
  bool has_surface_tangents() const { return surface_tangents_; }

  /// Closest hit along the ray within [t_min, t_max], or nothing.
  std::optional<SurfaceHit> intersect(const Ray& ray) const override;
  /// True if anything blocks the ray within [t_min, t_max].
  bool occluded(const Ray& ray) const override;

  /// Axis-aligned bounds of everything (after commit()).
  Vec3 bounds_min() const { return bounds_min_; }
  Vec3 bounds_max() const { return bounds_max_; }

  /// Bytes Embree has allocated and not freed (BVHs, its build scratch while building), from its memory monitor.
  int64_t embree_bytes() const { return embree_bytes_.load(); }

 private:
  bool surface_tangents_ = true;
  struct GeometryInfo {
    enum class Kind { mesh, sphere, curves } kind = Kind::mesh;
    int material = -1;
    int light = -1;
    const TriangleMesh* mesh = nullptr;  // owned by meshes_ (kept for positions, normals and uvs)
    Vec3 centre;                         // spheres: the hit point is put back on the sphere from these
    float radius = 0;
    bool pbrt_uv = false;                // spheres: uv about uv_axes (pbrt-v4's convention), else Rimu's
    std::array<Vec3, 3> uv_axes{};
    const CurveSet* curves = nullptr;    // owned by curve_sets_
  };
  struct Prototype {
    RTCScene scene = nullptr;
    std::vector<GeometryInfo> geometries;
    std::vector<std::unique_ptr<TriangleMesh>> meshes;
  };
  struct Instance {
    int prototype;
    Transform object_to_world;
    int motion = -1;  ///< index in motion_keys_, or -1: the instance does not move
  };

  unsigned attach_mesh(RTCScene scene, TriangleMesh& mesh, std::shared_ptr<const AlphaMask> alpha);
  /// Records what top-level geometry `geometry_id` is (slot_of_geometry_).
  void set_slot(unsigned geometry_id, int slot);
  SurfaceHit shade_hit(const RTCRayHit& rh) const;
  void check_error(const char* what) const;

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<GeometryInfo> geometries_;  // the top-level meshes and spheres, found through slot_of_geometry_
  std::vector<std::unique_ptr<TriangleMesh>> meshes_;
  std::vector<Prototype> prototypes_;
  std::vector<Instance> instances_;       // found through slot_of_geometry_
  std::vector<std::vector<Transform>> motion_keys_;  // per moving instance (Instance::motion)
  /// Per top-level geomID: ≥ 0, the index in geometries_; < 0, the instance −1 − value. An int per instance,
  /// where a GeometryInfo apiece cost 80 bytes.
  std::vector<int> slot_of_geometry_;
  Vec3 bounds_min_, bounds_max_;
  mutable std::string last_error_;
  std::atomic<int64_t> embree_bytes_{0};
  std::vector<std::unique_ptr<CurveSet>> curve_sets_;
  std::vector<std::unique_ptr<EmbreeAlphaFilter>> alpha_filters_;  // Embree's filter functions point at these
};

}  // namespace rimu
