#include "render/output/partial_exr.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <set>

#include "render/image/exr_input.h"
#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {
namespace {

InputError partial_error(const std::filesystem::path& path, const std::string& what) {
  return InputError({path.string(), 0, ""}, what);
}

const std::string& string_attribute(const Imf::Header& h, const std::filesystem::path& path, const char* name) {
  const auto* a = h.findTypedAttribute<Imf::StringAttribute>(name);
  if (!a)
    throw partial_error(path, std::string("not a partial render: no '") + name +
                                  "' attribute (render it with --samples or --checkpoint)");
  return a->value();
}

// Attributes that write_exr derives itself from the film, the RenderMetadata fields or the PartialRecord: every
// other "rimu:*" string is copied as RenderMetadata::extra.
bool derived_attribute(const std::string& name) {
  static const std::set<std::string> derived = {"rimu:version", "rimu:filmResponse", "rimu:camera", "rimu:seed",
                                                "rimu:scene", "rimu:interrupted", "rimu:lightGroups",
                                                "rimu:whiteBalanceTarget"};
  return derived.count(name) > 0 || name.rfind("rimu:partial:", 0) == 0;
}

// Calls band(first_row, rows, sums) for successive bands of rows of the partial's crop, sums holding the
// accumulators of rows·crop width pixels (accumulators_per_pixel doubles each, row by row), exactly: two UINT words
// per double. Only one band is in memory at a time, so a 4K spectral partial (GBs of sums) is read in bounded memory.
template <typename Band>
void for_each_sum_band(Imf::InputFile& file, const PartialImage& p, const Band& band) {
  // EXR has no 64-bit type: each double is two UINT channels, read here straight into the double's halves (the
  // high word at byte 4 on a little-endian machine), so the bits come back exactly and without a second buffer.
  static_assert(std::endian::native == std::endian::little, "the sum slices assume a little-endian double");
  constexpr int kBandRows = 64;
  const int n = p.accumulators_per_pixel;
  const size_t width = size_t(p.crop.width());
  const size_t pixel_stride = sizeof(double) * size_t(n);
  std::vector<double> sums(size_t(n) * width * kBandRows);
  for (int y0 = p.crop.y0; y0 < p.crop.y1; y0 += kBandRows) {
    const int y1 = std::min(y0 + kBandRows, p.crop.y1);  // exclusive
    Imf::FrameBuffer frame_buffer;
    // Accumulator k of pixel (x, y) of the band at sums[((y - y0) · width + x - x0) · n + k].
    char* origin = reinterpret_cast<char*>(sums.data()) -
                   (ptrdiff_t(y0) * ptrdiff_t(width) + p.crop.x0) * ptrdiff_t(pixel_stride);
    for (int k = 0; k < n; ++k)
      for (const bool high : {true, false})
        frame_buffer.insert(partial_sum_channel_name(k, high),
                            Imf::Slice(Imf::UINT, origin + sizeof(double) * size_t(k) + (high ? 4 : 0), pixel_stride,
                                       pixel_stride * width));
    try {
      file.setFrameBuffer(frame_buffer);
      file.readPixels(y0, y1 - 1);
    } catch (const std::exception& e) {
      throw partial_error(p.path, std::string("cannot read its pixels: ") + e.what());
    }
    band(y0, y1 - y0, static_cast<const double*>(sums.data()));
  }
}

// The header's windows and accumulator count size what the merge allocates (a film over the data window, a band
// of sums): check them against a render Rimu can write and against the file before anything is allocated.
void check_partial_size(const PartialImage& p, std::uintmax_t file_bytes) {
  const auto fail = [&p](const std::string& what) { throw partial_error(p.path, what); };
  // A scene's film is at most 32768 × 32768 pixels with at most 471 spectral bins (docs/scene-format.md). The
  // number of light groups has no cap: the sums' size is bounded by the file's (below).
  constexpr int kMaxSide = 1 << 15, kMaxBins = 471;
  if (p.width < 1 || p.height < 1 || p.width > kMaxSide || p.height > kMaxSide)
    fail("its display window is " + std::to_string(p.width) + " x " + std::to_string(p.height) +
         " pixels; a render has 1 to 32768 pixels a side");
  if (p.crop.empty() || p.crop.x0 < 0 || p.crop.y0 < 0 || p.crop.x1 > p.width || p.crop.y1 > p.height)
    fail("its data window does not lie inside its display window (a partial render's crop must)");
  if (p.spectral_bins < 0 || p.spectral_bins > kMaxBins)
    fail("rimu:partial:spectralBins is " + std::to_string(p.spectral_bins) + "; a film has 0 to 471 spectral bins");
  // The accumulators: 3 channel sums, the weight, the N bins, and per light group 3 channel sums and N bins
  // (render/film/film_tile.h), in 64 bits: a damaged header's group list may be long.
  const int64_t expected = int64_t(FilmTile::kFirstBin) + p.spectral_bins +
                           int64_t(p.light_groups.size()) * (3 + int64_t(p.spectral_bins));
  if (p.accumulators_per_pixel != expected)
    fail("rimu:partial:accumulators is " + std::to_string(p.accumulators_per_pixel) + ", but " +
         std::to_string(p.spectral_bins) + " spectral bins and " + std::to_string(p.light_groups.size()) +
         " light groups (rimu:lightGroups) make " + std::to_string(expected));
  // The sums are two 32-bit words per accumulator per pixel, compressed by deflate (ZIP), which expands at most
  // 1032:1: a header claiming more than that is damaged, and the merge would allocate for it.
  const std::uintmax_t sum_bytes = std::uintmax_t(p.crop.area()) * std::uintmax_t(p.accumulators_per_pixel) * 8;
  if (sum_bytes > 1032 * file_bytes)
    fail("its header claims " + std::to_string(p.crop.width()) + " x " + std::to_string(p.crop.height()) +
         " pixels of " + std::to_string(p.accumulators_per_pixel) + " accumulators (" + format_bytes(sum_bytes) +
         " of sums), more than a file of " + format_bytes(file_bytes) + " can hold (deflate expands at most 1032:1)");
}

}  // namespace

PartialImage read_partial_exr(const std::filesystem::path& path, bool with_sums) {
  PartialImage p;
  p.path = path;
  const std::uintmax_t file_bytes = check_input_file(path, kMaxBinaryFileBytes);  // a FIFO would block OpenEXR
  const std::unique_ptr<Imf::InputFile> file = open_exr_input(path);
  const Imf::Header& h = file->header();
  PartialRecord& r = p.record;
  r.scene_hash = string_attribute(h, path, "rimu:partial:sceneHash");
  r.samples = parse_sample_ranges(string_attribute(h, path, "rimu:partial:samples"), path.string() + ": rimu:partial:samples");
  r.requested = parse_sample_range(string_attribute(h, path, "rimu:partial:requested"), path.string() + ": rimu:partial:requested");
  r.film_spec = string_attribute(h, path, "rimu:partial:film");
  r.job = string_attribute(h, path, "rimu:partial:job");
  try {
    r.seed = std::stoull(string_attribute(h, path, "rimu:seed"));
  } catch (const std::invalid_argument&) {
    throw partial_error(path, "rimu:seed is not a number");
  }
  const auto* total = h.findTypedAttribute<Imf::IntAttribute>("rimu:partial:totalSpp");
  const auto* accumulators = h.findTypedAttribute<Imf::IntAttribute>("rimu:partial:accumulators");
  const auto* matrix = h.findTypedAttribute<Imf::M33dAttribute>("rimu:partial:outputMatrix");
  const auto* scale = h.findTypedAttribute<Imf::DoubleAttribute>("rimu:partial:outputScale");
  if (!total || !accumulators || !matrix || !scale)
    throw partial_error(path, "not a partial render: its rimu:partial:* record is incomplete");
  r.total_spp = total->value();
  p.accumulators_per_pixel = accumulators->value();
  for (int row = 0; row < 3; ++row)
    for (int c = 0; c < 3; ++c) r.output_transform.channel_matrix(row, c) = matrix->value()[row][c];
  r.output_transform.scale = scale->value();

  const Imath::Box2i& display = h.displayWindow();
  const Imath::Box2i& data = h.dataWindow();
  // In 64 bits: a damaged header's corners may be ±2^31 apart. check_partial_size refuses what is out of range.
  const int64_t display_width = int64_t(display.max.x) - display.min.x + 1;
  const int64_t display_height = int64_t(display.max.y) - display.min.y + 1;
  p.width = int(std::clamp<int64_t>(display_width, 0, int64_t(1) << 30));
  p.height = int(std::clamp<int64_t>(display_height, 0, int64_t(1) << 30));
  if (int64_t(data.max.x) + 1 > INT32_MAX || int64_t(data.max.y) + 1 > INT32_MAX)
    throw partial_error(path, "its data window reaches beyond 2^31 pixels");
  p.crop = {data.min.x, data.min.y, data.max.x + 1, data.max.y + 1};
  if (const auto* groups = h.findTypedAttribute<Imf::StringAttribute>("rimu:lightGroups"))
    p.light_groups = parse_light_groups_text(groups->value());
  if (const auto* bins = h.findTypedAttribute<Imf::IntAttribute>("rimu:partial:spectralBins")) {
    p.spectral_bins = bins->value();
  } else {
    // Written before the attribute existed, when a light group kept 3 sums and no bins: 4 + N + 3·G. Its sums are
    // laid out as a film now lays out only a partial without bins or without groups.
    const int64_t bins_before = int64_t(p.accumulators_per_pixel) - FilmTile::kFirstBin -
                                3 * int64_t(p.light_groups.size());
    if (bins_before > 0 && !p.light_groups.empty())
      throw partial_error(path, "was written by an older Rimu whose light-group layers had no spectral bins "
                                "(no rimu:partial:spectralBins); render it again to merge, resume or display it");
    if (bins_before < 0)
      throw partial_error(path, "rimu:partial:accumulators is " + std::to_string(p.accumulators_per_pixel) +
                                    ", fewer than 4 plus 3 per light group in rimu:lightGroups");
    p.spectral_bins = int(std::min<int64_t>(bins_before, 1 << 20));
  }
  check_partial_size(p, file_bytes);
  const Imf::Channel* first = h.channels().findChannel(h.channels().begin().name());
  p.pixel_type = first && first->type == Imf::FLOAT ? ExrPixelType::float32 : ExrPixelType::half;

  // The accumulators, exactly: two UINT words per double, read a band of rows at a time (for_each_sum_band).
  const int n = p.accumulators_per_pixel;
  for (int k = 0; k < 2 * n; ++k) {
    const std::string name = partial_sum_channel_name(k / 2, k % 2 == 0);
    const Imf::Channel* channel = h.channels().findChannel(name);
    if (!channel || channel->type != Imf::UINT)
      throw partial_error(path, "not a partial render: no UINT channel '" + name + "'");
  }
  if (with_sums) {
    p.sums.resize(size_t(p.crop.area()) * size_t(n));
    for_each_sum_band(*file, p, [&](int first_row, int rows, const double* sums) {
      std::copy_n(sums, size_t(rows) * size_t(p.crop.width()) * size_t(n),
                  &p.sums[size_t(first_row - p.crop.y0) * size_t(p.crop.width()) * size_t(n)]);
    });
  }

  auto count = [&](const char* name) -> uint64_t {
    const auto* a = h.findTypedAttribute<Imf::DoubleAttribute>(name);
    if (!a) return 0;
    // Counts are whole numbers below 2^53 (exact in a double); anything else is a damaged header, not a count.
    if (!(a->value() >= 0.0 && a->value() <= 0x1p53))
      throw partial_error(path, std::string(name) + " is not a sample count");
    return uint64_t(a->value());
  };
  p.counts = {count("rimu:samplesAccepted"), count("rimu:discardedNaN"), count("rimu:discardedInf"),
              count("rimu:discardedNegative"), count("rimu:samplesClamped")};

  RenderMetadata& m = p.metadata;
  m.seed = r.seed;
  if (const auto* a = h.findTypedAttribute<Imf::IntAttribute>("rimu:spp")) m.samples_per_pixel = a->value();
  if (const auto* a = h.findTypedAttribute<Imf::DoubleAttribute>("rimu:renderTimeSeconds")) m.render_time_s = a->value();
  if (const auto* a = h.findTypedAttribute<Imf::DoubleAttribute>("rimu:maxSampleValue")) p.max_sample_value = a->value();
  if (const auto* a = h.findTypedAttribute<Imf::StringAttribute>("rimu:scene")) m.scene = a->value();
  if (Imf::hasIsoSpeed(h) && Imf::hasExpTime(h) && Imf::hasAperture(h)) {
    PhysicalCameraSettings camera;
    camera.iso = Imf::isoSpeed(h);
    camera.shutter_s = Imf::expTime(h);
    camera.f_number = Imf::aperture(h);
    m.camera = camera;
  }
  if (const auto* a = h.findTypedAttribute<Imf::M33fAttribute>("cameraToXYZ")) {
    Matrix3 c;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) c(row, col) = a->value()[row][col];
    m.camera_to_xyz = c;
    if (const auto* e = h.findTypedAttribute<Imf::DoubleAttribute>("rimu:cameraToXYZMeanDeltaE2000"))
      m.camera_to_xyz_mean_delta_e2000 = e->value();
  }
  for (auto it = h.begin(); it != h.end(); ++it) {
    const std::string name = it.name();
    if (name.rfind("rimu:", 0) != 0 || derived_attribute(name)) continue;
    if (const auto* a = dynamic_cast<const Imf::StringAttribute*>(&it.attribute())) m.extra[name.substr(5)] = a->value();
  }
  return p;
}

std::unique_ptr<Film> film_from_partial(const PartialImage& partial, SpectralLibrary& library) {
  // A colour-corrected camera film is rebuilt under its white balance's name ("rimu:whiteBalance"), for the
  // description the merged image carries; its sums are already the film's, so the curves are not used again.
  const auto white = partial.metadata.extra.find("whiteBalance");
  SpectralResponse response =
      partial.record.film_spec == "rgb-transport"
          ? SpectralResponse::rgb_transport(library)
          : SpectralResponse::from_spec(library, partial.record.film_spec, nullptr,
                                        white == partial.metadata.extra.end() ? "D65" : white->second);
  FilmOptions options{partial.width, partial.height, partial.crop, partial.spectral_bins};
  auto film = std::make_unique<Film>(options, std::move(response), partial.light_groups);
  film->set_output_transform(partial.record.output_transform);
  film->set_max_sample_value(partial.max_sample_value);  // (for the metadata: the sums are already clamped)
  add_partial_to_film(partial, *film);
  return film;
}

ResumePoint resume_on_film(const PartialImage& previous, Film& film) {
  if (previous.crop != film.pixel_bounds() || previous.spectral_bins != film.binning().count)
    throw InputError({previous.path.string(), 0, ""}, "its window or spectral bins differ from its recorded job's");
  if (previous.light_groups != film.light_groups())
    throw InputError({previous.path.string(), 0, ""},
                     "its light groups (" + light_groups_text(previous.light_groups) + ") differ from its scene's (" +
                         light_groups_text(film.light_groups()) + ")");
  add_partial_to_film(previous, film);
  return {previous.record.samples.front().end, previous.metadata.render_time_s};
}

void add_partial_to_film(const PartialImage& partial, Film& film) {
  if (partial.sums.empty()) return;  // a header only
  FilmTile tile = film.make_tile(partial.crop);
  const int n = partial.accumulators_per_pixel;
  size_t i = 0;
  for (int y = partial.crop.y0; y < partial.crop.y1; ++y)
    for (int x = partial.crop.x0; x < partial.crop.x1; ++x, ++i)
      for (int k = 0; k < n; ++k) tile.pixel(x, y)[k] = partial.sums[i * size_t(n) + size_t(k)];
  tile.add_sample_counts(partial.counts);
  film.merge_tile(tile);
}

void add_partial_exr_to_film(const PartialImage& header, Film& film) {
  const std::unique_ptr<Imf::InputFile> file = open_exr_input(header.path);
  const int n = header.accumulators_per_pixel;
  bool counted = false;
  for_each_sum_band(*file, header, [&](int first_row, int rows, const double* sums) {
    FilmTile tile = film.make_tile({header.crop.x0, first_row, header.crop.x1, first_row + rows});
    size_t i = 0;
    for (int y = first_row; y < first_row + rows; ++y)
      for (int x = header.crop.x0; x < header.crop.x1; ++x, ++i)
        std::copy_n(&sums[i * size_t(n)], n, tile.pixel(x, y));
    if (!counted) tile.add_sample_counts(header.counts);
    counted = true;
    film.merge_tile(tile);
  });
}

}  // namespace rimu
