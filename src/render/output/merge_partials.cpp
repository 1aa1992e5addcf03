#include "render/output/merge_partials.h"

#include <algorithm>
#include <ctime>
#include <ostream>

#include "render/output/output_file.h"
#include "render/output/partial_exr.h"
#include "spectral/error.h"
#include "spectral/library/spectral_library.h"

namespace rimu {
namespace {

std::string crop_text(const PixelBounds& b) {
  return std::to_string(b.x0) + "," + std::to_string(b.y0) + "," + std::to_string(b.x1) + "," + std::to_string(b.y1);
}

// The two partials must come from the same render: the first difference is an error naming both files.
void check_same_render(const PartialImage& a, const PartialImage& b) {
  auto mismatch = [&](const std::string& what, const std::string& va, const std::string& vb) {
    throw InputError({b.path.string(), 0, ""}, "does not belong to the same render as " + a.path.string() + ": " +
                                                   what + " " + vb + " here, " + va + " there");
  };
  if (a.record.seed != b.record.seed) mismatch("seed", std::to_string(a.record.seed), std::to_string(b.record.seed));
  if (a.width != b.width || a.height != b.height)
    mismatch("resolution", std::to_string(a.width) + "x" + std::to_string(a.height),
             std::to_string(b.width) + "x" + std::to_string(b.height));
  if (a.record.total_spp != b.record.total_spp)
    mismatch("total samples per pixel", std::to_string(a.record.total_spp), std::to_string(b.record.total_spp));
  if (a.record.film_spec != b.record.film_spec) mismatch("film", a.record.film_spec, b.record.film_spec);
  if (a.spectral_bins != b.spectral_bins)
    mismatch("spectral bins", std::to_string(a.spectral_bins), std::to_string(b.spectral_bins));
  if (a.light_groups != b.light_groups)
    mismatch("light groups (rimu:lightGroups)", "'" + light_groups_text(a.light_groups) + "'",
             "'" + light_groups_text(b.light_groups) + "'");
  bool same_transform = a.record.output_transform.scale == b.record.output_transform.scale;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      same_transform = same_transform && a.record.output_transform.channel_matrix(r, c) ==
                                             b.record.output_transform.channel_matrix(r, c);
  if (!same_transform)
    mismatch("exposure or white balance", "one", "another");
  // Before the hash, which the clamp also changes: a clamped sample's weight is not that of an unclamped one.
  const auto clamp_of = [](const PartialImage& p) {
    return p.max_sample_value ? std::to_string(*p.max_sample_value) : std::string("none");
  };
  if (a.max_sample_value != b.max_sample_value) mismatch("sample clamp (max_sample_value)", clamp_of(a), clamp_of(b));
  // Before the hash (which a guiding option also changes): say plainly why guided and unguided partials do not mix.
  // Each partial trains its own field, so the merge of guided partials is unbiased; a mix is refused because it
  // is not the render either command asked for (docs/farm.md).
  const auto guiding_of = [](const PartialImage& p) {
    const auto it = p.metadata.extra.find("guiding");
    return it == p.metadata.extra.end() ? std::string("off") : it->second;
  };
  if (guiding_of(a) != guiding_of(b)) mismatch("path guiding (rimu:guiding)", guiding_of(a), guiding_of(b));
  if (a.record.scene_hash != b.record.scene_hash)
    mismatch("the scene (its file, the files it names, or image options) differs: scene hash", a.record.scene_hash,
             b.record.scene_hash);
  if (a.pixel_type != b.pixel_type)
    mismatch("pixel type", a.pixel_type == ExrPixelType::half ? "half" : "float",
             b.pixel_type == ExrPixelType::half ? "half" : "float");
}

std::vector<SampleRange> union_of(std::vector<SampleRange> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const SampleRange& x, const SampleRange& y) { return x.begin < y.begin; });
  std::vector<SampleRange> out;
  for (const SampleRange& r : ranges) {
    if (!out.empty() && r.begin <= out.back().end) out.back().end = std::max(out.back().end, r.end);
    else out.push_back(r);
  }
  return out;
}

// [0, total) minus the (sorted, disjoint) ranges.
std::vector<SampleRange> missing_ranges(const std::vector<SampleRange>& held, int total) {
  std::vector<SampleRange> missing;
  int at = 0;
  for (const SampleRange& r : held) {
    if (r.begin > at) missing.push_back({at, r.begin});
    at = std::max(at, r.end);
  }
  if (at < total) missing.push_back({at, total});
  return missing;
}

}  // namespace

MergeResult merge_partials(const std::vector<std::filesystem::path>& inputs, const std::filesystem::path& output,
                           const MergeOptions& options, std::ostream& log) {
  if (inputs.empty()) throw InputError({"", 0, "merge"}, "no partial renders to merge");
  if (lower_case_extension(output) != "exr")
    throw InputError({output.string(), 0, "-o"}, "the merged image needs a name ending in .exr");
  check_output_path(output);
  std::vector<InputFile> partials;
  for (const auto& path : inputs) partials.push_back({path, "a partial"});
  check_output_not_input(output, "-o", partials);  // -o q0.exr would replace q0.exr's exact sums
  std::vector<PartialImage> parts;
  for (const auto& path : inputs) {
    parts.push_back(read_partial_exr(path, false));  // headers first: every check before any pixel is read
    check_same_render(parts.front(), parts.back());
  }
  // A fixed summation order, whatever the order on the command line.
  std::sort(parts.begin(), parts.end(), [](const PartialImage& a, const PartialImage& b) {
    const int fa = a.record.samples.empty() ? 0 : a.record.samples.front().begin;
    const int fb = b.record.samples.empty() ? 0 : b.record.samples.front().begin;
    if (fa != fb) return fa < fb;
    if (a.crop.y0 != b.crop.y0) return a.crop.y0 < b.crop.y0;
    return a.crop.x0 < b.crop.x0;
  });

  // No sample of a pixel twice.
  for (size_t i = 0; i < parts.size(); ++i)
    for (size_t j = i + 1; j < parts.size(); ++j) {
      const PixelBounds common = parts[i].crop.intersect(parts[j].crop);
      if (common.empty()) continue;
      for (const SampleRange& a : parts[i].record.samples)
        for (const SampleRange& b : parts[j].record.samples)
          if (a.overlaps(b))
            throw InputError({parts[j].path.string(), 0, ""},
                             "overlaps " + parts[i].path.string() + ": both hold samples " +
                                 SampleRange{std::max(a.begin, b.begin), std::min(a.end, b.end)}.text() +
                                 " of pixels " + crop_text(common) + " (x0,y0,x1,y1); merging would count them twice");
    }

  // The result's window and each pixel's sample count: a gap is a pixel with fewer than total_spp samples.
  PixelBounds window = parts.front().crop;
  for (const PartialImage& p : parts)
    window = {std::min(window.x0, p.crop.x0), std::min(window.y0, p.crop.y0), std::max(window.x1, p.crop.x1),
              std::max(window.y1, p.crop.y1)};
  std::vector<int> held(size_t(window.area()), 0);
  std::vector<SampleRange> all_ranges;
  bool same_crops = true;
  for (const PartialImage& p : parts) {
    int count = 0;
    for (const SampleRange& r : p.record.samples) count += r.count();
    for (int y = p.crop.y0; y < p.crop.y1; ++y)
      for (int x = p.crop.x0; x < p.crop.x1; ++x)
        held[size_t(y - window.y0) * size_t(window.width()) + size_t(x - window.x0)] += count;
    all_ranges.insert(all_ranges.end(), p.record.samples.begin(), p.record.samples.end());
    same_crops = same_crops && p.crop == parts.front().crop;
  }
  const int total = parts.front().record.total_spp;
  MergeResult result;
  result.samples = union_of(all_ranges);
  result.samples_per_pixel = *std::min_element(held.begin(), held.end());
  result.complete = result.samples_per_pixel == total;
  if (!result.complete) {
    std::string what;
    if (same_crops) {
      what = "no partial holds samples " + sample_ranges_text(missing_ranges(result.samples, total)) + " of " +
             std::to_string(total);
    } else {
      const auto short_pixels = std::count_if(held.begin(), held.end(), [&](int n) { return n < total; });
      what = std::to_string(short_pixels) + " pixels of the window " + crop_text(window) + " have fewer than " +
             std::to_string(total) + " samples (the fewest: " + std::to_string(result.samples_per_pixel) +
             "); a crop tile or sample range is missing";
    }
    if (!options.allow_gaps)
      throw InputError({"", 0, "merge"}, "the partials do not cover the render: " + what +
                                             " (render them, or merge with --allow-gaps to write what there is)");
    log << "rimu merge: warning: " << what << "; the result holds " << sample_ranges_text(result.samples) << "\n";
  }

  // The sum, in the order above.
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const PartialImage& first = parts.front();
  PartialImage shape = first;  // the window and film of the result, without sums
  shape.crop = window;
  shape.counts = {};
  const std::unique_ptr<Film> film = film_from_partial(shape, library);
  double render_time_s = 0.0;
  for (const PartialImage& p : parts) {  // one band of one partial's sums in memory at a time
    add_partial_exr_to_film(p, *film);
    render_time_s += p.metadata.render_time_s;
  }

  ExrOptions exr;
  exr.pixel_type = first.pixel_type;
  exr.metadata = first.metadata;
  exr.metadata.samples_per_pixel = result.samples_per_pixel;
  exr.metadata.render_time_s = render_time_s;  // CPU-side total over the partials (their wall-clock sum)
  exr.metadata.interrupted = false;
  exr.metadata.finished_at = std::time(nullptr);
  exr.metadata.extra["mergedFrom"] = std::to_string(parts.size()) + " partial renders";
  if (options.keep_sums) {
    PartialRecord record = first.record;
    record.samples = result.samples;
    if (!result.samples.empty()) record.requested = {result.samples.front().begin, result.samples.back().end};
    exr.partial = record;
  }
  if (exr.pixel_type == ExrPixelType::half) {
    const std::string warning = half_range_warning(half_range_counts(*film), output.string());
    if (!warning.empty()) log << warning << "\n";
  }
  const size_t replaced = write_exr(output, *film, exr);
  if (replaced > 0)
    log << "rimu merge: warning: " << replaced << " values were NaN or beyond the largest float and were replaced\n";
  log << "rimu merge: wrote " << output.string() << " from " << parts.size() << " partials: samples "
      << sample_ranges_text(result.samples) << " of " << total << (result.complete ? "" : " (incomplete)") << "\n";
  return result;
}

}  // namespace rimu
