#include "render/image/exr_input.h"

#include <ImfHeader.h>

#include <mutex>
#include <system_error>

#include "render/film/render_size.h"
#include "render/image/exr_header_check.h"
#include "spectral/error.h"

namespace rimu {

std::unique_ptr<Imf::InputFile> open_exr_input(const std::filesystem::path& path) {
  static std::once_flag limits_set;
  std::call_once(limits_set, [] {
    // A tile is never larger than the image; both limits make a header that claims more fail OpenEXR's sanity
    // check ("The width of the data window exceeds the maximum width…") instead of allocating for it.
    Imf::Header::setMaxImageSize(kMaxImageDimension, kMaxImageDimension);
    Imf::Header::setMaxTileSize(kMaxImageDimension, kMaxImageDimension);
  });
  // OpenEXR allocates each header attribute at the size it claims: refuse sizes the file cannot hold first
  // (a file whose size cannot be read is left to OpenEXR, which then fails to open it).
  std::error_code error;
  if (const std::uintmax_t bytes = std::filesystem::file_size(path, error); !error) check_exr_header_sizes(path, bytes);
  try {
    return std::make_unique<Imf::InputFile>(path.c_str());
  } catch (const std::exception& e) {
    throw InputError({path.string(), 0, ""}, std::string("cannot read as OpenEXR: ") + e.what());
  }
}

}  // namespace rimu
