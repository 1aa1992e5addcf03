#include "render/output/exr_compare.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <bit>
#include <cmath>
#include <memory>
#include <vector>

#include "render/image/exr_input.h"
#include "spectral/error.h"

namespace rimu {
namespace {

// Distance of two floats in representable values (same sign: difference of their bit patterns as integers).
uint64_t ulp_distance(float a, float b) {
  if (a == b) return 0;
  if (std::isnan(a) || std::isnan(b)) return UINT64_MAX;
  auto ordered = [](float f) {
    const int32_t i = std::bit_cast<int32_t>(f);
    return i < 0 ? int64_t(INT32_MIN) - int64_t(i) : int64_t(i);  // monotonic across zero
  };
  const int64_t d = ordered(a) - ordered(b);
  return uint64_t(d < 0 ? -d : d);
}

struct Channels {
  std::unique_ptr<Imf::InputFile> file;
  Imath::Box2i window;
};

Channels open(const std::filesystem::path& path) {
  Channels c{open_exr_input(path), {}};
  c.window = c.file->header().dataWindow();
  return c;
}

}  // namespace

ExrDifference compare_exr(const std::filesystem::path& a, const std::filesystem::path& b, bool image_only) {
  Channels ca = open(a), cb = open(b);
  if (ca.window != cb.window) throw InputError({b.string(), 0, ""}, "its data window differs from " + a.string() + "'s");
  const Imath::Box2i& w = ca.window;
  const int width = w.max.x - w.min.x + 1, height = w.max.y - w.min.y + 1;
  const size_t n = size_t(width) * size_t(height);
  ExrDifference d;
  for (auto it = ca.file->header().channels().begin(); it != ca.file->header().channels().end(); ++it) {
    const std::string name = it.name();
    const bool words = it.channel().type == Imf::UINT;
    if (words && image_only) continue;
    const Imf::Channel* other = cb.file->header().channels().findChannel(name);
    if (!other) throw InputError({b.string(), 0, ""}, "has no channel '" + name + "' (" + a.string() + " has)");
    std::vector<uint32_t> va(n), vb(n);  // floats or UINT words, 4 bytes either way
    const Imf::PixelType type = words ? Imf::UINT : Imf::FLOAT;
    for (auto* c : {&ca, &cb}) {
      Imf::FrameBuffer fb;
      fb.insert(name, Imf::Slice::Make(type, (c == &ca ? va : vb).data(), w, 4, 4 * size_t(width)));
      c->file->setFrameBuffer(fb);
      c->file->readPixels(w.min.y, w.max.y);
    }
    for (size_t i = 0; i < n; ++i) {
      ++d.values;
      if (va[i] == vb[i]) continue;
      ++d.different;
      const uint64_t ulps =
          words ? 1 : ulp_distance(std::bit_cast<float>(va[i]), std::bit_cast<float>(vb[i]));
      if (ulps > d.max_ulps) {
        d.max_ulps = ulps;
        d.worst = "channel " + name + " at (" + std::to_string(w.min.x + int(i % size_t(width))) + ", " +
                  std::to_string(w.min.y + int(i / size_t(width))) + ")";
      }
    }
  }
  return d;
}

}  // namespace rimu
