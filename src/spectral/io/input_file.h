// Reading a user's input file: the one way every reader of Rimu opens a file (scene and light JSON, spectrum CSVs,
// camera curves, IES files, OBJ and PLY meshes, voxel grids).
//
// A scene can name any path, so a reader must not hang on something that never ends (/dev/zero, /dev/urandom, a
// FIFO nobody writes to) nor allocate without bound: only regular files are read, and each kind of input has a
// size limit (docs/scene-format.md, "Limits"). The readers parse from memory, so a test or a fuzzer can hand them
// bytes directly.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rimu {

/// Size limits, bytes. Each bounds the memory a parse can take (a parsed table or JSON document takes several
/// times its file's size) far above any real input of the kind:
/// - scene and light JSON: 256 MiB (a scene can hold triangles inline);
/// - tables (spectrum and camera-curve CSVs, IES files): 16 MiB (a 1 nm spectrum is 10 KiB, an IES file 100 KiB);
/// - meshes (OBJ, PLY), voxel grids and images: 16 GiB.
inline constexpr std::uintmax_t kMaxJsonFileBytes = std::uintmax_t(256) << 20;
inline constexpr std::uintmax_t kMaxTableFileBytes = std::uintmax_t(16) << 20;
inline constexpr std::uintmax_t kMaxBinaryFileBytes = std::uintmax_t(16) << 30;

/// Checks that `path` is a regular file (following symbolic links) of at most `max_bytes`, and returns its size.
/// Throws InputError naming the file: it does not exist or cannot be inspected, it is a directory, it is not a
/// regular file (a FIFO, a device, a socket), or it is larger than the limit.
std::uintmax_t check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

/// The whole file as bytes, after check_input_file. A file that grows past `max_bytes` while it is read (or a file
/// whose size the system reports as 0, as /proc does) is still read no further than the limit.
std::string read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

/// Throws InputError "name:line: column C: ..." at the first NUL byte of `text`, if any. Text readers call it on
/// what they parse: text never holds a NUL, and a parser that stops at one would silently ignore the rest.
void reject_nul_bytes(std::string_view text, const std::string& name);

/// The files read on this thread while it is alive: every file read_input_file reads (with a digest of exactly the
/// bytes it returned) and every file check_input_file admits for a library to read (OpenImageIO's images; no
/// digest: the caller hashes the file itself). The scene hash (render_job.h) is built from it, so it covers what
/// the readers read and nothing a second parser guesses. Logs nest (each active one records); reads on other
/// threads are not recorded (the scene readers read on the calling thread).
class InputFileLog {
 public:
  InputFileLog();
  ~InputFileLog();
  InputFileLog(const InputFileLog&) = delete;
  InputFileLog& operator=(const InputFileLog&) = delete;

  /// Absolute, lexically normal path → 64-bit FNV-1a of the bytes read (none: only admitted, not read here).
  const std::map<std::filesystem::path, std::optional<std::uint64_t>>& files() const { return files_; }
  void record(const std::filesystem::path& path, const std::optional<std::uint64_t>& digest);

 private:
  std::map<std::filesystem::path, std::optional<std::uint64_t>> files_;
};

/// 64-bit FNV-1a (Fowler, Noll, Vo), continuing from `h`: tells changed bytes from unchanged ones; not a security
/// check.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 0xcbf29ce484222325ULL);

/// "12.3 MiB" style sizes for messages.
std::string format_bytes(std::uintmax_t bytes);

}  // namespace rimu
