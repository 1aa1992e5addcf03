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
/// `limit` says what max_bytes is, for the message ("the limit for meshes").
std::string gunzip(std::string_view compressed, const std::string& file, std::uintmax_t max_bytes,
                   const std::string& limit = "the limit for meshes");

/// The first `max_bytes` of what `compressed` decompresses to (all of it if shorter), for reading a header before
/// deciding how much of the rest may be decompressed. Errors as gunzip, except that more data is not one.
std::string gunzip_prefix(std::string_view compressed, const std::string& file, std::uintmax_t max_bytes);

}  // namespace rimu
