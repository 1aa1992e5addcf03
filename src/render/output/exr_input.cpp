#include "render/output/exr_input.h"

#include <ImfHeader.h>

#include <mutex>

#include "render/film/render_size.h"

namespace rimu {

std::unique_ptr<Imf::InputFile> open_exr_input(const std::filesystem::path& path) {
  static std::once_flag limits_set;
  std::call_once(limits_set, [] {
    // A tile is never larger than the image; both limits make a header that claims more fail OpenEXR's sanity
    // check ("The width of the data window exceeds the maximum width…") instead of allocating for it.
    Imf::Header::setMaxImageSize(kMaxImageDimension, kMaxImageDimension);
    Imf::Header::setMaxTileSize(kMaxImageDimension, kMaxImageDimension);
  });
  return std::make_unique<Imf::InputFile>(path.c_str());
}

}  // namespace rimu
