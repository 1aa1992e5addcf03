#pragma once
// A bounds check of an OpenEXR file's header before a library reads it.
//
// OpenEXR 3.1 allocates each header attribute at the size the file claims for it, before anything checks that
// the file holds that many bytes: a 1.2 KB file whose `lineOrder` claims 128 MB, or a 2.7 KB partial whose string
// attribute claims 1.8 GB, made the reader allocate that much (found by fuzz_image and fuzz_merge). And OpenEXR
// reads most attribute values by their type, not by their declared size (a `chlist` runs to its empty channel
// name, a `box2i` is always 16 bytes): when the two disagree, the reader's position drifts from the declared
// layout and the next "size" it reads is whatever bytes it landed on (a 2.5 KB partial whose channel list ran past
// its declared 303 bytes made the next string attribute claim gigabytes). The check walks the attribute list
// (name, type, 4-byte size), reads each value's extent the way the library's reader does for its type, and
// refuses a value whose extent differs from its declared size or runs past the file, so both Rimu's own EXR
// reading (partials, `rimu compare`) and OpenImageIO's (image textures) only see headers whose declared layout is
// the layout the library reads.
#include <cstdint>
#include <filesystem>

namespace rimu {

/// For a file that starts with OpenEXR's magic number (76 2f 31 01): throws InputError naming `path` and the
/// attribute if an attribute of the header (of every part's header, for a multi-part file) claims more bytes than
/// follow it in the file of `file_bytes` bytes, if its value as OpenEXR reads its type would span a different
/// number of bytes than it declares (a fixed-size type of another size, a channel list, string vector or preview
/// image that does not fill its declared size exactly), if a name or type name runs past 255 characters, or if
/// the header ends before its terminating empty name. Any other file is left to its reader. Reads only the
/// header, opening the file once.
void check_exr_header_sizes(const std::filesystem::path& path, std::uintmax_t file_bytes);

}  // namespace rimu
