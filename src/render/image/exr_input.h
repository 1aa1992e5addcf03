#pragma once
// Opening an OpenEXR file Rimu did not necessarily write (partials for `rimu merge`, images for `rimu compare`,
// image textures and environment maps).
//
// OpenEXR's header reader allocates for what the header claims (the line-offset table of a data window of 2³¹ rows
// is gigabytes) before any of Rimu's checks see the header: a 2 KB damaged partial made `Imf::InputFile` allocate
// 1.3-1.9 GB (fuzz/regressions/merge/). OpenEXR bounds that itself when given a largest image and tile size
// (Imf::Header::setMaxImageSize / setMaxTileSize, checked in the header's sanity check before the table is
// allocated), so every EXR Rimu reads is opened here, with the limits of the largest film Rimu renders.
#include <ImfInputFile.h>

#include <filesystem>
#include <memory>

namespace rimu {

/// Opens `path` with OpenEXR after checking that its header's attribute sizes fit the file (exr_header_check.h)
/// and setting OpenEXR's process-wide header limits to Rimu's largest film (kMaxImageDimension on either side).
/// Every failure is an InputError naming the file: "cannot read as OpenEXR: " and OpenEXR's reason (a missing
/// file, not an EXR, a damaged header, a size beyond the limits).
std::unique_ptr<Imf::InputFile> open_exr_input(const std::filesystem::path& path);

}  // namespace rimu
