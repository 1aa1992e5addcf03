#include "render/scene/gzip_bytes.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <limits>

#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {

bool has_gzip_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".gz";
}

namespace {

// gunzip, or gunzip_prefix when `prefix_only` (then reaching max_bytes ends the output instead of failing).
std::string inflate_gzip(std::string_view compressed, const std::string& file, std::uintmax_t max_bytes,
                         const std::string& limit, bool prefix_only) {
  const auto fail = [&file](const std::string& what) -> void { throw InputError({file, 0, ""}, what); };
  // A gzip member starts with the magic bytes 1f 8b (RFC 1952 §2.3.1); checked here so that a plain file with a
  // .gz name gets a message saying so rather than zlib's "incorrect header check".
  if (compressed.size() < 2 || static_cast<unsigned char>(compressed[0]) != 0x1f ||
      static_cast<unsigned char>(compressed[1]) != 0x8b)
    fail("is not gzip-compressed (it does not start with the gzip signature 1f 8b)");
  z_stream stream{};
  // windowBits 15 + 16: a gzip wrapper (not zlib's, not raw deflate), the full 32 KiB window.
  if (inflateInit2(&stream, 15 + 16) != Z_OK) throw std::runtime_error("zlib: inflateInit2 failed");
  std::string out;
  // Typical mesh data compresses 2-4 times: start at 3x and grow geometrically.
  out.resize(std::min<std::uintmax_t>(max_bytes, std::max<std::uintmax_t>(3 * compressed.size(), 1 << 16)));
  size_t consumed = 0, produced = 0;
  int status = Z_OK;
  try {
    while (true) {
      // zlib counts in 32-bit uInt: feed and drain in chunks of at most 1 GiB.
      constexpr size_t kChunk = size_t(1) << 30;
      if (produced == out.size()) {
        if (out.size() >= max_bytes) {
          if (prefix_only) break;
          fail("decompresses to more than " + format_bytes(max_bytes) + ", " + limit);
        }
        out.resize(size_t(std::min<std::uintmax_t>(max_bytes, 2 * std::uintmax_t(out.size()))));
      }
      stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data() + consumed));
      stream.avail_in = uInt(std::min(kChunk, compressed.size() - consumed));
      stream.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
      stream.avail_out = uInt(std::min(kChunk, out.size() - produced));
      const uInt in_before = stream.avail_in, out_before = stream.avail_out;
      status = inflate(&stream, Z_NO_FLUSH);
      consumed += in_before - stream.avail_in;
      produced += out_before - stream.avail_out;
      if (status == Z_STREAM_END) {
        if (consumed == compressed.size()) break;
        // Another member follows (gzip allows concatenation); anything else after the end is an error.
        if (static_cast<unsigned char>(compressed[consumed]) != 0x1f)
          fail("has " + std::to_string(compressed.size() - consumed) + " bytes of data after the end of the gzip stream");
        inflateReset(&stream);
        continue;
      }
      if (status == Z_DATA_ERROR)
        fail(std::string("is corrupt: ") + (stream.msg ? stream.msg : "invalid compressed data") + " (after " +
             std::to_string(consumed) + " compressed bytes)");
      if (status == Z_MEM_ERROR) throw std::bad_alloc();
      if (status == Z_BUF_ERROR && consumed == compressed.size() && produced < out.size())
        fail("ends before its gzip stream does (truncated after " + std::to_string(compressed.size()) + " bytes?)");
      if (status != Z_OK && status != Z_BUF_ERROR)
        fail("cannot be decompressed (zlib status " + std::to_string(status) + ")");
    }
  } catch (...) {
    inflateEnd(&stream);
    throw;
  }
  inflateEnd(&stream);
  out.resize(produced);  // not shrunk: that would copy, and the caller parses and drops the buffer
  return out;
}

}  // namespace

std::string gunzip(std::string_view compressed, const std::string& file, std::uintmax_t max_bytes,
                   const std::string& limit) {
  return inflate_gzip(compressed, file, max_bytes, limit, false);
}

std::string gunzip_prefix(std::string_view compressed, const std::string& file, std::uintmax_t max_bytes) {
  return inflate_gzip(compressed, file, max_bytes, "", true);
}

}  // namespace rimu
