#include "render/image/exr_image_decoder.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfPartType.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "render/image/exr_input.h"
#include "spectral/error.h"

namespace rimu {
namespace {

bool starts_with_exr_magic(const std::filesystem::path& path) {
  unsigned char magic[4] = {0, 0, 0, 0};
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  const size_t n = std::fread(magic, 1, 4, f);
  std::fclose(f);
  return n == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

// The channel names in OpenImageIO's order if the set is one this decoder takes (exr_image_decoder.h), else empty.
std::vector<std::string> channels_taken(const Imf::Header& header) {
  std::vector<std::string> names;
  bool sampled_everywhere = true, half_or_float = true;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
    names.emplace_back(c.name());
    sampled_everywhere = sampled_everywhere && c.channel().xSampling == 1 && c.channel().ySampling == 1;
    half_or_float = half_or_float && (c.channel().type == Imf::HALF || c.channel().type == Imf::FLOAT);
  }
  if (!sampled_everywhere || !half_or_float) return {};
  // OpenEXR lists channels alphabetically; OpenImageIO puts R, G, B, A first, in that order.
  for (const std::vector<std::string>& set : {std::vector<std::string>{"R", "G", "B"},
                                              std::vector<std::string>{"R", "G", "B", "A"},
                                              std::vector<std::string>{"Y"}, std::vector<std::string>{"Y", "A"}}) {
    bool match = names.size() == set.size();
    for (const std::string& name : set) match = match && header.channels().findChannel(name) != nullptr;
    if (match) return set;
  }
  return {};
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError({path.string(), 0, ""}, "cannot read the OpenEXR image: " + what);
}

}  // namespace

std::optional<DecodedImage> exr_image_header(const std::filesystem::path& path) {
  if (!starts_with_exr_magic(path)) return std::nullopt;
  const std::unique_ptr<Imf::InputFile> file = open_exr_input(path);
  const Imf::Header& header = file->header();
  if (header.hasType() && Imf::isDeepData(header.type())) return std::nullopt;
  const std::vector<std::string> names = channels_taken(header);
  if (names.empty()) return std::nullopt;
  const Imath::Box2i window = header.dataWindow();
  DecodedImage image;
  image.width = window.max.x - window.min.x + 1;
  image.height = window.max.y - window.min.y + 1;
  image.channels = int(names.size());
  image.alpha_channel = names.back() == "A" ? image.channels - 1 : -1;
  bool all_half = true;
  for (const std::string& name : names) all_half = all_half && header.channels().findChannel(name)->type == Imf::HALF;
  image.bits_per_sample = all_half ? 16 : 32;
  image.stored_as_float = true;
  image.format_name = "openexr";
  return image;
}

DecodedImage exr_image_pixels(const std::filesystem::path& path, const DecodedImage& header, bool halves_if_half) {
  DecodedImage image = header;
  try {
    const std::unique_ptr<Imf::InputFile> file = open_exr_input(path);
    // OpenEXR fills the lines a short file lacks with zeros (or stops at the first); either way it is not the image.
    if (!file->isComplete()) fail(path, "the file ends before its pixels do");
    const Imf::Header& h = file->header();
    const std::vector<std::string> names = channels_taken(h);
    const Imath::Box2i window = h.dataWindow();
    if (int(names.size()) != header.channels || window.max.x - window.min.x + 1 != header.width ||
        window.max.y - window.min.y + 1 != header.height)
      throw InputError({path.string(), 0, ""}, "the image changed while it was read");
    const size_t channels = names.size();
    const size_t values = size_t(header.width) * size_t(header.height) * channels;
    const bool halves = halves_if_half && header.bits_per_sample == 16;
    Imf::FrameBuffer frame;
    // Channel c of pixel i at samples[i·channels + c], as `type`.
    const auto interleave = [&](Imf::PixelType type, auto* samples) {
      const size_t bytes = sizeof(*samples);
      for (size_t c = 0; c < channels; ++c)
        frame.insert(names[c], Imf::Slice::Make(type, samples + c, window, bytes * channels,
                                                bytes * channels * size_t(header.width)));
    };
    if (halves) {
      image.halves.assign(values, 0);
      interleave(Imf::HALF, image.halves.data());
    } else {
      image.pixels.assign(values, 0.0f);
      interleave(Imf::FLOAT, image.pixels.data());
    }
    file->setFrameBuffer(frame);
    file->readPixels(window.min.y, window.max.y);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fail(path, e.what());
  }
  return image;
}

}  // namespace rimu
