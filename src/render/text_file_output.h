// Text outputs of the tools (a light definition, a report): written whole or not at all, every write checked.
#pragma once

#include <filesystem>
#include <string>

namespace rimu {

/// Writes `text` to `path` through write_atomically() (output_file.h): the file appears complete or not at all.
/// A path that names no writable file in an existing folder is an InputError (exit 1); a failed write (a full
/// disk, /dev/full) an OutputError naming the path and the system's reason (exit 2).
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace rimu
