#include "render/exr_output.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfChromaticities.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <algorithm>
#include <charconv>
#include <vector>

#include "render/output_file.h"
#include "render/version.h"

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
    h.insert("rimu:luminanceNitsPerUnitY",
             Imf::DoubleAttribute(response.luminance_nits_per_unit_y() / film.output_transform().scale));
  } else {
    add_string(h, "rimu:camera", response.camera_name());
  }
  add_string(h, "rimu:version", rimu_version());
  add_string(h, "rimu:filmResponse", response.description());

  const RenderMetadata& m = options.metadata;
  h.insert("rimu:spp", Imf::IntAttribute(m.samples_per_pixel));
  add_string(h, "rimu:seed", std::to_string(m.seed));
  h.insert("rimu:renderTimeSeconds", Imf::DoubleAttribute(m.render_time_s));
  const FilmSampleCounts counts = film.sample_counts();
  h.insert("rimu:samplesAccepted", Imf::DoubleAttribute(double(counts.accepted)));
  h.insert("rimu:discardedNaN", Imf::DoubleAttribute(double(counts.nan)));
  h.insert("rimu:discardedInf", Imf::DoubleAttribute(double(counts.infinite)));
  h.insert("rimu:discardedNegative", Imf::DoubleAttribute(double(counts.negative)));
  if (!m.scene.empty()) add_string(h, "rimu:scene", m.scene);
  if (m.interrupted) add_string(h, "rimu:interrupted", "interrupted at " + std::to_string(m.samples_per_pixel) + " spp");
  for (const auto& [key, value] : m.extra) add_string(h, "rimu:" + key, value);
  if (film.binning().count > 0) {
    add_string(h, "spectralLayoutVersion", "1.0");
    add_string(h, "rimu:spectralUnits", "W.m^-2.sr^-1.nm^-1 (mean over each bin)");
  }
  return h;
}

}  // namespace

std::string spectral_channel_name(const SpectralBinning& binning, int bin) {
  char digits[64];
  const auto end = std::to_chars(digits, digits + sizeof(digits), binning.bin_centre_nm(bin)).ptr;
  std::string centre(digits, end);
  std::replace(centre.begin(), centre.end(), '.', ',');  // a '.' would start a new EXR layer
  return "S0." + centre + "nm";
}

void write_exr(const std::filesystem::path& path, const Film& film, const ExrOptions& options) {
  const PixelBounds& b = film.pixel_bounds();
  const bool use_half = options.pixel_type == ExrPixelType::half;
  const SpectralResponse& response = film.response();

  std::vector<ChannelBuffer> channels;
  for (int c = 0; c < 3; ++c) {
    const bool rename = options.xyz_channels_as_rgb && response.kind() == ResponseKind::cie_xyz;
    channels.push_back({rename ? std::string(1, "RGB"[c]) : response.channel_names()[c], {}, {}});
  }
  for (int bin = 0; bin < film.binning().count; ++bin)
    channels.push_back({spectral_channel_name(film.binning(), bin), {}, {}});

  const size_t pixel_count = size_t(b.area());
  for (size_t c = 0; c < channels.size(); ++c) {
    std::vector<float> values;
    values.reserve(pixel_count);
    for (int y = b.y0; y < b.y1; ++y)
      for (int x = b.x0; x < b.x1; ++x)
        values.push_back(float(c < 3 ? film.output_value(x, y)[c] : film.spectral_value(x, y, int(c) - 3)));
    if (use_half) {
      channels[c].halves.reserve(pixel_count);
      for (float v : values) channels[c].halves.emplace_back(std::clamp(v, -kHalfMax, kHalfMax));
    } else {
      channels[c].floats = std::move(values);
    }
  }

  Imf::Header header = make_header(film, options);
  const Imf::PixelType type = use_half ? Imf::HALF : Imf::FLOAT;
  for (const auto& channel : channels) header.channels().insert(channel.name, Imf::Channel(type));

  write_atomically(path, [&](const std::filesystem::path& temporary) {
    Imf::FrameBuffer frame_buffer;
    const size_t element = use_half ? sizeof(half) : sizeof(float);
    for (auto& channel : channels) {
      char* base = use_half ? reinterpret_cast<char*>(channel.halves.data())
                            : reinterpret_cast<char*>(channel.floats.data());
      frame_buffer.insert(channel.name, Imf::Slice::Make(type, base, header.dataWindow(), element,
                                                         element * size_t(b.width())));
    }
    Imf::OutputFile file(temporary.c_str(), header);
    file.setFrameBuffer(frame_buffer);
    file.writePixels(b.height());
  });
}

}  // namespace rimu
