// Internal to scene loading: the state shared by the parts of the loader (one file per section).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "render/scene/coordinate_limit.h"
#include "render/scene/json_cursor.h"
#include "render/image/rgb_image.h"
#include "render/scene/scene.h"
#include "render/scene/spectrum_input.h"
#include "render/scene/triangle_mesh.h"
#include "transport/bsdfs/measured_brdf.h"
#include "transport/lights/radiance_image.h"

namespace rimu::scene_loading {

/// An instance's place in the document: the index of its shape in "shapes" and, for "instances", of its matrix.
struct InstanceKey {
  static constexpr uint32_t kNoMatrix = ~uint32_t(0);  ///< a shape of type "instance"
  uint32_t shape;
  uint32_t matrix;
};

struct LoadContext {
  Scene& scene;
  SpectrumInputContext spectra;
  std::map<std::string, int> material_index;
  std::map<std::string, int> prototype_index;
  std::map<int, BoundsD> prototype_bounds;  ///< object-space bounds of each prototype, to check its instances
  /// Where each instance of the scene came from, in the order of EmbreeScene's instances: their transforms are
  /// checked against the whole scene's extent once it is known. Indices, not cursors (a cursor holds two strings:
  /// 300 bytes an instance).
  std::vector<InstanceKey> instance_keys;
  /// Measured BRDFs by resolved path: materials that name the same file share its tables (tens of MB each).
  std::map<std::filesystem::path, MeasuredBrdfPtr> measured_brdfs;
};

/// The key of an instance's placement (for its errors): its "transform" (or the shape, without one), or the
/// element of "matrices". `shapes` is the document's "shapes".
JsonCursor instance_cursor(const JsonCursor& shapes, InstanceKey key);

/// "transform": an array of operations applied in order to the object ({"translate": v}, {"scale": v or s},
/// {"rotate": {"angle_deg": a, "axis": v}}, {"matrix": 12 row-major numbers}); absent = identity. `key` names
/// another array of the same steps ("transform_end": where a moving shape is at shutter close).
Transform parse_transform(const JsonCursor& shape, const char* key = "transform");
/// Reads the image named by a texture or environment object: "encoding" is "srgb" (8-bit sRGB-encoded, decoded to
/// linear) or "linear"; by default integer files are sRGB-encoded and float files (EXR, HDR) linear.
std::shared_ptr<const RgbImage> load_rgb_image(const JsonCursor& value, const std::filesystem::path& path);
/// An image of emitted radiance (an environment's, an emissive shape's): the pixels of `l`'s "image" (with its
/// "encoding" and "colour_space", default srgb-linear) as radiance, upsampled to spectra (or RGB lanes in rgb
/// transport), and the factor to apply for `scale` (≥ 0, finite) in film units: a pixel of luminance Y renders as film
/// Y · scale. Every pixel times `scale` must be at most 1e30 (an error names the first that is not).
struct EmissionImage {
  std::shared_ptr<const RadianceImage> pixels;
  double scale = 1.0;
};
EmissionImage load_emission_image(const JsonCursor& l, double scale, LoadContext& context);
void load_materials(const JsonCursor& section, LoadContext& context);
/// Loads the "media" section (render/scene/scene_media.cpp); runs after the materials, which media name as boundaries.
void load_media(const JsonCursor& section, LoadContext& context);
void load_shapes(const JsonCursor& section, LoadContext& context);
/// A "curves" shape (scene_curves.cpp), its material already resolved: Embree curves, not instanced, not emissive.
void load_curves(const JsonCursor& shape, int material, LoadContext& context);
void load_prototypes(const JsonCursor& section, LoadContext& context);
/// Loads the "lights" section. Runs before load_shapes, which appends an AreaLight per emissive shape.
void load_lights(const JsonCursor& section, LoadContext& context);

}  // namespace rimu::scene_loading
