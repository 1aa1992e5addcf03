#include "render/output_file.h"

#include <unistd.h>

#include <atomic>

#include "spectral/error.h"

namespace rimu {
namespace {

std::filesystem::path folder_of(const std::filesystem::path& path) {
  const std::filesystem::path parent = path.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

}  // namespace

OutputError::OutputError(std::filesystem::path path, const std::string& what)
    : RenderError("cannot write '" + path.string() + "': " + what), path_(std::move(path)) {}

void check_output_path(const std::filesystem::path& path) {
  if (path.empty() || !path.has_filename()) throw InputError({path.string(), 0, ""}, "the output path names no file");
  std::error_code error;
  const std::filesystem::path folder = folder_of(path);
  if (!std::filesystem::is_directory(folder, error))
    throw InputError({path.string(), 0, ""}, "the output folder '" + folder.string() + "' does not exist");
  if (std::filesystem::is_directory(path, error))
    throw InputError({path.string(), 0, ""}, "the output path is a folder, not a file");
}

std::filesystem::path temporary_output_path(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  const std::string name = "." + path.stem().string() + ".rimu-tmp-" + std::to_string(::getpid()) + "-" +
                           std::to_string(counter.fetch_add(1)) + path.extension().string();
  return folder_of(path) / name;
}

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& temporary)>& write) {
  check_output_path(path);
  // A destination that is not a plain file (/dev/stdout, /dev/full, a FIFO, a symbolic link) is written in place:
  // renaming a temporary file over it would replace the device or the link itself.
  std::error_code status_error;
  const auto status = std::filesystem::symlink_status(path, status_error);
  if (!status_error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    try {
      write(path);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw OutputError(path, e.what());
    }
    return;
  }
  const std::filesystem::path temporary = temporary_output_path(path);
  std::error_code ignored;
  try {
    write(temporary);
  } catch (const InputError&) {
    std::filesystem::remove(temporary, ignored);
    throw;
  } catch (const std::exception& e) {
    std::filesystem::remove(temporary, ignored);
    throw OutputError(path, e.what());
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, ignored);
    throw OutputError(path, "renaming the finished temporary file failed: " + error.message());
  }
}

}  // namespace rimu
