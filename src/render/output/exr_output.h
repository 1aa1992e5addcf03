// Writing a film to OpenEXR: its channels, spectral bins and the render's metadata.
#pragma once

#include <cstdint>
#include <ctime>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/film/film.h"
#include "render/output/partial_record.h"
#include "render/camera/physical_camera.h"
#include "spectral/colour_spaces/matrix3.h"

namespace rimu {

/// What the render did, for the file's metadata.
struct RenderMetadata {
  int samples_per_pixel = 0;  ///< spp actually reached (less than requested when interrupted)
  uint64_t seed = 0;
  double render_time_s = 0.0;
  bool interrupted = false;   ///< adds "rimu:interrupted" = "interrupted at N spp"
  std::string scene;          ///< scene file, if any
  std::map<std::string, std::string> extra;  ///< more string attributes, written as "rimu:<key>"
  /// The physical camera's settings, if any: written as the standard isoSpeed, expTime and aperture too.
  std::optional<PhysicalCameraSettings> camera;
  /// When the image was made (seconds since the epoch; 0: unknown): the standard capDate and utcOffset.
  std::time_t finished_at = 0;
  /// For camera films: the matrix from the written R, G, B to CIE XYZ (render/film/camera_colour_matrix.h with the
  /// white balance undone), written as the m33f attribute "cameraToXYZ" (row-major, acting on column vectors).
  std::optional<Matrix3> camera_to_xyz;
  double camera_to_xyz_mean_delta_e2000 = 0;  ///< its fit's residual, "rimu:cameraToXYZMeanDeltaE2000"
};

enum class ExrPixelType { half, float32 };

struct ExrOptions {
  /// 32-bit floats by default: film units put Y = 1 at about 73,000 cd/m², so a scene lit in lux without a physical
  /// camera's exposure sits near or below half's normal range (see HalfRangeCounts). Half is opt-in (`rimu --half`).
  ExrPixelType pixel_type = ExrPixelType::float32;
  RenderMetadata metadata;
  /// Name XYZ channels R, G, B instead of X, Y, Z. Some readers take a lone "Y" channel for luminance and ignore
  /// X and Z; with R, G, B and the XYZ chromaticities, colour-managed readers show the right colours.
  bool xyz_channels_as_rgb = false;
  /// A partial render (render/output/partial_record.h): also write the film's accumulators exactly and the record.
  std::optional<PartialRecord> partial;
  /// More 32-bit float channels, each a value per pixel of the film's crop window, row by row (e.g. an adaptive
  /// render's "spp" and "relativeError"). Written as they are (finite values only, like every channel).
  std::vector<std::pair<std::string, std::vector<float>>> extra_channels;
};

/// Writes the film's crop window as the EXR data window (display window = the full image); pixels without samples
/// are 0. The X, Y, Z / R, G, B channels are Film::output_value() (exposure and white balance applied); spectral
/// bins stay in radiance units. Channels:
/// - XYZ film: X, Y, Z, and the `chromaticities` attribute for XYZ: the chromaticities of the RGB triples
///   (1,0,0), (0,1,0), (0,0,1), (1,1,1) as ImfChromaticities.h defines them, which for X, Y, Z stored as
///   R, G, B are red (1, 0), green (0, 1), blue (0, 0), white (1/3, 1/3).
/// - camera film: R, G, B (raw sensor, no chromaticities; the camera is named in "rimu:camera"; with
///   metadata.camera_to_xyz, the m33f "cameraToXYZ" that turns them into XYZ).
/// - spectral bins (when the film has them): one channel per bin named "S0.<centre>nm" with a comma as the
///   decimal separator, e.g. "S0.362,35nm", following Fichet, Pacanowski & Wilkie, "An OpenEXR Layout for
///   Spectral Images", JCGT 10(3), 2021 (S0 = unpolarised emission), plus "spectralLayoutVersion" = "1.0".
///   Values are the mean spectral radiance over the bin (W/(m²·sr·nm) for radiance inputs), and the layout's
///   "emissiveUnits" attribute says so: "W.m^-2.sr^-1" (the layout's spelling for spectral radiance, per nm).
/// - light groups (when the film has them): per group a layer "<group>.X", "<group>.Y", "<group>.Z" (the beauty's
///   channel names after the group's: "<group>.R" ... for camera films or xyz_channels_as_rgb), with the same
///   output transform as the beauty, and on a spectral film the group's bins "<group>.S0.<centre>nm", so the layers
///   sum to the beauty channel by channel and bin by bin; the names in layer order in "rimu:lightGroups"
///   ("sun,lamps,ungrouped").
/// Half values are clamped to ±65504 (the largest half) rather than overflowing to Inf. No non-finite value is ever
/// written: NaN becomes 0 and ±Inf the largest finite value of the type (an exposure scale times a bright pixel can
/// overflow a float); their number is returned and, when not 0, written as "rimu:nonFiniteValuesReplaced".
/// Standard attributes (OpenEXR's ImfStandardAttributes.h), besides Rimu's own: chromaticities (XYZ films),
/// whiteLuminance (XYZ films: cd/m² of the written Y = 1), isoSpeed, expTime, aperture (with a physical camera),
/// capDate and utcOffset (metadata.finished_at), comments; and "software" = "Rimu <version>" (no standard key).
/// Attributes: rimu:version, rimu:filmResponse, rimu:camera, rimu:spp (int), rimu:seed (string: 64 bits),
/// rimu:renderTimeSeconds (double), rimu:samplesAccepted / rimu:discardedNaN / rimu:discardedInf /
/// rimu:discardedNegative (double: exact to 2⁵³), rimu:luminanceNitsPerUnitY (XYZ films), rimu:scene,
/// rimu:interrupted, rimu:<extra keys>; with a white balance (an output transform whose matrix M is not the
/// identity) rimu:whiteBalanceMatrix (m33d: M, row-major, acting on column vectors) and rimu:whiteBalanceTarget
/// (the white M adapts to: "D65" on XYZ films, "equal R, G, B (G kept)" on camera films).
/// With options.partial, the file is also a partial render: every accumulator of the film (Film::accumulators: the
/// three channel sums in film units before the output transform, the filter-weight sum, the spectral bin sums, each
/// light group's channel and bin sums; "rimu:partial:spectralBins" = N gives the layout) is
/// stored exactly, the 64 bits of its double split over two UINT channels "rimu.sum.<k>.hi" and "rimu.sum.<k>.lo"
/// (k = 0, 1, ..., at least two digits), and the record as "rimu:partial:*" attributes (docs/farm.md lists them).
/// Written to a temporary file in the same folder and renamed (write_atomically): on failure no file is left at
/// `path`. Throws InputError for a missing folder, OutputError for anything else. Returns the number of non-finite
/// values replaced (see above).
size_t write_exr(const std::filesystem::path& path, const Film& film, const ExrOptions& options = {});

/// How well half floats hold the film's X, Y, Z / R, G, B output (Film::output_value()), counted over its non-zero
/// finite values. Half keeps 11 significant bits (relative step ≤ 2⁻¹¹ ≈ 0.05 %) only between its smallest normal
/// value, 2⁻¹⁴ ≈ 6.1e-5, and 65504: below, the step stays 2⁻²⁴ ≈ 6e-8 in absolute terms (1e-6 keeps 6 %, values
/// under 3e-8 become 0); above, write_exr clamps. Film units put Y = 1 at about 73,000 cd/m² (XYZ films), so a scene
/// lit in lux without a physical camera's exposure can sit mostly below the normal range: an office at 500 lx gives
/// a grey card Y ≈ 4e-4, moonlight 1e-7.
struct HalfRangeCounts {
  size_t nonzero = 0;       ///< non-zero finite values
  size_t below_normal = 0;  ///< 0 < |v| < 2⁻¹⁴
  size_t above_max = 0;     ///< |v| > 65504 (clamped when written as half)
};
HalfRangeCounts half_range_counts(const Film& film);
/// A warning line (no trailing newline) when half floats would lose the image: some value is clamped, or at least
/// a tenth of the non-zero values lie below half's normal range; empty otherwise.
std::string half_range_warning(const HalfRangeCounts& counts, const std::string& file);

/// The EXR channel holding the high (or low) 32 bits of accumulator `accumulator` of a partial (see write_exr).
std::string partial_sum_channel_name(int accumulator, bool high_word);

/// "a,b,c": the light groups' names as "rimu:lightGroups" holds them (names never contain a comma), and back.
std::string light_groups_text(const std::vector<std::string>& groups);
std::vector<std::string> parse_light_groups_text(const std::string& text);

/// The EXR channel name of spectral bin `bin` (see write_exr).
std::string spectral_channel_name(const SpectralBinning& binning, int bin);

}  // namespace rimu
