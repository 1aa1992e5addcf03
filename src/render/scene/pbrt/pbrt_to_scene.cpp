#include "render/scene/pbrt/pbrt_to_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <tuple>

#include "render/scene/pbrt/pbrt_converter.h"
#include "transport/geometry/motion_transform.h"
#include "render/film/film_tile.h"
#include "render/film/spectral_response.h"
#include "spectral/indefinite_article.h"

namespace rimu {

namespace {

// The largest samples per pixel a scene may ask for (the JSON loader's bound on "spp").
constexpr int64_t kMaxSamplesPerPixel = int64_t(1) << 24;

const char* type_word(PbrtParamType t) {
  switch (t) {
    case PbrtParamType::integer: return "integer";
    case PbrtParamType::real: return "float";
    case PbrtParamType::point2: return "point2";
    case PbrtParamType::vector2: return "vector2";
    case PbrtParamType::point3: return "point3";
    case PbrtParamType::vector3: return "vector3";
    case PbrtParamType::normal: return "normal";
    case PbrtParamType::boolean: return "bool";
    case PbrtParamType::string: return "string";
    case PbrtParamType::rgb: return "rgb";
    case PbrtParamType::spectrum: return "spectrum";
    case PbrtParamType::blackbody: return "blackbody";
    case PbrtParamType::texture: return "texture";
  }
  return "?";
}

// pbrt's colour space names → Rimu's.
std::optional<std::string> rimu_colour_space(const std::string& pbrt_name) {
  if (pbrt_name == "srgb") return "srgb-linear";
  if (pbrt_name == "rec2020") return "rec2020";
  if (pbrt_name == "aces2065-1") return "aces2065-1";
  if (pbrt_name == "dci-p3") return "display-p3";  // pbrt's DCI-P3 uses the D65 white: Display P3's primaries
  return std::nullopt;
}

}  // namespace

// ---- PbrtParams ---------------------------------------------------------------------------------------------

PbrtParams::PbrtParams(PbrtConverter& converter, const PbrtStatement& s, std::string context,
                       const std::vector<PbrtParam>* defaults)
    : converter_(converter), statement_(s), context_(std::move(context)) {
  for (const PbrtParam& p : s.params) {
    // pbrt-v4 reads the first of a parameter given twice (ParameterDictionary::lookupSingle) and says nothing;
    // pbrt-v3's files have such repeats (a resolution changed by adding a second line). The later one is listed.
    if (std::any_of(all_.begin(), all_.end(), [&](const PbrtParam* q) { return q->name == p.name; })) {
      converter_.ignore("parameter \"" + p.type_name + " " + p.name + "\" of " + context_ +
                            " given again (pbrt-v4 reads the first)",
                        p.where);
      continue;
    }
    all_.push_back(&p);
  }
  // Attribute defaults apply where the statement does not give the parameter; unused ones are not reported
  // (they are meant for every shape or light, and most use only some of them).
  if (defaults)
    for (const PbrtParam& d : *defaults)
      if (std::none_of(all_.begin(), all_.end(), [&](const PbrtParam* q) { return q->name == d.name; })) {
        all_.push_back(&d);
        used_.insert(d.name);
      }
}

PbrtParams::~PbrtParams() {
  if (std::uncaught_exceptions() > 0) return;
  for (const PbrtParam* p : all_)
    if (!used_.count(p->name))
      converter_.ignore_unused("parameter \"" + p->type_name + " " + p->name + "\" of " + context_, p->where);
}

const PbrtParam* PbrtParams::get(const std::string& name, std::initializer_list<PbrtParamType> types) {
  for (const PbrtParam* p : all_) {
    if (p->name != name) continue;
    used_.insert(name);
    if (std::find(types.begin(), types.end(), p->type) == types.end()) {
      std::string expected;
      for (PbrtParamType t : types) expected += (expected.empty() ? "" : " or ") + std::string(type_word(t));
      throw InputError(p->where, context_ + ": parameter \"" + name + "\" must be of type " + expected + ", not " +
                                     p->type_name);
    }
    return p;
  }
  return nullptr;
}

double PbrtParams::real(const std::string& name, double fallback) {
  const PbrtParam* p = get(name, {PbrtParamType::real});
  if (!p) return fallback;
  if (p->numbers.size() != 1) throw InputError(p->where, context_ + ": \"" + name + "\" takes one number");
  return p->numbers[0];
}

int PbrtParams::integer(const std::string& name, int fallback) {
  const PbrtParam* p = get(name, {PbrtParamType::integer});
  if (!p) return fallback;
  if (p->numbers.size() != 1) throw InputError(p->where, context_ + ": \"" + name + "\" takes one integer");
  return int(p->numbers[0]);
}

bool PbrtParams::boolean(const std::string& name, bool fallback) {
  const PbrtParam* p = get(name, {PbrtParamType::boolean});
  if (!p) return fallback;
  if (p->bools.size() != 1) throw InputError(p->where, context_ + ": \"" + name + "\" takes one value");
  return p->bools[0];
}

std::string PbrtParams::string(const std::string& name, const std::string& fallback) {
  const PbrtParam* p = get(name, {PbrtParamType::string});
  if (!p) return fallback;
  if (p->strings.size() != 1) throw InputError(p->where, context_ + ": \"" + name + "\" takes one string");
  return p->strings[0];
}

std::vector<double> PbrtParams::numbers(const std::string& name, std::initializer_list<PbrtParamType> types) {
  const PbrtParam* p = get(name, types);
  return p ? p->numbers : std::vector<double>{};
}

// ---- the converter ------------------------------------------------------------------------------------------

PbrtConverter::PbrtConverter(SpectralLibrary& library, std::filesystem::path output_directory, bool strict,
                             std::size_t max_generated_triangles, std::size_t max_instances, std::size_t max_shapes,
                             PbrtRgbUpsampler rgb_upsampler)
    : library_(library),
      rgb_upsampler_(rgb_upsampler),
      output_directory_(std::move(output_directory)),
      strict_(strict),
      nits_per_unit_y_(SpectralResponse::from_spec(library, "xyz").luminance_nits_per_unit_y()),
      max_generated_triangles_(max_generated_triangles),
      max_instances_(max_instances),
      max_shapes_(max_shapes) {}

void PbrtConverter::ignore_unused(const std::string& what, const SourceLocation& where) {
  if (!strict_) return ignore(what, where);
  if (!unused_parameter_error_) unused_parameter_error_ = InputError(where, "not supported (--strict): " + what);
}

void PbrtConverter::ignore(const std::string& what, const SourceLocation& where) {
  if (strict_) throw InputError(where, "not supported (--strict): " + what);
  const auto [it, added] = ignored_index_.emplace(what, ignored_.size());
  if (added) ignored_.push_back({what, 0, where});
  ++ignored_[it->second].count;
}

std::string PbrtConverter::path_for_document(const std::filesystem::path& absolute) const {
  std::error_code error;
  const std::filesystem::path relative = std::filesystem::relative(absolute, output_directory_, error);
  return error || relative.empty() ? absolute.string() : relative.generic_string();
}

json PbrtConverter::matrix_rows(const PbrtMatrix& m, const SourceLocation& where) const {
  if (!m.is_finite()) throw InputError(where, "the current transform is not finite (check for huge numbers)");
  if (!m.is_affine()) throw InputError(where, "the current transform is projective; only affine transforms place shapes");
  const double det = m.determinant3();
  if (!(std::abs(det) > 1e-30)) throw InputError(where, "the current transform is singular (determinant 0): it collapses the shape");
  json rows = json::array();
  rows.get_ref<json::array_t&>().reserve(12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) rows.push_back(m.m[i][j]);
  return rows;
}

json PbrtConverter::transform_steps(const PbrtMatrix& m, const SourceLocation& where) const {
  json rows = matrix_rows(m, where);
  if (m.is_identity()) return json();
  return json::array({{{"matrix", std::move(rows)}}});
}

bool PbrtConverter::ctm_moves() const { return state_.ctm.m != state_.ctm_end.m; }

namespace {

Transform to_transform(const PbrtMatrix& m) {
  std::array<float, 12> rows{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) rows[size_t(4 * i + j)] = float(m.m[i][j]);
  bool invertible = false;
  return Transform::from_rows(rows, invertible);
}

PbrtMatrix to_pbrt_matrix(const Transform& t) {
  PbrtMatrix m = PbrtMatrix::identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) m.m[i][j] = t.rows()[size_t(4 * i + j)];
  return m;
}

}  // namespace

std::pair<PbrtMatrix, PbrtMatrix> PbrtConverter::shutter_placements(const PbrtMatrix& start, const PbrtMatrix& end,
                                                                     const SourceLocation& where) {
  const double span = transform_end_time_ - transform_start_time_;
  // pbrt-v4's AnimatedTransform: the fraction of the way from the start time to the end time, clamped.
  const auto fraction = [&](double time) {
    return span > 0 ? std::clamp((time - transform_start_time_) / span, 0.0, 1.0) : 0.0;
  };
  const bool beyond = shutter_open_ < transform_start_time_ || shutter_close_ > transform_end_time_;
  if (beyond && !shutter_beyond_times_listed_) {
    shutter_beyond_times_listed_ = true;
    ignore("a shutter (shutteropen/shutterclose) reaching beyond TransformTimes: pbrt-v4 holds moving objects at "
           "their start or end placement there, Rimu moves them evenly from the one at shutteropen to the one at "
           "shutterclose",
           where);
  }
  const double a = fraction(shutter_open_), b = fraction(shutter_close_);
  if (a == 0.0 && b == 1.0) return {start, end};
  bool valid = false;
  const MotionTransform motion(to_transform(start), to_transform(end), valid);
  return {to_pbrt_matrix(motion.at(float(a))), to_pbrt_matrix(motion.at(float(b)))};
}

PbrtMatrix PbrtConverter::render_from_world_for_instances() const {
  // pbrt-v4's CameraTransform for its default camera-world rendering space: the camera's position at the middle of
  // the TransformTimes (its transform's translation, interpolated linearly) becomes the origin.
  Vec3d p = world_from_camera_->point({0, 0, 0});
  if (world_from_camera_end_) {
    const Vec3d q = world_from_camera_end_->point({0, 0, 0});
    for (int k = 0; k < 3; ++k) p[size_t(k)] = 0.5 * (p[size_t(k)] + q[size_t(k)]);
  }
  return PbrtMatrix::translate(-p[0], -p[1], -p[2]);
}

std::string PbrtConverter::render_space_prototype(const std::string& name, const PbrtMatrix& render_from_world) {
  const std::string copy = name + " (pbrt render space)";
  if (prototypes_.contains(copy)) return copy;
  json shapes = prototypes_[name];
  const Vec3d shift = render_from_world.point({0, 0, 0});
  for (size_t i = 0; i < shapes.size(); ++i) {
    json& shape = shapes[i];
    if (!shape.contains("transform")) shape["transform"] = json::array();
    shape["transform"].push_back({{"translate", shift}});
    // Errors in the copy point at the original's statement.
    const std::string original = "/prototypes/" + name + "/" + std::to_string(i);
    for (size_t k = 0; k < origins_.size(); ++k)
      if (origins_[k].pointer == original) {
        origin("/prototypes/" + copy + "/" + std::to_string(i), origins_[k].where, origins_[k].statement);
        break;
      }
  }
  prototypes_[copy] = std::move(shapes);
  return copy;
}

void PbrtConverter::object_instance(const PbrtStatement& s) {
  const std::string& name = s.strings[0];
  if (ctm_moves()) {
    // A moving instance is a shape of its own (a batch holds still placements). pbrt-v4 interpolates an instance's
    // two placements as seen from its rendering space (by default camera-world: the world moved so that the
    // camera's mid-shutter position is the origin), C⁻¹·M·C with C the translation to that position, and keeps the
    // object's shapes in that space: so a turning instance turns about its origin's image in the shifted space,
    // not about its own origin as a moving shape does. Rimu's instance moves C⁻¹·M, with the prototype's shapes
    // shifted by C⁻¹ (a copy of the prototype): the same placement at every time.
    instance_batch_.reset();
    const PbrtMatrix render_from_world = render_from_world_for_instances();
    const PbrtMatrix world_from_render = *render_from_world.inverse();
    const auto [open, close] = shutter_placements(render_from_world * state_.ctm * world_from_render,
                                                  render_from_world * state_.ctm_end * world_from_render, s.where);
    const PbrtMatrix open_world = mirror_ * world_from_render * open, close_world = mirror_ * world_from_render * close;
    json shape = {{"type", "instance"}, {"prototype", render_space_prototype(name, render_from_world)},
                  {"transform", json::array({{{"matrix", matrix_rows(open_world, s.where)}}})},
                  {"transform_end", json::array({{{"matrix", matrix_rows(close_world, s.where)}}})}};
    origin("/shapes/" + std::to_string(shapes_.size()), s.where, "ObjectInstance \"" + name + "\"");
    shapes_.push_back(std::move(shape));
    return;
  }
  json matrix = matrix_rows(world_from_object(), s.where);
  // Consecutive instances of one object from one file are one "instances" shape, a 3×4 matrix each, with one
  // origin holding a line per instance: 25,000 placed buddhas took 2 KB each as a shape object and an origin apiece.
  if (instance_batch_ && instance_batch_->shape + 1 == shapes_.size() && instance_batch_->prototype == name &&
      origins_[instance_batch_->origin].where.file == s.where.file) {
    shapes_.back()["matrices"].push_back(std::move(matrix));
    origins_[instance_batch_->origin].element_lines.push_back(s.where.line);
    return;
  }
  instance_batch_ = InstanceBatch{name, shapes_.size(), origins_.size()};
  origin("/shapes/" + std::to_string(shapes_.size()), s.where, "ObjectInstance \"" + name + "\"");
  origins_.back().element_lines.push_back(s.where.line);
  shapes_.push_back({{"type", "instances"}, {"prototype", name}, {"matrices", json::array({std::move(matrix)})}});
}

void PbrtConverter::statement(const PbrtStatement& s) {
  unused_parameter_error_.reset();
  statement_body(s);
  if (unused_parameter_error_) throw InputError(*unused_parameter_error_);
}

void PbrtConverter::statement_body(const PbrtStatement& s) {
  const std::string& k = s.keyword;
  // pbrt-v4 keeps two CTMs, at TransformTimes' start and end; ActiveTransform chooses which ones statements change.
  const auto set = [&](const PbrtMatrix& m) {
    if (state_.active_transforms & 1) state_.ctm = m;
    if (state_.active_transforms & 2) state_.ctm_end = m;
  };
  const auto apply = [&](const PbrtMatrix& t) {
    if (state_.active_transforms & 1) state_.ctm = state_.ctm * t;
    if (state_.active_transforms & 2) state_.ctm_end = state_.ctm_end * t;
  };
  const auto require_world = [&](bool inside) {
    if (world_begun_ != inside)
      throw InputError(s.where, k + (inside ? " is only allowed after WorldBegin" : " is only allowed before WorldBegin"));
  };
  if (k == "Identity") {
    set(PbrtMatrix::identity());
  } else if (k == "Translate") {
    apply(PbrtMatrix::translate(s.numbers[0], s.numbers[1], s.numbers[2]));
  } else if (k == "Scale") {
    apply(PbrtMatrix::scale(s.numbers[0], s.numbers[1], s.numbers[2]));
  } else if (k == "Rotate") {
    if (s.numbers[1] == 0 && s.numbers[2] == 0 && s.numbers[3] == 0) throw InputError(s.where, "Rotate: the axis is (0, 0, 0)");
    apply(PbrtMatrix::rotate(s.numbers[0], s.numbers[1], s.numbers[2], s.numbers[3]));
  } else if (k == "LookAt") {
    const auto m = PbrtMatrix::look_at({s.numbers[0], s.numbers[1], s.numbers[2]}, {s.numbers[3], s.numbers[4], s.numbers[5]},
                                       {s.numbers[6], s.numbers[7], s.numbers[8]});
    if (!m) throw InputError(s.where, "LookAt: the eye equals the target, or the up vector is zero or parallel to the view direction");
    apply(*m);
  } else if (k == "Transform" || k == "ConcatTransform") {
    const PbrtMatrix m = PbrtMatrix::from_pbrt_numbers(s.numbers.data());
    if (k == "Transform") {
      set(m);
    } else {
      apply(m);
    }
  } else if (k == "CoordinateSystem") {
    named_coordinate_systems_[s.strings[0]] = {state_.ctm, state_.ctm_end};
  } else if (k == "CoordSysTransform") {
    const auto it = named_coordinate_systems_.find(s.strings[0]);
    if (it == named_coordinate_systems_.end()) throw InputError(s.where, "CoordSysTransform: no coordinate system named \"" + s.strings[0] + "\"");
    std::tie(state_.ctm, state_.ctm_end) = it->second;
  } else if (k == "ActiveTransform") {
    const std::string& which = s.strings[0];
    if (which != "StartTime" && which != "EndTime" && which != "All")
      throw InputError(s.where, "ActiveTransform: expected StartTime, EndTime or All, not " + which);
    state_.active_transforms = which == "StartTime" ? 1 : which == "EndTime" ? 2 : 3;
  } else if (k == "TransformTimes") {
    require_world(false);
    if (!(s.numbers[1] >= s.numbers[0]) || !std::isfinite(s.numbers[0]) || !std::isfinite(s.numbers[1]))
      throw InputError(s.where, "TransformTimes: the end time must be finite and not before the start time");
    transform_start_time_ = s.numbers[0];
    transform_end_time_ = s.numbers[1];
  } else if (k == "ReverseOrientation") {
    state_.reverse_orientation = !state_.reverse_orientation;
  } else if (k == "AttributeBegin" || k == "TransformBegin") {
    stack_.push_back({k == "AttributeBegin" ? 'a' : 't', state_});
  } else if (k == "AttributeEnd" || k == "TransformEnd") {
    const char kind = k == "AttributeEnd" ? 'a' : 't';
    if (stack_.empty()) throw InputError(s.where, k + " without a matching " + (kind == 'a' ? "AttributeBegin" : "TransformBegin"));
    if (stack_.back().first != kind)
      throw InputError(s.where, k + " closes " + with_article(stack_.back().first == 'a' ? "AttributeBegin" : stack_.back().first == 't' ? "TransformBegin" : "ObjectBegin"));
    if (kind == 'a') {
      state_ = stack_.back().second;
    } else {
      state_.ctm = stack_.back().second.ctm;  // TransformEnd restores the transform only
      state_.ctm_end = stack_.back().second.ctm_end;
    }
    stack_.pop_back();
  } else if (k == "Attribute") {
    const std::string& target = s.strings[0];
    if (target != "shape" && target != "light" && target != "material" && target != "medium" && target != "texture")
      throw InputError(s.where, "Attribute: unknown target \"" + target + "\"; expected shape, light, material, medium or texture");
    if (target == "medium" || target == "texture") {
      ignore("Attribute \"" + target + "\" (media and procedural textures are not imported)", s.where);
      return;
    }
    for (const PbrtParam& p : s.params) state_.attributes[target].push_back(p);
  } else if (k == "ColorSpace") {
    const auto cs = rimu_colour_space(s.strings[0]);
    if (!cs) throw InputError(s.where, "ColorSpace: unknown colour space \"" + s.strings[0] + "\"; expected srgb, rec2020, aces2065-1 or dci-p3");
    state_.colour_space = *cs;
  } else if (k == "Option") {
    ignore("Option \"" + s.params[0].type_name + " " + s.params[0].name + "\"", s.where);
  } else if (k == "Camera") {
    require_world(false);
    const auto world_from_camera = state_.ctm.inverse();
    if (!world_from_camera) throw InputError(s.where, "Camera: the camera transform is singular");
    world_from_camera_ = *world_from_camera;
    camera_where_ = s.where;
    PbrtMatrix world_from_camera_end = *world_from_camera;
    if (ctm_moves()) {
      // A moving camera: pbrt-v4 animates its transform between the two CTMs as it does a shape's.
      const auto end = state_.ctm_end.inverse();
      if (!end)
        throw InputError(s.where, "Camera: the camera transform at the end time (ActiveTransform EndTime) is singular");
      world_from_camera_end_ = world_from_camera_end = *end;
    }
    named_coordinate_systems_["camera"] = {*world_from_camera, world_from_camera_end};
    PbrtParams p(*this, s, "Camera \"" + s.strings[0] + "\"");
    // pbrt's camera medium is the outside medium in effect at Camera (docs/pbrt-import.md, "Media").
    camera_medium_ = state_.outside_medium;
    camera_medium_where_ = s.where;
    orthographic_ = s.strings[0] == "orthographic";
    spherical_ = s.strings[0] == "spherical";
    if (s.strings[0] != "perspective" && !orthographic_ && !spherical_)
      ignore("Camera \"" + s.strings[0] + "\" (rendered as perspective)", s.where);
    if (spherical_) {
      // pbrt-v4's SphericalCamera: uv = pFilm / resolution; equirectangular: θ = π v, φ = 2π u, the direction
      // (sin θ cos φ, sin θ sin φ, cos θ); equal-area: EqualAreaSquareToSphere(uv); then y and z swapped, in camera
      // space (whose axes are Rimu's camera axes after the importer's mirror). Rimu's mappings put the image centre
      // on the view axis; the frame turns them into pbrt's: equirectangular, pbrt's direction is (−c.z, c.y, −c.x)
      // of Rimu's c (a mirror: pbrt's panorama runs right to left), equal-area (c.x, c.z, −c.y).
      const std::string mapping = p.string("mapping", "equalarea");
      if (mapping != "equalarea" && mapping != "equirectangular")
        throw InputError(s.where, "Camera \"spherical\": \"mapping\" must be \"equalarea\" or \"equirectangular\", not \"" +
                                      mapping + "\"");
      camera_shutter(p);
      p.real("lensradius", 0.0);  // read and unused by pbrt-v4's spherical camera too
      p.real("focaldistance", 1e30);
      camera_ = json::object();
      camera_["type"] = "spherical";
      if (mapping == "equirectangular") {
        camera_["mapping"] = "equirectangular";
        camera_["frame"] = {{0, 0, -1}, {0, 1, 0}, {-1, 0, 0}};
      } else {
        camera_["mapping"] = "equal_area_octahedral";
        camera_["frame"] = {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}};
      }
    } else {
      if (!orthographic_) {
        fov_deg_ = p.real("fov", 90.0);
        if (!(fov_deg_ > 0 && fov_deg_ < 180)) throw InputError(s.where, "Camera: \"fov\" must be in (0, 180) degrees");
      }
      camera_shutter(p);
      const double lens_radius = p.real("lensradius", 0.0);
      const double focal_distance = p.real("focaldistance", 1e6);
      camera_ = json::object();
      if (lens_radius > 0) {
        camera_["type"] = "thin_lens";
        camera_["lens_radius"] = lens_radius;
        camera_["focus_distance"] = focal_distance;
      }
      if (orthographic_) camera_["type"] = "orthographic";
    }
  } else if (k == "Film") {
    require_world(false);
    film(s);
  } else if (k == "Sampler") {
    require_world(false);
    PbrtParams p(*this, s, "Sampler \"" + s.strings[0] + "\"");
    // In 64 bits: xsamples × ysamples of two large integers overflows an int. The bound is the JSON loader's.
    int64_t spp = p.integer("pixelsamples", 16);
    if (s.strings[0] == "stratified") {
      spp = int64_t(p.integer("xsamples", 4)) * p.integer("ysamples", 4);
      p.boolean("jitter", true);
    }
    if (spp < 1 || spp > kMaxSamplesPerPixel)
      throw InputError(s.where, "Sampler: the sample count must be 1-" + std::to_string(kMaxSamplesPerPixel) + ", not " +
                                    std::to_string(spp));
    integrator_["spp"] = spp;
    if (s.strings[0] == "independent") integrator_["sampler"] = "independent";
    if (const PbrtParam* seed = p.get("seed", {PbrtParamType::integer})) integrator_["seed"] = std::max(0, int(seed->numbers[0]));
    p.string("randomization", "");  // Rimu's Sobol' is always Owen-scrambled
  } else if (k == "Integrator") {
    require_world(false);
    PbrtParams p(*this, s, "Integrator \"" + s.strings[0] + "\"");
    const std::string& type = s.strings[0];
    if (type == "bdpt") {
      // Rimu's bidirectional path tracer (transport/integrators/bidirectional_path_integrator.h); where it cannot
      // run (media, an orthographic camera) the path tracer with light-traced caustics stands in.
      integrator_["method"] = "bidirectional";
      integrator_["caustics"] = "light_tracing";
    } else if (type == "sppm") {
      // Photon mapping: Rimu's vertex connection and merging (transport/integrators/vertex_merging.h), whose merges
      // are SPPM's photon lookups, with pbrt's initial search radius; where it cannot run (media, an orthographic
      // camera), the path tracer with light-traced caustics.
      integrator_["method"] = "vcm";
      integrator_["merge_radius"] = p.real("radius", 1.0);
      integrator_["caustics"] = "light_tracing";
      if (p.get("photonsperiteration", {PbrtParamType::integer}))
        ignore("Integrator \"sppm\" \"photonsperiteration\" (Rimu traces one light subpath per pixel per pass)", s.where);
    } else if (type == "mlt") {
      // Metropolis light transport: Rimu's runs over its path tracer in primary sample space (Kelemen et al. 2002;
      // render/metropolis_renderer.h), pbrt-v4's over bidirectional path tracing (multiplexed MLT); pbrt's chains,
      // sigma, large-step probability, bootstrap paths and mutations per pixel carry over.
      integrator_["method"] = "metropolis";
      const int chains = p.integer("chains", 1000);
      const double sigma = p.real("sigma", 0.01), large = p.real("largestepprobability", 0.3);
      if (chains < 1 || chains > (1 << 24))
        throw InputError(s.where, "Integrator \"mlt\": \"chains\" must be 1-16777216, not " + std::to_string(chains));
      if (!(sigma >= 1e-5 && sigma <= 0.5))
        throw InputError(s.where, "Integrator \"mlt\": \"sigma\" must be in [1e-5, 0.5]");
      if (!(large >= 0.0 && large <= 1.0))
        throw InputError(s.where, "Integrator \"mlt\": \"largestepprobability\" must be in [0, 1]");
      integrator_["metropolis"] = {{"chains", chains}, {"sigma", sigma}, {"large_step_probability", large}};
      metropolis_bootstrap_ = double(p.integer("bootstrapsamples", 100000));
      metropolis_spp_ = p.integer("mutationsperpixel", 100);
      if (metropolis_spp_ < 1 || metropolis_spp_ > kMaxSamplesPerPixel)
        throw InputError(s.where, "Integrator \"mlt\": \"mutationsperpixel\" must be 1-" +
                                      std::to_string(kMaxSamplesPerPixel) + ", not " + std::to_string(metropolis_spp_));
      if (metropolis_bootstrap_ < 1.0)
        throw InputError(s.where, "Integrator \"mlt\": \"bootstrapsamples\" must be at least 1");
    } else if (type == "lightpath") {
      // Light tracing: what a path tracer misses most in such scenes is caustics (a lamp through glass or water);
      // Rimu light-traces those (transport/integrators/caustic_light_tracer.h) and path-traces the rest.
      integrator_["caustics"] = "light_tracing";
      ignore("Integrator \"" + type + "\" (rendered with Rimu's path tracer, caustics light-traced)", s.where);
    } else if (type != "path" && type != "volpath") {
      ignore("Integrator \"" + type + "\" (rendered with Rimu's path tracer)", s.where);
    }
    const int max_depth = p.integer("maxdepth", 5);
    if (max_depth < 0) throw InputError(s.where, "Integrator: \"maxdepth\" must be >= 0");
    integrator_["max_depth"] = max_depth;
  } else if (k == "PixelFilter") {
    require_world(false);
    PbrtParams p(*this, s, "PixelFilter \"" + s.strings[0] + "\"");
    const std::string& type = s.strings[0];
    if (type == "gaussian" || type == "box" || type == "triangle") {
      // pbrt-v4's default radii: box 0.5, gaussian 1.5, triangle 2.
      const double fallback = type == "box" ? 0.5 : type == "triangle" ? 2.0 : 1.5;
      const double rx = p.real("xradius", fallback), ry = p.real("yradius", fallback);
      if (rx != ry) ignore("PixelFilter with xradius != yradius (the larger is used)", s.where);
      film_["filter"] = {{"type", type}, {"radius", std::max(rx, ry)}};
      if (type == "gaussian") film_["filter"]["sigma"] = p.real("sigma", 0.5);
    } else {
      ignore("PixelFilter \"" + type + "\" (Rimu's Gaussian of radius 1.5 is used)", s.where);
    }
  } else if (k == "Accelerator") {
    ignore("Accelerator (Rimu always builds Embree's BVH)", s.where);
  } else if (k == "WorldBegin") {
    require_world(false);
    world_begun_ = true;
    state_.ctm = state_.ctm_end = PbrtMatrix::identity();
    state_.active_transforms = 3;
    named_coordinate_systems_["world"] = {state_.ctm, state_.ctm_end};
    if (world_from_camera_) {
      // pbrt's camera space has image-right along +x = up × forward; Rimu's has forward × up (docs/pbrt-import.md).
      // Where they disagree the world is mirrored in the plane of the view direction and image-up, which leaves
      // the camera where it is and shows the image pbrt shows.
      const PbrtMatrix& c = *world_from_camera_;
      const Vec3d o = c.point({0, 0, 0}), f = c.vector({0, 0, 1}), u = c.vector({0, 1, 0}), r = c.vector({1, 0, 0});
      const Vec3d rimu_right = {f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]};
      const double len = std::sqrt(rimu_right[0] * rimu_right[0] + rimu_right[1] * rimu_right[1] + rimu_right[2] * rimu_right[2]);
      if (len > 0 && rimu_right[0] * r[0] + rimu_right[1] * r[1] + rimu_right[2] * r[2] < 0) {
        const Vec3d n = {rimu_right[0] / len, rimu_right[1] / len, rimu_right[2] / len};
        // Householder reflection about the plane through o with normal n: x → x − 2 n (n·(x − o)).
        PbrtMatrix h = PbrtMatrix::identity();
        const double no = n[0] * o[0] + n[1] * o[1] + n[2] * o[2];
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) h.m[i][j] -= 2 * n[i] * n[j];
          h.m[i][3] = 2 * n[i] * no;
        }
        mirror_ = h;
      }
    }
  } else if (k == "WorldEnd") {
    // pbrt-v3's end marker; pbrt-v4 ends the world at the end of the file.
  } else if (k == "Shape") {
    require_world(true);
    if (++shapes_read_ > max_shapes_)
      throw InputError(s.where, "Shape: the scene has more than " + std::to_string(max_shapes_) +
                                    " Shape statements (counting each read of an included file), beyond the "
                                    "importer's limit (PbrtImportOptions::max_shapes; docs/pbrt-import.md, \"Limits\")");
    shape(s);
  } else if (k == "Material") {
    require_world(true);
    state_.material = material(s, s.strings[0], "Material \"" + s.strings[0] + "\"");
  } else if (k == "MakeNamedMaterial") {
    require_world(true);
    const std::string& name = s.strings[0];
    std::string type;
    if (const PbrtParam* t = s.find("type"); t && t->type == PbrtParamType::string && t->strings.size() == 1) type = t->strings[0];
    if (type.empty()) throw InputError(s.where, "MakeNamedMaterial \"" + name + "\": needs \"string type\"");
    if (named_materials_.count(name)) throw InputError(s.where, "MakeNamedMaterial: \"" + name + "\" is already defined");
    named_materials_.insert(name);
    material(s, type, "MakeNamedMaterial \"" + name + "\"");
  } else if (k == "NamedMaterial") {
    require_world(true);
    // pbrt-v4 looks named materials up only after the whole file is read, so a scene may name one before its
    // MakeNamedMaterial (contemporary-bathroom does, for its lights): checked in finish().
    if (!named_materials_.count(s.strings[0])) forward_materials_.emplace(s.strings[0], s.where);
    state_.material = s.strings[0];
  } else if (k == "Texture") {
    texture(s);
  } else if (k == "LightSource") {
    require_world(true);
    light_source(s);
  } else if (k == "AreaLightSource") {
    require_world(true);
    if (s.strings[0] != "diffuse") {
      ignore("AreaLightSource \"" + s.strings[0] + "\"", s.where);
      state_.area_light.reset();
    } else {
      state_.area_light = s;
    }
  } else if (k == "MakeNamedMedium") {
    make_named_medium(s);
  } else if (k == "MediumInterface") {
    state_.inside_medium = s.strings[0];
    state_.outside_medium = s.strings.size() > 1 ? s.strings[1] : s.strings[0];
    state_.medium_interface_where = s.where;
  } else if (k == "ObjectBegin") {
    require_world(true);
    if (object_) throw InputError(s.where, "ObjectBegin inside ObjectBegin \"" + *object_ + "\"");
    if (prototypes_.contains(s.strings[0])) throw InputError(s.where, "ObjectBegin: \"" + s.strings[0] + "\" is already defined");
    stack_.push_back({'o', state_});
    object_ = s.strings[0];
    object_where_ = s.where;
    prototypes_[*object_] = json::array();
  } else if (k == "ObjectEnd") {
    if (!object_ || stack_.empty() || stack_.back().first != 'o') throw InputError(s.where, "ObjectEnd without a matching ObjectBegin");
    state_ = stack_.back().second;
    stack_.pop_back();
    object_.reset();
  } else if (k == "ObjectInstance") {
    require_world(true);
    if (object_) {
      ignore("ObjectInstance inside ObjectBegin (nested instancing)", s.where);
      return;
    }
    if (!prototypes_.contains(s.strings[0])) throw InputError(s.where, "ObjectInstance: no object named \"" + s.strings[0] + "\"");
    if (prototypes_[s.strings[0]].empty()) return;  // nothing Rimu could import in it (already reported)
    if (const PbrtMatrix m = world_from_object(); m.is_finite() && m.is_affine() && !(std::abs(m.determinant3()) > 1e-30)) {
      ignore("ObjectInstance under a singular transform (pbrt-v4 renders it flattened; left out)", s.where);  // as Shape
      return;
    }
    if (++instances_ > max_instances_)
      throw InputError(s.where, "ObjectInstance: the scene places more than " + std::to_string(max_instances_) +
                                    " instances, beyond the importer's limit (PbrtImportOptions::max_instances; "
                                    "docs/pbrt-import.md, \"Limits\")");
    // A reference to the prototype and its transform: an instance costs its bytes, never a copy of the object.
    object_instance(s);
  } else {
    ignore(k, s.where);
  }
}

void PbrtConverter::film_crop(PbrtParams& p, const PbrtStatement& s) {
  // pbrt-v4 (FilmBaseParameters): "cropwindow" [x0 x1 y0 y1] in [0, 1] gives the pixels ceil(res·x0) ≤ x <
  // ceil(res·x1) (likewise y) and wins over "pixelbounds" [x0 x1 y0 y1]; both are clamped to the image.
  const std::vector<double> window = p.numbers("cropwindow", {PbrtParamType::real});
  const std::vector<double> bounds = p.numbers("pixelbounds", {PbrtParamType::integer});
  if (window.empty() && bounds.empty()) return;
  int x0 = 0, x1 = width_, y0 = 0, y1 = height_;
  CropWindow crop_window;
  if (!window.empty()) {
    if (window.size() != 4) throw InputError(s.where, "Film: \"cropwindow\" takes 4 numbers [x0 x1 y0 y1], not " + std::to_string(window.size()));
    if (!bounds.empty()) ignore("Film \"pixelbounds\" together with \"cropwindow\" (the crop window is used, as in pbrt)", s.where);
    const auto clamp01 = [](double v) { return std::clamp(v, 0.0, 1.0); };
    crop_window = {clamp01(std::min(window[0], window[1])), clamp01(std::min(window[2], window[3])),
                   clamp01(std::max(window[0], window[1])), clamp01(std::max(window[2], window[3]))};
    const PixelBounds pixels = crop_window.pixels(width_, height_);
    x0 = pixels.x0, y0 = pixels.y0, x1 = pixels.x1, y1 = pixels.y1;
  } else {
    if (bounds.size() != 4) throw InputError(s.where, "Film: \"pixelbounds\" takes 4 integers [x0 x1 y0 y1], not " + std::to_string(bounds.size()));
    x0 = std::max(0, int(bounds[0]));
    x1 = std::min(width_, int(bounds[1]));
    y0 = std::max(0, int(bounds[2]));
    y1 = std::min(height_, int(bounds[3]));
    if (x0 != int(bounds[0]) || x1 != int(bounds[1]) || y0 != int(bounds[2]) || y1 != int(bounds[3]))
      ignore("Film \"pixelbounds\" beyond the image (clamped, as in pbrt)", s.where);
  }
  if (x1 <= x0 || y1 <= y0)
    throw InputError(s.where, "Film: the crop window or pixel bounds select no pixels (x " + std::to_string(x0) + "-" + std::to_string(x1) +
                                  ", y " + std::to_string(y0) + "-" + std::to_string(y1) + ")");
  if (!window.empty()) {
    // Kept as fractions, so that `rimu --resolution` crops the same part of the picture (pbrt-v4 applies the
    // window to whatever resolution it renders at); the pixels above are what it selects at the file's own.
    if (crop_window != CropWindow{})
      film_["crop_window"] = {crop_window.x0, crop_window.y0, crop_window.x1, crop_window.y1};
  } else if (x0 != 0 || y0 != 0 || x1 != width_ || y1 != height_) {
    film_["crop"] = {x0, y0, x1, y1};
  }
}

json PbrtConverter::finish(const std::string& main_file) {
  // As pbrt-v4 (a graphics state still pushed at the end of the files is an error): without it every shape after
  // the ObjectBegin would silently become part of the object.
  if (object_)
    throw InputError(object_where_, "ObjectBegin \"" + *object_ +
                                        "\" has no ObjectEnd: the scene's files end inside the object's definition");
  if (!world_from_camera_) throw InputError({main_file, 0, ""}, "the scene has no Camera statement before WorldBegin");
  for (const auto& [name, where] : forward_materials_) {
    if (!named_materials_.count(name)) {
      std::string defined;
      for (const std::string& n : named_materials_) defined += (defined.empty() ? "" : ", ") + n;
      throw InputError(where, "NamedMaterial: no material named \"" + name + "\"; defined: " + (defined.empty() ? "none" : defined));
    }
    // Shapes that used it before its definition were written as ordinary surfaces: an "interface" (no surface,
    // left out or index-matched by what it bounds) cannot be undone at the end.
    if (interface_materials_.count(name))
      throw InputError(where, "NamedMaterial: \"" + name + "\" is an \"interface\" material defined after shapes use it; "
                              "Rimu needs an interface material's MakeNamedMaterial before its first use");
  }
  // pbrt's fov spans the shorter image axis; Rimu's vertical_fov_deg always spans the height.
  double vertical_fov_deg = fov_deg_;
  if (width_ < height_) {
    const double half = fov_deg_ * M_PI / 360.0;
    vertical_fov_deg = 2.0 * std::atan(std::tan(half) * double(height_) / double(width_)) * 180.0 / M_PI;
  }
  PbrtMatrix c = *world_from_camera_;
  json camera = camera_.is_null() ? json::object() : camera_;
  if (world_from_camera_end_) {
    // A moving camera: where it is at shutteropen and shutterclose, in the world as mirrored (the mirror's plane
    // passes through the camera at the start only).
    const auto [open, close] = shutter_placements(mirror_ * c, mirror_ * *world_from_camera_end_, camera_where_);
    c = open;
    const Vec3d o = close.point({0, 0, 0}), f = close.vector({0, 0, 1}), u = close.vector({0, 1, 0});
    camera["from_end"] = o;
    camera["to_end"] = Vec3d{o[0] + f[0], o[1] + f[1], o[2] + f[2]};
    camera["up_end"] = u;
  }
  const Vec3d o = c.point({0, 0, 0}), f = c.vector({0, 0, 1}), u = c.vector({0, 1, 0});
  camera["from"] = o;
  camera["to"] = Vec3d{o[0] + f[0], o[1] + f[1], o[2] + f[2]};
  camera["up"] = u;
  if (spherical_) {
    // no field of view
  } else if (orthographic_) {
    // pbrt's default screen window spans [-1, 1] camera-space units along the shorter image axis; camera space is
    // scaled like the world when the camera transform scales (|up| is the world length of one camera unit).
    const double camera_unit_m = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    camera["height"] = (width_ >= height_ ? 2.0 : 2.0 * double(height_) / double(width_)) * camera_unit_m;
  } else {
    camera["vertical_fov_deg"] = vertical_fov_deg;
  }
  finish_exposure(camera);
  if (film_.find("resolution") == film_.end()) film_["resolution"] = {width_, height_};
  if (integrator_.find("max_depth") == integrator_.end()) integrator_["max_depth"] = 5;
  if (integrator_.find("spp") == integrator_.end()) integrator_["spp"] = 16;
  if (metropolis_spp_ > 0) {
    integrator_["spp"] = metropolis_spp_;
    const double pixels = double(width_) * double(height_);
    integrator_["metropolis"]["bootstrap_per_pixel"] = std::clamp(metropolis_bootstrap_ / pixels, 1e-3, 1e4);
  }
  // Moved, not copied: a scene of a million instances holds a million shapes here (copying took a tenth of its
  // import and as much memory again). The converter is done after finish().
  json document = {{"description", "imported from the pbrt-v4 file " + std::filesystem::path(main_file).filename().string()},
                   {"camera", camera}, {"film", film_}, {"integrator", integrator_}};
  document["materials"] = std::move(materials_);
  document["lights"] = std::move(lights_);
  document["shapes"] = std::move(shapes_);
  finish_media();
  if (!media_.empty()) {
    document["media"] = std::move(media_);
    // pbrt-v4's volpath counts scattering in media towards "maxdepth" as it counts surface bounces.
    document["integrator"]["max_depth_includes_media"] = true;
  }
  json prototypes = json::object();
  for (auto& [name, shapes] : prototypes_.items())
    if (!shapes.empty()) prototypes[name] = std::move(shapes);
  if (!prototypes.empty()) document["prototypes"] = std::move(prototypes);  // moved: objects hold inline meshes
  return document;
}

// ---- entry points -------------------------------------------------------------------------------------------

PbrtImport import_pbrt_text(const std::string& text, const std::string& file, const std::filesystem::path& directory,
                            SpectralLibrary& library, const PbrtImportOptions& options) {
  PbrtConverter converter(library, options.output_directory.empty() ? directory : options.output_directory, options.strict,
                          options.max_generated_triangles, options.max_instances, options.max_shapes, options.rgb_upsampler);
  parse_pbrt_text(text, file, directory, [&](const PbrtStatement& s) { converter.statement(s); }, options.parse_limits);
  PbrtImport result;
  result.document = converter.finish(file);
  result.ignored = converter.ignored();
  result.origins = converter.take_origins();
  return result;
}

PbrtImport import_pbrt(const std::filesystem::path& file, SpectralLibrary& library, const PbrtImportOptions& options) {
  const std::filesystem::path directory = std::filesystem::absolute(file).parent_path();
  PbrtConverter converter(library, options.output_directory.empty() ? directory : std::filesystem::absolute(options.output_directory),
                          options.strict, options.max_generated_triangles, options.max_instances, options.max_shapes, options.rgb_upsampler);
  parse_pbrt_file(file, [&](const PbrtStatement& s) { converter.statement(s); }, options.parse_limits);
  PbrtImport result;
  result.document = converter.finish(file.string());
  result.ignored = converter.ignored();
  result.origins = converter.take_origins();
  return result;
}

std::optional<InputError> at_pbrt_origin(const InputError& error, const std::vector<PbrtOrigin>& origins) {
  const std::string& key = error.where().key;
  const PbrtOrigin* best = nullptr;
  for (const PbrtOrigin& o : origins)
    if (key.compare(0, o.pointer.size(), o.pointer) == 0 && (key.size() == o.pointer.size() || key[o.pointer.size()] == '/'))
      if (!best || o.pointer.size() > best->pointer.size()) best = &o;
  if (!best) return std::nullopt;
  SourceLocation where = best->where;
  if (!best->element_lines.empty()) {
    // "/shapes/3/matrices/7…": the eighth ObjectInstance of the batch; "/shapes/3/counts/7": its eighth curve.
    for (const char* member : {"/matrices/", "/counts/"}) {
      const std::string elements = best->pointer + member;
      if (key.compare(0, elements.size(), elements) == 0) {
        const size_t k = std::strtoul(key.c_str() + elements.size(), nullptr, 10);
        if (k < best->element_lines.size()) where.line = best->element_lines[k];
      }
    }
  }
  // The problem's own place (a PLY's file:line) stays in the message; the document's key goes last, in brackets.
  const SourceLocation inner{error.where().file == best->where.file ? "" : error.where().file, error.where().line, ""};
  const std::string place = inner.file.empty() ? "" : inner.describe() + ": ";
  return InputError(where, best->statement + ": " + place + error.explanation() + " (the converted scene's " + key + ")");
}

std::string describe_ignored(const std::vector<PbrtIgnored>& ignored) {
  std::ostringstream out;
  for (const PbrtIgnored& item : ignored)
    out << "ignored: " << item.what << " (" << item.count << (item.count == 1 ? " time" : " times") << "), first at "
        << item.first.file << ":" << item.first.line << "\n";
  return out.str();
}

bool is_pbrt_scene_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".pbrt";
}

}  // namespace rimu
