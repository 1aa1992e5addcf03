// Writing an output file so that it either appears complete at its destination or not at all.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "render/render_error.h"

namespace rimu {

/// An output file could not be written (disk full, permissions, a library failure). The message names the path.
/// A RenderError, so tools exit with status 2.
/// A bad destination the user can fix before rendering (a missing folder) is an InputError instead.
class OutputError : public RenderError {
 public:
  OutputError(std::filesystem::path path, const std::string& what);
  const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

/// Throws InputError (naming the path) if the folder `path` would be written in does not exist or is not a folder.
/// Cheap: callers run it before rendering so that a typo in -o does not cost a render.
void check_output_path(const std::filesystem::path& path);

/// The temporary name write_atomically() uses for `path`: a hidden file in the same folder (so the final rename
/// stays on one file system and is atomic), unique per process and call, ending in the destination's extension
/// (OpenImageIO picks the format by extension).
std::filesystem::path temporary_output_path(const std::filesystem::path& path);

/// Runs `write(temporary)` and renames the temporary file to `path` (replacing an existing file atomically).
/// Every library's error style ends here: any exception thrown by `write` (OpenEXR's Iex exceptions, OpenColorIO's,
/// a runtime_error built from OpenImageIO's geterror()) becomes an OutputError naming `path`, and the temporary
/// file is removed, so a failed write leaves neither the destination nor a temporary behind. InputError from
/// check_output_path() passes through unchanged. A destination that exists and is not a regular file (a device such
/// as /dev/stdout or /dev/full, a FIFO, a symbolic link) is kept: the temporary file goes to the system's temporary
/// folder and its bytes are copied into the destination with every write checked.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write);

}  // namespace rimu
