// pbrt-v4 scene files translated into Rimu's JSON scene (docs/pbrt-import.md): the JSON then goes through the
// ordinary, validated loader, so a .pbrt file and the JSON it becomes render the same image.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/scene/pbrt/pbrt_parser.h"
#include "spectral/error.h"
#include "spectral/library/spectral_library.h"

namespace rimu {

/// Something of the pbrt file that Rimu does not render (or renders approximately), counted.
struct PbrtIgnored {
  std::string what;     ///< e.g. Material "measured", parameter "float alpha" of Shape "trianglemesh"
  int count = 0;
  SourceLocation first; ///< file and line of the first occurrence
};

/// How the importer turns pbrt's constant RGB parameters (reflectances, RGB lights, RGB optical constants and
/// medium coefficients) into spectra (docs/pbrt-import.md, "RGB parameters").
enum class PbrtRgbUpsampler {
  sigmoid,  ///< pbrt-v4's own function space (Jakob & Hanika 2019 sigmoid polynomials), fitted per colour: the default
  rimu,     ///< Rimu's smoothest-spectrum upsampler, as the scene format's "rgb" form (the importer before Dec 2026)
};

struct PbrtImportOptions {
  /// Any ignored statement, parameter or type is an InputError at its location instead of a report entry.
  bool strict = false;
  /// File paths in the document (PLY meshes, image textures) are written relative to this folder; empty: the
  /// folder of the pbrt file (right for rendering the document in memory).
  std::filesystem::path output_directory;
  /// The most triangles the importer may generate for the whole scene: Loop subdivision (4^levels per control
  /// triangle) and the meshes standing in for spheres, cylinders and disks, all written inline into the document (about
  /// 150 bytes of JSON per triangle, then the loader's own copy). Beyond it the import is an InputError at the
  /// shape that crosses it. Triangles the file lists itself do not count (they cost what the file's size does).
  std::size_t max_generated_triangles = std::size_t(1) << 21;
  /// The most ObjectInstance statements imported for the whole scene (2^20 = 1,048,576): each becomes a placement
  /// of its prototype (a 3×4 matrix in an "instances" shape, about 250 bytes of JSON) and an Embree instance. Beyond it the import is an
  /// InputError at the instance that crosses it.
  std::size_t max_instances = std::size_t(1) << 20;
  /// The most Shape statements for the whole scene (2^20), counting each read of an included file: a file of
  /// shapes included over and over would otherwise fill memory with copies of its shapes (each is an Embree
  /// geometry of its own; repeated geometry belongs in ObjectBegin/ObjectInstance).
  std::size_t max_shapes = std::size_t(1) << 20;
  /// Statements and included files, counted over the whole Include graph (pbrt_parser.h).
  PbrtParseLimits parse_limits{};
  /// RGB → spectrum for the file's constant RGB parameters; image textures always use Rimu's upsampler.
  PbrtRgbUpsampler rgb_upsampler = PbrtRgbUpsampler::sigmoid;
};

/// Where a part of the imported document came from: the pbrt statement that made it.
struct PbrtOrigin {
  std::string pointer;    ///< key path of the part as the JSON loader writes it, names unescaped ("/shapes/3", "/materials/gold")
  SourceLocation where;   ///< the pbrt file and line of the statement
  std::string statement;  ///< e.g. Shape "plymesh"
  /// For an "instances" shape (consecutive ObjectInstances of one object in one file): the line of each of its
  /// "matrices", in order; `where` holds the first. 4 bytes an instance, where an origin apiece took 200.
  std::vector<int> element_lines;
};

struct PbrtImport {
  nlohmann::json document;           ///< a Rimu scene (docs/scene-format.md)
  std::vector<PbrtIgnored> ignored;  ///< in order of first occurrence
  std::vector<PbrtOrigin> origins;   ///< every shape, instance, material, light and medium of the document
};

/// Reads a pbrt-v4 file (and what it Includes/Imports) into a Rimu scene document. Throws InputError with the pbrt
/// file and line for malformed input, missing files, singular or non-finite transforms, a scene without a Camera,
/// and (strict) anything unsupported. `library` supplies the film's luminance unit (pbrt's pixel value 1 = 1 nit).
PbrtImport import_pbrt(const std::filesystem::path& file, SpectralLibrary& library, const PbrtImportOptions& options = {});
/// The same on text in memory: `file` is the name errors carry, `directory` resolves relative paths.
PbrtImport import_pbrt_text(const std::string& text, const std::string& file, const std::filesystem::path& directory,
                            SpectralLibrary& library, const PbrtImportOptions& options = {});

/// An InputError that loading the imported document raised (a truncated PLY, a bad image, a value Rimu refuses)
/// moved to the pbrt statement that made the part it names: "scene.pbrt:12: Shape \"plymesh\": mesh.ply:40:
/// vertex 2: …", with the document's key kept at the end. Empty when the error names no imported part.
std::optional<InputError> at_pbrt_origin(const InputError& error, const std::vector<PbrtOrigin>& origins);

/// The report printed after loading: one line per entry, `ignored: Shape "bilinearmesh" under a singular transform (12 times), first at a.pbrt:1234`.
std::string describe_ignored(const std::vector<PbrtIgnored>& ignored);

/// True for a path ending in .pbrt (case-insensitive): the scene readers dispatch on it.
bool is_pbrt_scene_path(const std::filesystem::path& path);

}  // namespace rimu
