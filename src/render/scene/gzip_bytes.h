// gzip-compressed inputs (RFC 1952), such as the .ply.gz meshes pbrt-v4 scenes ship, decompressed in memory.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace rimu {

/// True if `path` ends in ".gz" (case-insensitive).
bool has_gzip_extension(const std::filesystem::path& path);

/// Decompresses the gzip stream `compressed` (one member or several concatenated, as gzip(1) allows) into at most
/// `max_bytes`. Throws InputError naming `file` when the bytes are not gzip, are corrupt (bad deflate data or a
/// CRC mismatch), end before the stream does (a truncated download), or expand past the limit.
/// Cost: one pass, memory = the decompressed size.
std::string gunzip(std::string_view compressed, const std::string& file, std::uintmax_t max_bytes);

}  // namespace rimu
