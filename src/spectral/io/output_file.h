// Writing an output file so that it either appears complete at its destination or not at all, and checking a
// destination before a render spends time on an image that could not be written there. The one output-file code of
// every tool: the renderer's images, the tools' text files, tables and plots (run_gnuplot) all end here.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rimu {

/// An output file could not be written (disk full, permissions, a library failure). The message names the path.
/// Not an InputError, so tools exit with status 2 (as for RenderError, spectral/error.h).
/// A bad destination the user can fix before rendering (a missing folder) is an InputError instead.
class OutputError : public std::runtime_error {
 public:
  OutputError(std::filesystem::path path, const std::string& what);
  const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

/// Throws InputError (naming `path`, never a temporary) if `path` names no file, is a folder, or its folder does
/// not exist or does not let this process create a file in it (checked by creating and removing the temporary
/// file write_atomically() would use). Also removes stale temporaries of `path` (remove_stale_temporaries()).
/// Cheap: callers run it before rendering so that a typo in -o does not cost a render.
void check_output_path(const std::filesystem::path& path);

/// The folder `path` is in: its parent, or "." for a bare file name.
std::filesystem::path folder_of(const std::filesystem::path& path);

/// The temporary name write_atomically() uses for `path`: in the same folder (so the final rename stays on one file
/// system and is atomic), hidden, named after the whole destination so a user recognises it, unique per process
/// and call, and ending in the destination's extension (OpenImageIO picks a format by extension):
/// ".<file name>.rimu-incomplete-<pid>-<n><extension>", e.g. ".out.exr.rimu-incomplete-4242-0.exr".
std::filesystem::path temporary_output_path(const std::filesystem::path& path);

/// Removes the temporaries of `path` left by writers that were killed (SIGKILL, power loss) before they could
/// clean up: files in its folder named as temporary_output_path() names them (or as earlier Rimu versions did,
/// ".<stem>.rimu-tmp-<pid>-<n><extension>") whose process <pid> no longer exists. Temporaries of other outputs and
/// of live processes are left alone. Returns how many were removed; failures to remove are ignored (best effort).
int remove_stale_temporaries(const std::filesystem::path& path);

/// True if `a` and `b` name the same file (compared as weakly canonical absolute paths, so "out.exr",
/// "./out.exr" and "sub/../out.exr" are the same, as are two names of one existing file through a symbolic link).
bool same_output_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// A file a tool reads, named for check_output_not_input()'s message: the path and how the user gave it (the
/// option or argument, e.g. "scene", "--csv"; empty for a file the input itself names).
struct InputFile {
  std::filesystem::path path;
  std::string option;
};

/// Throws InputError (naming `output`, `option` and the input) if `output` is one of `inputs`: the same existing
/// regular file (the same st_dev and st_ino after following symbolic links, so another name, a symbolic link or a
/// hard link of an input is caught; devices and FIFOs destroy nothing and pass; an output that does not exist yet
/// is no input). Writing it would destroy the input, e.g. `rimu-convert a.pbrt -o a.pbrt` or `rimu merge q0.exr
/// q1.exr --final -o q0.exr`. Every tool calls it for every output option before it reads anything slow.
void check_output_not_input(const std::filesystem::path& output, const std::string& option,
                            const std::vector<InputFile>& inputs);

/// The extension of `path` in lower case, without the dot ("exr", "png"; empty if none).
std::string lower_case_extension(const std::filesystem::path& path);

/// Runs `write(temporary)` and renames the temporary file to `path` (replacing an existing file atomically).
/// Every library's error style ends here: any exception thrown by `write` (OpenEXR's Iex exceptions, OpenColorIO's,
/// a runtime_error built from OpenImageIO's geterror()) becomes an OutputError naming `path` (a library message
/// that names the temporary has it replaced by `path`), and the temporary file is removed, so a failed write
/// leaves neither the destination nor a temporary behind. InputError from check_output_path() passes through.
/// A destination that exists and is not a regular file (a device such as /dev/stdout or /dev/full, a FIFO, a
/// symbolic link) is kept: the temporary file goes to the system's temporary folder and its bytes are copied into
/// the destination with every write checked.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write);

/// Writes `text` to `path` through write_atomically(): the file appears complete or not at all. A path that names
/// no writable file in an existing folder is an InputError (exit 1); a failed write (a full disk, /dev/full) an
/// OutputError naming the path and the system's reason (exit 2). The tools' text outputs and tables.
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace rimu
