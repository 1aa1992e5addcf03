#include "render/output/exr_output.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <vector>

#include "render/output/output_file.h"
#include "spectral/version.h"

namespace rimu {
namespace {

constexpr float kHalfMax = 65504.0f;  // the largest finite half (IEEE 754 binary16)

// One channel's pixels over the data window, in the type the file stores.
struct ChannelBuffer {
  std::string name;
  std::vector<float> floats;
  std::vector<half> halves;
};

void add_string(Imf::Header& h, const std::string& name, const std::string& value) {
  h.insert(name, Imf::StringAttribute(value));
}

// OpenEXR's capDate ("YYYY:MM:DD hh:mm:ss", local time) and utcOffset (seconds, UTC minus local time).
void add_capture_time(Imf::Header& h, std::time_t when) {
  std::tm local{};
  if (!localtime_r(&when, &local)) return;
  char text[32];
  if (std::strftime(text, sizeof(text), "%Y:%m:%d %H:%M:%S", &local) == 0) return;
  Imf::addCapDate(h, text);
  Imf::addUtcOffset(h, float(-local.tm_gmtoff));
}

// The value written for `v`: finite and inside the type's range (NaN → 0, ±Inf or beyond → ± the largest).
float writable(double v, float largest, size_t& replaced) {
  if (std::isnan(v)) {
    ++replaced;
    return 0.0f;
  }
  if (std::abs(v) > double(largest)) {
    if (std::isinf(v) || largest == std::numeric_limits<float>::max()) ++replaced;
    return v > 0 ? largest : -largest;
  }
  return float(v);
}

Imf::Header make_header(const Film& film, const ExrOptions& options) {
  const PixelBounds& b = film.pixel_bounds();
  const Imath::Box2i display_window(Imath::V2i(0, 0), Imath::V2i(film.width() - 1, film.height() - 1));
  const Imath::Box2i data_window(Imath::V2i(b.x0, b.y0), Imath::V2i(b.x1 - 1, b.y1 - 1));
  Imf::Header h(display_window, data_window);
  h.compression() = Imf::ZIP_COMPRESSION;

  const SpectralResponse& response = film.response();
  if (response.kind() == ResponseKind::cie_xyz) {
    // ImfChromaticities.h: the (x, y) of the pixel triples (1,0,0), (0,1,0), (0,0,1), (1,1,1). With X, Y, Z in the
    // three channels these are the chromaticities of pure X, pure Y, pure Z and equal XYZ.
    Imf::addChromaticities(h, Imf::Chromaticities(Imath::V2f(1.0f, 0.0f), Imath::V2f(0.0f, 1.0f),
                                                  Imath::V2f(0.0f, 0.0f), Imath::V2f(1.0f / 3.0f, 1.0f / 3.0f)));
    // Of the written Y: an exposed film (Film::output_transform) has Y scaled by the exposure.
    const double nits_per_y = response.luminance_nits_per_unit_y() / film.output_transform().scale;
    h.insert("rimu:luminanceNitsPerUnitY", Imf::DoubleAttribute(nits_per_y));
    Imf::addWhiteLuminance(h, float(nits_per_y));  // the luminance of the written (1, 1, 1), i.e. of Y = 1
  } else {
    add_string(h, "rimu:camera", response.camera_name());
    if (options.metadata.camera_to_xyz) {
      Imath::M33f m;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m[r][c] = float((*options.metadata.camera_to_xyz)(r, c));
      h.insert("cameraToXYZ", Imf::M33fAttribute(m));
      h.insert("rimu:cameraToXYZMeanDeltaE2000", Imf::DoubleAttribute(options.metadata.camera_to_xyz_mean_delta_e2000));
    }
  }
  add_string(h, "rimu:version", rimu_version());
  add_string(h, "software", std::string("Rimu ") + rimu_version());
  Imf::addComments(h, std::string("Rendered by Rimu ") + rimu_version() +
                          (options.metadata.scene.empty() ? std::string() : " from " + options.metadata.scene));
  if (options.metadata.camera) {
    Imf::addIsoSpeed(h, float(options.metadata.camera->iso));
    Imf::addExpTime(h, float(options.metadata.camera->shutter_s));
    Imf::addAperture(h, float(options.metadata.camera->f_number));
  }
  if (options.metadata.finished_at != 0) add_capture_time(h, options.metadata.finished_at);
  add_string(h, "rimu:filmResponse", response.description());
  // The white balance the written channels carry (v = scale · M · film value), exactly, so that `rimu display
  // --white-balance` can undo it and show another white; rimu:whiteBalance names the white it adapts from.
  const Matrix3& white_balance = film.output_transform().channel_matrix;
  if (white_balance.m != Matrix3::identity().m) {
    Imath::M33d m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = white_balance(r, c);
    h.insert("rimu:whiteBalanceMatrix", Imf::M33dAttribute(m));
    add_string(h, "rimu:whiteBalanceTarget",
               response.kind() == ResponseKind::cie_xyz ? "D65" : "equal R, G, B (G kept)");
  }

  const RenderMetadata& m = options.metadata;
  h.insert("rimu:spp", Imf::IntAttribute(m.samples_per_pixel));
  add_string(h, "rimu:seed", std::to_string(m.seed));
  h.insert("rimu:renderTimeSeconds", Imf::DoubleAttribute(m.render_time_s));
  const FilmSampleCounts counts = film.sample_counts();
  h.insert("rimu:samplesAccepted", Imf::DoubleAttribute(double(counts.accepted)));
  h.insert("rimu:discardedNaN", Imf::DoubleAttribute(double(counts.nan)));
  h.insert("rimu:discardedInf", Imf::DoubleAttribute(double(counts.infinite)));
  h.insert("rimu:discardedNegative", Imf::DoubleAttribute(double(counts.negative)));
  if (film.max_sample_value()) {
    h.insert("rimu:maxSampleValue", Imf::DoubleAttribute(*film.max_sample_value()));
    h.insert("rimu:samplesClamped", Imf::DoubleAttribute(double(counts.clamped)));
  }
  if (!m.scene.empty()) add_string(h, "rimu:scene", m.scene);
  if (m.interrupted) add_string(h, "rimu:interrupted", "interrupted at " + std::to_string(m.samples_per_pixel) + " spp");
  for (const auto& [key, value] : m.extra) add_string(h, "rimu:" + key, value);
  if (options.partial) {
    const PartialRecord& p = *options.partial;
    add_string(h, "rimu:partial:sceneHash", p.scene_hash);
    add_string(h, "rimu:partial:samples", sample_ranges_text(p.samples));
    add_string(h, "rimu:partial:requested", p.requested.text());
    h.insert("rimu:partial:totalSpp", Imf::IntAttribute(p.total_spp));
    add_string(h, "rimu:partial:film", p.film_spec);
    add_string(h, "rimu:partial:job", p.job);
    h.insert("rimu:partial:accumulators", Imf::IntAttribute(film.accumulators_per_pixel()));
    // The layout of the accumulators (4 + N + G·(3 + N)): with it the reader needs no arithmetic guess, and a
    // partial written before light groups carried spectral bins (no such attribute) is told apart.
    h.insert("rimu:partial:spectralBins", Imf::IntAttribute(film.binning().count));
    Imath::M33d m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = p.output_transform.channel_matrix(r, c);
    h.insert("rimu:partial:outputMatrix", Imf::M33dAttribute(m));
    h.insert("rimu:partial:outputScale", Imf::DoubleAttribute(p.output_transform.scale));
  }
  if (!film.light_groups().empty()) add_string(h, "rimu:lightGroups", light_groups_text(film.light_groups()));
  if (film.binning().count > 0) {
    add_string(h, "spectralLayoutVersion", "1.0");
    // Fichet et al. 2021's emissive layout: S0 channels of spectral radiance (per nm: the mean over each bin).
    add_string(h, "emissiveUnits", "W.m^-2.sr^-1");
  }
  return h;
}

}  // namespace

std::string partial_sum_channel_name(int accumulator, bool high_word) {
  char name[32];
  std::snprintf(name, sizeof(name), "rimu.sum.%02d.%s", accumulator, high_word ? "hi" : "lo");
  return name;
}

std::string light_groups_text(const std::vector<std::string>& groups) {
  std::string text;
  for (const std::string& g : groups) text += (text.empty() ? "" : ",") + g;
  return text;
}

std::vector<std::string> parse_light_groups_text(const std::string& text) {
  std::vector<std::string> groups;
  if (text.empty()) return groups;
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    groups.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return groups;
    start = comma + 1;
  }
}

std::string spectral_channel_name(const SpectralBinning& binning, int bin) {
  char digits[64];
  const auto end = std::to_chars(digits, digits + sizeof(digits), binning.bin_centre_nm(bin)).ptr;
  std::string centre(digits, end);
  std::replace(centre.begin(), centre.end(), '.', ',');  // a '.' would start a new EXR layer
  return "S0." + centre + "nm";
}

HalfRangeCounts half_range_counts(const Film& film) {
  constexpr double kSmallestNormalHalf = 0x1p-14;
  const PixelBounds& b = film.pixel_bounds();
  HalfRangeCounts counts;
  for (int y = b.y0; y < b.y1; ++y)
    for (int x = b.x0; x < b.x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const double v = std::abs(double(film.output_value(x, y)[c]));
        if (!(v > 0.0) || !std::isfinite(v)) continue;
        ++counts.nonzero;
        if (v < kSmallestNormalHalf) ++counts.below_normal;
        if (v > double(kHalfMax)) ++counts.above_max;
      }
  return counts;
}

std::string half_range_warning(const HalfRangeCounts& counts, const std::string& file) {
  std::string problems;
  if (counts.above_max > 0)
    problems = std::to_string(counts.above_max) + " values above 65504 (half's largest) were clamped";
  // A tenth: deep shadows of an ordinary image may be subnormal and lose little that shows; when that much of the
  // image is, its colours (X, Y, Z → RGB amplifies the rounding several-fold) are no longer to be trusted.
  if (counts.nonzero > 0 && 10 * counts.below_normal >= counts.nonzero) {
    if (!problems.empty()) problems += " and ";
    char percent[32];
    std::snprintf(percent, sizeof(percent), "%.0f %%", 100.0 * double(counts.below_normal) / double(counts.nonzero));
    problems += std::string(percent) + " of the non-zero values lie below half's normal range (6.1e-5), where it " +
                "keeps less than 0.05 % precision";
  }
  if (problems.empty()) return {};
  return "rimu: warning: " + file + " is written as half floats: " + problems +
         "; write 32-bit floats (the default: render without --half) or set an exposure (docs/light-units.md)";
}

size_t write_exr(const std::filesystem::path& path, const Film& film, const ExrOptions& options) {
  const PixelBounds& b = film.pixel_bounds();
  const bool use_half = options.pixel_type == ExrPixelType::half;
  const SpectralResponse& response = film.response();

  // Each channel and where its values come from: the beauty's 3 channels and N bins, then per light group its 3
  // channels ("sun.X", ...) and N bins ("sun.S0.362,35nm", ...).
  std::vector<ChannelBuffer> channels;
  std::vector<std::function<double(int, int)>> sources;
  for (int c = 0; c < 3; ++c) {
    const bool rename = options.xyz_channels_as_rgb && response.kind() == ResponseKind::cie_xyz;
    channels.push_back({rename ? std::string(1, "RGB"[c]) : response.channel_names()[c], {}, {}});
    sources.push_back([&film, c](int x, int y) { return film.output_value(x, y)[size_t(c)]; });
  }
  const int bins = film.binning().count;
  for (int bin = 0; bin < bins; ++bin) {
    channels.push_back({spectral_channel_name(film.binning(), bin), {}, {}});
    sources.push_back([&film, bin](int x, int y) { return film.spectral_value(x, y, bin); });
  }
  for (int g = 0; g < int(film.light_groups().size()); ++g) {
    const std::string& group = film.light_groups()[size_t(g)];
    for (int c = 0; c < 3; ++c) {
      channels.push_back({group + "." + channels[size_t(c)].name, {}, {}});
      sources.push_back([&film, g, c](int x, int y) { return film.group_output_value(x, y, g)[size_t(c)]; });
    }
    for (int bin = 0; bin < bins; ++bin) {
      channels.push_back({group + "." + spectral_channel_name(film.binning(), bin), {}, {}});
      sources.push_back([&film, g, bin](int x, int y) { return film.group_spectral_value(x, y, g, bin); });
    }
  }

  const size_t pixel_count = size_t(b.area());
  const float largest = use_half ? kHalfMax : std::numeric_limits<float>::max();
  size_t replaced = 0;
  for (size_t c = 0; c < channels.size(); ++c) {
    std::vector<float> values;
    values.reserve(pixel_count);
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x) values.push_back(writable(sources[c](x, y), largest, replaced));
    if (use_half) {
      channels[c].halves.reserve(pixel_count);
      for (float v : values) channels[c].halves.emplace_back(v);
    } else {
      channels[c].floats = std::move(values);
    }
  }

  Imf::Header header = make_header(film, options);
  if (replaced > 0) header.insert("rimu:nonFiniteValuesReplaced", Imf::DoubleAttribute(double(replaced)));
  const Imf::PixelType type = use_half ? Imf::HALF : Imf::FLOAT;
  for (const auto& channel : channels) header.channels().insert(channel.name, Imf::Channel(type));
  std::vector<std::vector<float>> extra_values;
  for (const auto& [name, values] : options.extra_channels) {
    assert(values.size() == pixel_count);
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    extra_values.emplace_back();
    for (float v : values) extra_values.back().push_back(writable(v, std::numeric_limits<float>::max(), replaced));
  }

  // A partial's accumulators: each double's bits as two 32-bit words (EXR has no 64-bit type; UINT is exact).
  // The slices point into the film's own doubles (high word at byte 4 on a little-endian machine), so the sums,
  // 3.4 GB for a 4K 47-bin film, are not copied.
  static_assert(std::endian::native == std::endian::little, "the sum slices assume a little-endian double");
  const int sum_count = options.partial ? film.accumulators_per_pixel() : 0;
  for (int k = 0; k < sum_count; ++k) {
    header.channels().insert(partial_sum_channel_name(k, true), Imf::Channel(Imf::UINT));
    header.channels().insert(partial_sum_channel_name(k, false), Imf::Channel(Imf::UINT));
  }

  write_atomically(path, [&](const std::filesystem::path& temporary) {
    Imf::FrameBuffer frame_buffer;
    if (sum_count > 0) {
      const char* first = reinterpret_cast<const char*>(film.accumulators(b.x0, b.y0));
      const size_t pixel_stride = sizeof(double) * size_t(sum_count);
      for (int k = 0; k < sum_count; ++k)
        for (const bool high : {true, false})
          frame_buffer.insert(partial_sum_channel_name(k, high),
                              Imf::Slice::Make(Imf::UINT, first + sizeof(double) * size_t(k) + (high ? 4 : 0),
                                               header.dataWindow(), pixel_stride, pixel_stride * size_t(b.width())));
    }
    const size_t element = use_half ? sizeof(half) : sizeof(float);
    for (auto& channel : channels) {
      char* base = use_half ? reinterpret_cast<char*>(channel.halves.data())
                            : reinterpret_cast<char*>(channel.floats.data());
      frame_buffer.insert(channel.name, Imf::Slice::Make(type, base, header.dataWindow(), element,
                                                         element * size_t(b.width())));
    }
    for (size_t e = 0; e < extra_values.size(); ++e)
      frame_buffer.insert(options.extra_channels[e].first,
                          Imf::Slice::Make(Imf::FLOAT, reinterpret_cast<char*>(extra_values[e].data()),
                                           header.dataWindow(), sizeof(float), sizeof(float) * size_t(b.width())));
    Imf::OutputFile file(temporary.c_str(), header);
    file.setFrameBuffer(frame_buffer);
    file.writePixels(b.height());
  });
  return replaced;
}

}  // namespace rimu
