// What a partial render (a sample range of every pixel, or a checkpoint) records besides its pixels, so that
// partials can be merged (render/output/merge_partials.h) and a checkpoint resumed (render/render_job.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/film/film_output_transform.h"

namespace rimu {

/// Sample indices [begin, end) of every pixel (the Sobol' sequence of a pixel is indexed by sample, so two
/// disjoint ranges are disjoint sets of samples).
struct SampleRange {
  int begin = 0, end = 0;

  int count() const { return end - begin; }
  bool overlaps(const SampleRange& o) const { return begin < o.end && o.begin < end; }
  /// "a:b" (as --samples takes it).
  std::string text() const { return std::to_string(begin) + ":" + std::to_string(end); }
  friend bool operator==(const SampleRange&, const SampleRange&) = default;
};

/// Parses "a:b" (0 <= a < b <= 2^24): InputError naming `option` otherwise.
SampleRange parse_sample_range(const std::string& text, const std::string& option);
/// A duration such as "30s", "10m", "1h" or "90" (seconds) as seconds > 0: InputError naming `option` otherwise.
double parse_duration_s(const std::string& text, const std::string& option);

/// "0:64,128:256" for a sorted list of ranges ("" for none); parse_sample_ranges() reads it back (InputError naming
/// `where`).
std::string sample_ranges_text(const std::vector<SampleRange>& ranges);
std::vector<SampleRange> parse_sample_ranges(const std::string& text, const std::string& where);

/// The partial's identity and accounting, written as "rimu:partial:*" attributes (docs/farm.md).
struct PartialRecord {
  /// scene_hash(): the scene file's bytes and the options that change the image (not the seed, the samples or the
  /// crop, which are checked on their own so that a mismatch gets a precise message).
  std::string scene_hash;
  uint64_t seed = 0;
  std::vector<SampleRange> samples;  ///< the sample ranges whose sums the file holds (sorted, disjoint)
  SampleRange requested;             ///< what the job that wrote it was asked for (a checkpoint has less)
  int total_spp = 0;                 ///< the whole render's samples per pixel: a merge covers [0, total_spp)
  std::string film_spec;             ///< SpectralResponse::from_spec() text, or "rgb-transport"
  FilmOutputTransform output_transform;  ///< exposure and white balance, exactly
  std::string job;                   ///< the render job as JSON (render_job_json), for --resume
};

}  // namespace rimu
