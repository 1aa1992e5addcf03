// Reading a partial render (an EXR written by write_exr with ExrOptions::partial) back: its record, its metadata
// and its exact accumulators.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/output/exr_output.h"

namespace rimu {

/// One partial render as read from its file.
struct PartialImage {
  std::filesystem::path path;
  PartialRecord record;
  int width = 0, height = 0;   ///< the display window (the full image)
  PixelBounds crop;            ///< the data window: the pixels it holds
  int spectral_bins = 0;
  std::vector<std::string> light_groups;  ///< "rimu:lightGroups": the film's group layers (empty: none)
  ExrPixelType pixel_type = ExrPixelType::float32;  ///< of its visible channels
  int accumulators_per_pixel = 0;
  std::vector<double> sums;    ///< accumulators_per_pixel doubles per pixel of `crop`, row by row (exact)
  FilmSampleCounts counts;     ///< accepted and discarded samples
  std::optional<double> max_sample_value;  ///< "rimu:maxSampleValue": the sample clamp its samples went through
  /// The metadata to write again (scene, camera, colour matrix, rimu:* strings such as the sampler); spp, render
  /// time and capture time are the file's own.
  RenderMetadata metadata;
};

/// Reads `path` (without `with_sums`, only its header: sums stays empty). Throws InputError naming the file if it
/// cannot be read as OpenEXR or is not a partial render (no "rimu:partial:*" record or accumulator channels: e.g. an
/// image rendered without --samples/--checkpoint).
PartialImage read_partial_exr(const std::filesystem::path& path, bool with_sums = true);

/// A film holding the partial's sums and sample counts (its response rebuilt from the record's film spec), with
/// the record's output transform: writing it gives the partial's image again.
std::unique_ptr<Film> film_from_partial(const PartialImage& partial, SpectralLibrary& library);

/// Adds the partial's sums (and counts) into `film` over the partial's crop (which must lie inside the film's).
void add_partial_to_film(const PartialImage& partial, Film& film);

/// The same for a partial read without its sums (read_partial_exr(path, false)): reads them from `header.path` a
/// band of 64 rows at a time straight into `film`, so the merge holds one film and one band, not a second copy of
/// the image (a 4K 47-bin partial's sums are 3.4 GB). Bit for bit the same additions as add_partial_to_film.
void add_partial_exr_to_film(const PartialImage& header, Film& film);

/// Where a resumed render continues: the samples after the partial's last one, and its render time so far.
struct ResumePoint {
  int first_sample = 0;
  double render_time_s = 0.0;
};
/// Starts `film` from `previous` (add_partial_to_film) for --resume. InputError naming the file if its window,
/// spectral bins or light groups differ from the film's (the film was rebuilt from the job it records).
ResumePoint resume_on_film(const PartialImage& previous, Film& film);

}  // namespace rimu
