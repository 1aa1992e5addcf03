// Internal to the pbrt importer: the graphics state machine that turns pbrt statements into Rimu JSON.
// pbrt_to_scene.cpp holds the statements and the state, pbrt_shapes.cpp the shapes, pbrt_appearance.cpp the
// materials, textures and lights.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "render/scene/pbrt/pbrt_matrix.h"
#include "render/scene/analytic_shapes.h"
#include "render/scene/pbrt/pbrt_parser.h"
#include "render/scene/pbrt/pbrt_to_scene.h"
#include "spectral/upsampling/sigmoid_polynomial.h"

namespace rimu {

using Vec3d = std::array<double, 3>;
using nlohmann::json;

class PbrtConverter;

/// A statement's parameters (plus the Attribute defaults of its kind) with the ones looked up remembered, so that
/// every parameter nobody asked for is reported once the statement is done.
class PbrtParams {
 public:
  PbrtParams(PbrtConverter& converter, const PbrtStatement& s, std::string context,
             const std::vector<PbrtParam>* defaults = nullptr);
  /// Reports the parameters nobody looked up. Under --strict the first becomes the statement's error, thrown by
  /// PbrtConverter::statement once the statement is done: a destructor that throws while its function returns a
  /// value leaks that value (clang 14 does; LeakSanitizer found it), so this one never throws.
  ~PbrtParams();
  PbrtParams(const PbrtParams&) = delete;
  PbrtParams& operator=(const PbrtParams&) = delete;

  /// The parameter, or null; InputError if present with a type not in `types`.
  const PbrtParam* get(const std::string& name, std::initializer_list<PbrtParamType> types);
  double real(const std::string& name, double fallback);
  int integer(const std::string& name, int fallback);
  bool boolean(const std::string& name, bool fallback);
  std::string string(const std::string& name, const std::string& fallback);
  /// Numbers of a point3/vector3/normal/point2/integer/float array (empty if absent).
  std::vector<double> numbers(const std::string& name, std::initializer_list<PbrtParamType> types);
  const std::string& context() const { return context_; }
  const SourceLocation& where() const { return statement_.where; }
  const std::filesystem::path& directory() const { return statement_.directory; }

 private:
  PbrtConverter& converter_;
  const PbrtStatement& statement_;
  std::string context_;
  std::vector<const PbrtParam*> all_;
  std::set<std::string> used_;
};

struct PbrtGraphicsState {
  PbrtMatrix ctm = PbrtMatrix::identity();
  /// The CTM at TransformTimes' end time (motion blur): `ctm` is the start time's. Equal unless ActiveTransform
  /// made them differ.
  PbrtMatrix ctm_end = PbrtMatrix::identity();
  /// Which of the two the transform statements change (ActiveTransform): 1 the start, 2 the end, 3 both.
  int active_transforms = 3;
  std::string material;                    ///< Rimu material name; empty = pbrt's default diffuse
  std::optional<PbrtStatement> area_light;  ///< the AreaLightSource in effect
  bool reverse_orientation = false;
  std::string colour_space = "srgb-linear";  ///< Rimu's name of the pbrt ColorSpace in effect
  std::map<std::string, std::vector<PbrtParam>> attributes;  ///< Attribute "shape"/"light"/... defaults
  std::string inside_medium, outside_medium;  ///< MediumInterface names; empty = vacuum
  SourceLocation medium_interface_where;      ///< the MediumInterface in effect, for errors
};

struct PbrtTexture {
  std::string kind;  ///< "spectrum" or "float"
  std::string texture_class;
  PbrtStatement statement;
  PbrtMatrix world_from_texture = PbrtMatrix::identity();  ///< the CTM at the statement (directionmix's "dir")
};

class PbrtConverter {
 public:
  PbrtConverter(SpectralLibrary& library, std::filesystem::path output_directory, bool strict,
                std::size_t max_generated_triangles, std::size_t max_instances, std::size_t max_shapes,
                PbrtRgbUpsampler rgb_upsampler = PbrtRgbUpsampler::sigmoid);

  void statement(const PbrtStatement& s);
  /// The finished document (the converter's shapes, materials and lights are moved into it); InputError if the
  /// scene has no camera.
  json finish(const std::string& main_file);
  std::vector<PbrtIgnored> ignored() const { return ignored_; }
  /// The origins, moved out (one per shape: a million for a million instances); call once, after finish().
  std::vector<PbrtOrigin> take_origins() { return std::move(origins_); }
  /// Remembers that the document's part at `pointer` comes from `statement` at `where`.
  void origin(std::string pointer, const SourceLocation& where, std::string statement) {
    origins_.push_back({std::move(pointer), where, std::move(statement), {}});
  }

  /// Records something unsupported (or, strict, throws at `where`).
  void ignore(const std::string& what, const SourceLocation& where);
  /// The same for a parameter nobody used, from PbrtParams' destructor: strict, the error is kept (the first one)
  /// and thrown when the statement is done, not from the destructor.
  void ignore_unused(const std::string& what, const SourceLocation& where);

  // pbrt_appearance.cpp
  std::string material(const PbrtStatement& s, const std::string& type, const std::string& context);
  void light_source(const PbrtStatement& s);
  /// The "emission" of an area light on a shape of world-space area `area_m2` (needed for "power").
  /// `power_multiple`: how many times "power" the shape emits in pbrt-v4: the number of shapes pbrt makes of it (one
  /// per triangle of a mesh), each of which gets "power"; for a sphere under a scale s, s² (pbrt normalises by its
  /// object-space area).
  /// A shape's "emission" from the AreaLightSource in effect. `image_capable`: the shape may take an emission image
  /// (a mesh; not Rimu's analytic sphere).
  json area_emission(const PbrtStatement& area_light, double area_m2, double power_multiple, bool& two_sided,
                     bool image_capable);
  /// The emission of an area light with "filename": {"image", "scale"}, scaled to `power` (> 0; pbrt's per-shape power
  /// times the shapes of the mesh) as pbrt-v4 does.
  /// LightSource "projection": {"type": "projection", image, position, frame, fov_deg, and white_intensity_cd or
  /// luminous_power_lm}; nullptr (listed) for a scale of 0.
  json projection_light(PbrtParams& p, const PbrtStatement& s, const PbrtMatrix& world);
  json image_area_emission(PbrtParams& p, const PbrtStatement& s, const std::string& filename, double area_m2, double power,
                           bool two_sided);
  void texture(const PbrtStatement& s);

  // pbrt_shapes.cpp
  void shape(const PbrtStatement& s);

  // pbrt_media.cpp
  void make_named_medium(const PbrtStatement& s);

 private:
  friend class PbrtParams;
  // pbrt_appearance.cpp
  /// A spectrum parameter or spectrum texture `name` of `p` as a Rimu reflectance value (docs/scene-format.md,
  /// "Textures"); `fallback` when absent or not imported (listed). `depth` guards texture chains.
  std::optional<json> reflectance(PbrtParams& p, const std::string& name, double fallback, int depth = 0);

  // pbrt_textures.cpp
  /// A float parameter or float texture `name` of `p` as a Rimu float value (a number or a float texture object);
  /// `fallback` when absent or not imported (listed).
  json float_value(PbrtParams& p, const std::string& name, double fallback, int depth = 0);
  /// Float texture `texture_name` (referred to at `where`) as a Rimu float value; empty when not imported (listed).
  std::optional<json> float_texture_value(const std::string& texture_name, const SourceLocation& where, int depth);
  /// Spectrum texture `texture` of a class other than constant/imagemap (scale, mix, directionmix, checkerboard)
  /// as a Rimu reflectance value; empty when not imported (listed).
  std::optional<json> spectrum_combinator(const PbrtTexture& texture, int depth);
  /// An imagemap's encoding as Rimu's "srgb" or "linear", as pbrt-v4's image reader applies it: EXR/PFM/HDR linear;
  /// a PNG by its "encoding" (default sRGB; "gamma g" listed and read as sRGB); any other file sRGB whatever
  /// "encoding" says (one that is not sRGB is listed).
  std::string image_encoding(PbrtParams& tp, const std::filesystem::path& image, const SourceLocation& where);
  /// True for the files pbrt-v4's Image::Read decodes as 8-bit sRGB whatever encoding it is asked for: all but
  /// EXR, PFM, HDR (float, linear), PNG (the encoding asked for) and QOI (its own) go through stb_image so.
  static bool read_as_srgb_regardless(const std::filesystem::path& image);
  /// pbrt's roughness value (number or texture) as Rimu's perceptual roughness: r = α^½ with pbrt's α = roughness^½
  /// under remaproughness, else α = roughness (a texture is raised to that power per hit: {"power": [t, e]}).
  json roughness_value(const json& pbrt_roughness, bool remap) const;
  /// pbrt's "mix": the JSON of the material `amount` favours, under `name`.
  std::string mix_material(const PbrtStatement& s, const std::string& name, const std::string& context,
                           const std::vector<PbrtParam>* material_defaults);
  /// A pbrt spectrum parameter as a Rimu spectral value; spectrum files resolve against `directory`. Empty (and
  /// listed) for what is not imported.
  std::optional<json> spectrum_value(const PbrtParam& param, bool illuminant, const std::filesystem::path& directory);
  /// A light's spectrum and amount from pbrt's `spectrum_key` × `scale_key`, normalised as pbrt-v4 normalises a
  /// light's spectrum (SpectrumToPhotometric): the shape and a photometric amount, or the absolute value.
  json light_amount(PbrtParams& p, const char* spectrum_key, const char* radiometric_key, const char* photometric_key,
                    std::optional<double> photometric_amount, const char* scale_key = "scale");
  double rgb_luminance(const PbrtParam& rgb) const;
  /// The value of float texture `name` if it is the same everywhere (constant, or scale/mix of such); empty
  /// otherwise. InputError (at `where`) for an unknown or spectrum texture.
  std::optional<double> constant_float_texture(const std::string& name, const SourceLocation& where, int depth);
  /// The unit world images of light-space x, y, z under `world` (made perpendicular, and listed, under a shear or
  /// non-uniform scale); InputError at `where` for a singular transform.
  std::array<Vec3d, 3> light_axes(const PbrtMatrix& world, const std::string& context, const SourceLocation& where);
  /// pbrt's "goniometric" light at the light transform `world`.
  json goniometric_light(PbrtParams& p, const PbrtStatement& s, const PbrtMatrix& world);
  /// pbrt's "infinite" light with an equal-area octahedral image `filename`, in the light transform `world`.
  json image_environment(PbrtParams& p, const PbrtStatement& s, const std::string& filename, const PbrtMatrix& world);
  std::string default_material();
  /// pbrt-v4's "hair" material as the scene format's "hair" (pbrt_appearance.cpp).
  json hair_material(PbrtParams& p, const PbrtStatement& s);
  /// Counts one lookup of texture `name` at nesting `depth` (0: the parameter's own texture, which starts the
  /// count); InputError at `where` beyond kMaxTextureLookups for one parameter.
  void count_texture_lookup(const std::string& name, int depth, const SourceLocation& where);
  /// An imagemap's "mapping", "uscale", "vscale", "udelta", "vdelta" as the image texture's mapping keys (none for
  /// plain uv); its "filter" (Rimu's is bilinear) taken, a "wrap" other than "repeat" listed.
  void image_mapping(PbrtParams& tp, json& value, const PbrtTexture& texture);

  // pbrt_media.cpp
  /// A medium's sigma_a/sigma_s (1/m; pbrt's unbounded RGB becomes a table through Rimu's upsampler).
  json coefficient_value(PbrtParams& p, const std::string& name, double fallback);
  /// pbrt's unbounded RGB coefficient `c` in `colour_space` (a Rimu colour space name) as a Rimu spectral value.
  /// A conductor's eta or k, a dielectric's or coat's eta: as spectrum_value, and RGB as pbrt-v4's unbounded RGB
  /// (unbounded_rgb in the colour space in effect). Throws InputError for a black RGB index of refraction.
  /// An "eta" or "k" as Rimu's spectral value. An RGB index of 0 (black) is an error, except for a conductor
  /// (`conductor_index`), whose complex index n + ik is meaningful at n = 0 with k > 0 and which pbrt-v4 accepts:
  /// Rimu's n > 0 then gets 1e-3 (the normal-incidence reflectance of n = 0, k = 1 is 1; of n = 1e-3, 0.998).
  std::optional<json> optical_constant(const PbrtParam& param, PbrtParams& p, bool conductor_index = false);
  json unbounded_rgb(const Vec3d& c, const std::string& colour_space, const SourceLocation& where);

  // pbrt_rgb_spectra.cpp: pbrt-v4's RGB spectra (RGBAlbedoSpectrum, RGBUnboundedSpectrum, RGBIlluminantSpectrum)
  /// The sigmoid fit of `rgb` in `colour_space` (albedo or unbounded), fitted once per distinct input.
  const SigmoidSpectrum& sigmoid_fit(const Rgb& rgb, bool unbounded, const std::string& colour_space, const SourceLocation& where);
  /// A constant RGB reflectance in the colour space in effect: pbrt's albedo spectrum as a 1 nm table (sigmoid
  /// upsampler), or the scene format's {"rgb", "space"} (Rimu's upsampler, and any RGB with a component above 1).
  json rgb_reflectance(const PbrtParam& rgb);
  /// The spectral shape of an RGB light (pbrt's RGBIlluminantSpectrum: the unbounded fit times the colour space's
  /// illuminant) as a 1 nm table, for a photometric key that sets its luminance; empty under Rimu's upsampler.
  std::optional<json> rgb_illuminant_shape(const PbrtParam& rgb);
  /// `s` (times `illuminant` if given) on a 1 nm grid over 360–830 nm as an inline table.
  static json sigmoid_table(const SigmoidSpectrum& s, const Spectrum* illuminant = nullptr);
  /// pbrt-v4's named measured medium `name` (data/media/scattering_presets.csv) as {sigma_a, sigma_s}; empty if
  /// pbrt has no such name.
  std::optional<std::pair<json, json>> scattering_preset(const std::string& name, const SourceLocation& where);
  /// The interior of pbrt-v4's "subsurface" material `material` (its scattering properties: "name", "sigma_a" and
  /// "sigma_s", or "reflectance" and "mfp"; "scale", "g"): a homogeneous medium bounded by that material (the
  /// dielectric surface made of its "eta" and roughness), added to the scene's media.
  void subsurface_medium(PbrtParams& p, const std::string& material);
  /// A "uniformgrid" medium's density grid, box and transform onto `medium` (a Rimu "grid" medium with its density
  /// inline, trilinear like pbrt's). InputError at the statement for a wrong voxel count or a negative density.
  void add_density_grid(PbrtParams& p, json& medium);
  /// A "nanovdb" medium: the JSON grid medium reading the .nvdb file's "density" grid (relative to the pbrt file).
  void add_nanovdb_grid(PbrtParams& p, json& medium);
  /// A "cloud" medium (pbrt-v4's procedural CloudMedium): Rimu's "noise_cloud" with its parameters, box and
  /// transform. pbrt's cloud takes no "scale" and no "Le" (left unread, so listed).
  json noise_cloud_medium(PbrtParams& p);
  /// "p0" and "p1" as pbrt's Bounds3f takes them (componentwise min and max; defaults 0 and 1); InputError if empty.
  std::pair<Vec3d, Vec3d> medium_box(PbrtParams& p);
  /// "g", default 0: an error outside (−1, 1), clamped (and listed) beyond Rimu's ±0.99.
  double medium_g(PbrtParams& p);
  /// The medium's space is the CTM at MakeNamedMedium (pbrt's renderFromMedium): its steps as `medium`'s
  /// "transform" (none for the identity); a moving CTM is listed (media stay at their start placement).
  void add_medium_placement(const SourceLocation& where, json& medium);
  /// The material a shape of `material` gets under the MediumInterface in effect: a copy bounding the inside medium
  /// where one begins at the shape; empty for an "interface" shape with no medium to bound (left out, listed).
  std::optional<std::string> boundary_material(const std::string& material, const SourceLocation& where, const std::string& context);
  /// Lists the outside media that no shape has inside (pbrt's scene-wide media).
  void finish_media();
  /// Whether the MediumInterface in effect puts an imported medium only in front of shapes of `material`
  /// (`MediumInterface "" "fog"`: pbrt-v4's exterior, on the side the normal points to), for a shape that is not an
  /// area light and whose material is defined already: such a shape may be turned inside out to bound it.
  bool medium_in_front_only(const std::string& material) const;
  /// Whether the mesh about to be emitted (pbrt's front already counter-clockwise) is turned inside out so that the
  /// medium in front of it becomes the medium it bounds from behind (pbrt_media.cpp has the rule); lists the shapes
  /// whose front medium cannot be represented.
  bool turn_for_front_medium(const std::vector<Vec3d>& positions, const std::vector<uint32_t>& indices,
                             const SourceLocation& where, const std::string& context);
  /// The material shapes get now: the Material/NamedMaterial in effect, else pbrt's default diffuse.
  std::string current_material() { return state_.material.empty() ? default_material() : state_.material; }

  // pbrt_to_scene.cpp
  void film_crop(PbrtParams& p, const PbrtStatement& s);

  // pbrt_film.cpp
  /// The Film statement: resolution, crop, sensor, iso, white balance, spectral buckets (docs/pbrt-import.md).
  void film(const PbrtStatement& s);
  /// The Camera's "shutteropen"/"shutterclose": pbrt's exposure time.
  void camera_shutter(PbrtParams& p);
  /// Adds the physical camera ("exposure": pbrt's imaging ratio t·S/100) and "white_balance" to `camera`.
  void finish_exposure(json& camera) const;

  // pbrt_shapes.cpp
  /// `pbrt_default_uvs`: a mesh without uvs gets pbrt-v4's per-triangle (0,0), (1,0), (1,1) at its vertices in the
  /// order pbrt read them ("uv_default": "pbrt", or explicit uvs where triangles are rewound).
  void emit_mesh(PbrtParams& p, std::vector<Vec3d> positions, std::vector<uint32_t> indices, std::vector<Vec3d> normals,
                 std::vector<std::array<double, 2>> uvs, const std::string& context, int shape_count,
                 bool pbrt_default_uvs = false);
  void emit_shape(json shape, const SourceLocation& where, const std::string& context, bool emissive_capable,
                  double area_m2, double power_multiple);
  /// Lists a mesh whose shading normals lie in (or across) the plane of 1 % or more of its area
  /// (TriangleMesh::normals_near_plane_area_share): there Rimu's image differs from pbrt-v4's.
  void list_normals_near_plane(const std::vector<Vec3d>& positions, const std::vector<uint32_t>& indices,
                               const std::vector<Vec3d>& normals, const SourceLocation& where, const std::string& context);
  /// The listing itself, for a mesh already found to have them.
  void list_normals_near_plane(const SourceLocation& where, const std::string& context);
  /// A cylinder, disk or sphere mesh (render/scene/analytic_shapes.h, in object space) through emit_mesh, counted
  /// against the generated-triangle limit.
  void emit_analytic_mesh(PbrtParams& p, AnalyticMesh mesh, const SourceLocation& where, const std::string& context);
  /// Shape "curve" (pbrt_curves.cpp) → a "curves" shape, merged into the one before when that holds curves of the
  /// same kind, basis, degree, material and transform from the same file (hair files hold tens of thousands).
  void curve_shape(const PbrtStatement& s, const std::string& context, const std::vector<PbrtParam>* shape_defaults);
  /// The shape's "alpha" (a float or a float texture) as Rimu's shape "alpha", or null (solid). `has_uvs`: whether
  /// the shape carries texture coordinates an alpha image can follow.
  json alpha_parameter(PbrtParams& p, bool has_uvs);
  /// The 12 numbers of `m`'s rows (the placement of a shape or instance); InputError at `where` if it is not finite,
  /// projective or singular.
  json matrix_rows(const PbrtMatrix& m, const SourceLocation& where) const;
  /// `m` as a shape's "transform" steps (null for the identity), checked as matrix_rows.
  json transform_steps(const PbrtMatrix& m, const SourceLocation& where) const;
  /// An ObjectInstance (already checked): appended to the "instances" shape of the statement before it when that
  /// placed the same object from the same file, else a new one.
  void object_instance(const PbrtStatement& s);
  PbrtMatrix world_from_object() const { return mirror_ * state_.ctm; }
  /// The CTM moves while pbrt's shutter is open (its start and end differ).
  bool ctm_moves() const;
  /// A moving placement as Rimu takes it: where `start`/`end` (at TransformTimes' start and end times) put the
  /// object at the camera's shutteropen and shutterclose (pbrt-v4's interpolation, MotionTransform, clamped to the
  /// TransformTimes as pbrt clamps). Lists once, at `where`, a shutter reaching beyond the TransformTimes, where pbrt
  /// holds the object still and Rimu moves it evenly over the whole shutter.
  /// pbrt-v4's render-from-world in its default camera-world rendering space (a translation taking the camera's
  /// position at the middle of the TransformTimes to the origin), in which it interpolates a moving ObjectInstance.
  PbrtMatrix render_from_world_for_instances() const;
  /// The name of a copy of prototype `name` whose shapes are moved by `render_from_world` (made once per name).
  std::string render_space_prototype(const std::string& name, const PbrtMatrix& render_from_world);
  std::pair<PbrtMatrix, PbrtMatrix> shutter_placements(const PbrtMatrix& start, const PbrtMatrix& end,
                                                       const SourceLocation& where);
  std::string path_for_document(const std::filesystem::path& absolute) const;

  SpectralLibrary& library_;
  PbrtRgbUpsampler rgb_upsampler_;
  std::map<std::string, std::unique_ptr<SigmoidFitter>> sigmoid_fitters_;  ///< per colour space
  std::map<std::tuple<std::string, bool, double, double, double>, SigmoidSpectrum> sigmoid_fits_;
  std::filesystem::path output_directory_;
  bool strict_;
  double nits_per_unit_y_;

  PbrtGraphicsState state_;
  std::vector<std::pair<char, PbrtGraphicsState>> stack_;  ///< 'a' AttributeBegin, 't' TransformBegin, 'o' ObjectBegin
  std::map<std::string, std::pair<PbrtMatrix, PbrtMatrix>> named_coordinate_systems_;  ///< start and end CTMs
  bool world_begun_ = false;
  std::optional<std::string> object_;  ///< inside ObjectBegin
  SourceLocation object_where_;        ///< that ObjectBegin
  json shape_alpha_;                   ///< the alpha of the Shape being converted (pbrt_shapes.cpp), or null
  bool shape_turned_for_medium_ = false;  ///< the Shape being converted bounds its front medium (turn_for_front_medium)
  std::map<std::string, PbrtTexture> textures_;

  // Camera: world-from-camera at the Camera statement, and its parameters.
  std::optional<PbrtMatrix> world_from_camera_;
  std::optional<PbrtMatrix> world_from_camera_end_;  ///< a moving camera's at TransformTimes' end
  SourceLocation camera_where_;
  double transform_start_time_ = 0.0, transform_end_time_ = 1.0;  ///< TransformTimes
  double shutter_open_ = 0.0, shutter_close_ = 1.0;                ///< Camera shutteropen, shutterclose
  bool shutter_beyond_times_listed_ = false;
  PbrtMatrix mirror_ = PbrtMatrix::identity();  ///< makes pbrt's image-right Rimu's (see docs/pbrt-import.md)
  json camera_;
  double fov_deg_ = 90.0;
  bool orthographic_ = false;  ///< Camera "orthographic"
  bool spherical_ = false;     ///< Camera "spherical"
  int width_ = 1280, height_ = 720;
  // Film and shutter (pbrt_film.cpp): pbrt's PixelSensor settings, combined by finish_exposure().
  std::optional<double> film_iso_;  ///< Film "iso", when given
  double film_white_balance_k_ = 0.0;  ///< Film "whitebalance" (0: pbrt's default)
  std::string film_sensor_ = "cie1931";
  SourceLocation film_where_;
  double shutter_s_ = 1.0;  ///< Camera shutterclose − shutteropen (pbrt's exposure time)
  bool shutter_given_ = false;

  json materials_ = json::object();
  json prototypes_ = json::object();
  json shapes_ = json::array();
  json lights_ = json::array();
  json film_ = json::object();
  json integrator_ = json::object();
  /// pbrt's `mlt`: its mutations per pixel (the sample count it renders, whatever the Sampler says; 0: not mlt) and
  /// bootstrap paths (a count for the whole image: per pixel once the resolution is known).
  int64_t metropolis_spp_ = 0;
  double metropolis_bootstrap_ = 0.0;
  std::set<std::string> named_materials_;
  /// NamedMaterial names used before their MakeNamedMaterial → the first such NamedMaterial (checked at finish)
  std::map<std::string, SourceLocation> forward_materials_;
  std::set<std::string> interface_materials_;  ///< pbrt's "interface": index-matched medium boundaries
  std::set<std::string> subsurface_materials_;  ///< pbrt's "subsurface": dielectrics that bound their own medium
  std::map<std::string, json> media_defined_;  ///< MakeNamedMedium name → Rimu medium (no boundary yet); null: not imported
  json media_ = json::object();                ///< the document's "media"
  std::map<std::string, std::string> boundary_materials_;  ///< material + '\n' + medium → the bounding copy's name
  std::set<std::string> interior_media_;                   ///< media some shape has inside
  std::map<std::string, SourceLocation> exterior_media_;   ///< media some shape has outside, first place
  std::string camera_medium_;                              ///< the outside medium at Camera; empty: vacuum
  SourceLocation camera_medium_where_;
  int anonymous_materials_ = 0;
  std::optional<InputError> unused_parameter_error_;  ///< strict: ignore_unused's first error in this statement
  void statement_body(const PbrtStatement& s);
  std::size_t max_generated_triangles_;  ///< PbrtImportOptions::max_generated_triangles
  std::size_t generated_triangles_ = 0;  ///< so far: Loop subdivision and sphere/disk stand-ins
  std::size_t max_instances_;            ///< PbrtImportOptions::max_instances
  std::size_t instances_ = 0;            ///< ObjectInstance statements imported so far
  /// The "instances" shape the last ObjectInstance went to.
  struct InstanceBatch {
    std::string prototype;
    std::size_t shape;   ///< index in shapes_
    std::size_t origin;  ///< index in origins_
  };
  std::optional<InstanceBatch> instance_batch_;
  /// The "curves" shape the last Shape "curve" went to (its origin holds a line per curve).
  struct CurveBatch {
    std::size_t shape;   ///< index in shapes_
    std::size_t origin;  ///< index in origins_
  };
  std::optional<CurveBatch> curve_batch_;
  std::size_t max_shapes_;               ///< PbrtImportOptions::max_shapes
  std::size_t shapes_read_ = 0;          ///< Shape statements so far
  /// Adds `triangles` to the generated count; InputError at `where` if that crosses max_generated_triangles_.
  void count_generated_triangles(double triangles, const SourceLocation& where, const std::string& context);
  /// Texture lookups made for the parameter being converted: textures may share operands, so a graph of n
  /// statements can unfold into 2ⁿ lookups (each texture mixing the one before with itself); bounded, see
  /// count_texture_lookup.
  int texture_lookups_ = 0;

  std::vector<PbrtIgnored> ignored_;
  std::map<std::string, size_t> ignored_index_;
  std::vector<PbrtOrigin> origins_;
  std::map<std::string, SourceLocation> media_where_;  ///< MakeNamedMedium name → its statement
};

}  // namespace rimu
