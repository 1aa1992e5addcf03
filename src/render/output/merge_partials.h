// Merging partial renders (sample ranges and/or crop windows of one render) into the image one process would have
// written for their union. The `rimu merge` subcommand is a thin parser in front of merge_partials().
#pragma once

#include <filesystem>
#include <iosfwd>
#include <vector>

#include "render/output/partial_record.h"

namespace rimu {

struct MergeOptions {
  /// Write even if some pixels lack some of the samples [0, total spp): a warning names what is missing and the
  /// result records the ranges it holds (rimu:partial:samples), so the missing ones can be rendered and merged later.
  /// Without it a gap is an error.
  bool allow_gaps = false;
  /// Write the exact accumulators too (the result is itself a partial: it can be merged again, as in a tree of
  /// merges, or resumed). Without them the file has only the image channels, as a plain render writes.
  bool keep_sums = true;
};

struct MergeResult {
  std::vector<SampleRange> samples;  ///< the ranges the result holds (of every pixel, when the crops agree)
  int samples_per_pixel = 0;         ///< the fewest samples any pixel of the result has
  bool complete = false;             ///< every pixel has all of [0, total spp)
};

/// Reads the partials, checks that they belong together (same scene hash, seed, total spp, film, resolution,
/// spectral bins, output transform, pixel type) and that no two hold the same sample of the same pixel, then writes
/// their sum to `output` atomically. The result's data window is the bounding box of the partials' crops.
///
/// Exactness: each pixel's sums are added in a fixed order (partials sorted by first sample, then crop), whatever
/// the order of `inputs`. A pixel held by one partial is copied bit for bit. A single process adds its passes one
/// at a time into one running double sum; the merge adds the partials' double sums, and a range that cuts a pass
/// splits that pass's tile sums, so a pixel's double sums are the same m non-negative terms in another
/// association: they differ by at most 2 (m - 1) 2^-53 relative (m = the samples reaching the pixel, a few hundred
/// to thousands), far below a float32 unit (2^-24). The written float32 (or half) values therefore equal the single
/// process's or differ by one unit in the last place where the two doubles straddle a rounding boundary of the
/// written type (tests/render/merge_partials_test.cpp).
///
/// Throws InputError (nothing written) for unreadable inputs, mismatches, overlaps and, unless allowed, gaps;
/// OutputError if the output cannot be written.
MergeResult merge_partials(const std::vector<std::filesystem::path>& inputs, const std::filesystem::path& output,
                           const MergeOptions& options, std::ostream& log);

}  // namespace rimu
