#pragma once
// A bounds check of an OpenEXR file's header before a library reads it.
//
// OpenEXR 3.1 allocates each header attribute at the size the file claims for it, before anything checks that
// the file holds that many bytes: a 1.2 KB file whose `lineOrder` claims 128 MB, or a 2.7 KB partial whose string
// attribute claims 1.8 GB, made the reader allocate that much (found by fuzz_image and fuzz_merge). The check walks
// the attribute list (name, type, 4-byte size) without allocating for values and refuses a size the rest of the
// file cannot hold, so both Rimu's own EXR reading (partials, `rimu compare`) and OpenImageIO's (image textures)
// only see headers that fit their file.
#include <cstdint>
#include <filesystem>

namespace rimu {

/// For a file that starts with OpenEXR's magic number (76 2f 31 01): throws InputError naming `path` and the
/// attribute if an attribute of the header (of every part's header, for a multi-part file) claims more bytes than
/// follow it in the file of `file_bytes` bytes, a name or type name runs past 255 characters, or the header ends
/// before its terminating empty name. Any other file is left to its reader. Reads only the header, opening the
/// file once.
void check_exr_header_sizes(const std::filesystem::path& path, std::uintmax_t file_bytes);

}  // namespace rimu
