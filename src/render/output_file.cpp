#include "render/output_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "spectral/error.h"

namespace rimu {
namespace {

std::filesystem::path folder_of(const std::filesystem::path& path) {
  const std::filesystem::path parent = path.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

// Copies the bytes of `from` into the existing `to` (a device, a FIFO, a link's target), checking every write.
void copy_into(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(from.c_str(), "rb"), &std::fclose);
  if (!in) throw std::runtime_error("cannot reopen the temporary file " + from.string() + ": " + std::strerror(errno));
  std::FILE* out = std::fopen(to.c_str(), "wb");
  if (!out) throw std::runtime_error(std::strerror(errno));
  char buffer[1 << 16];
  size_t n = 0;
  int error = 0;
  errno = 0;
  while (error == 0 && (n = std::fread(buffer, 1, sizeof buffer, in.get())) > 0)
    if (std::fwrite(buffer, 1, n, out) != n) error = errno != 0 ? errno : EIO;
  if (error == 0 && std::ferror(in.get())) error = EIO;
  if (std::fflush(out) != 0 && error == 0) error = errno != 0 ? errno : EIO;
  if (std::fclose(out) != 0 && error == 0) error = errno != 0 ? errno : EIO;
  if (error != 0) throw std::runtime_error(std::strerror(error));
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
  // A destination that is not a plain file (/dev/stdout, /dev/full, a FIFO, a symbolic link) cannot take the rename,
  // which would replace the device or the link itself. It is written through a temporary file in the system's
  // temporary folder and then copied into, every write checked: the libraries that write images do not all report a
  // failed write, so the copy is where a full device shows.
  std::error_code status_error;
  const auto status = std::filesystem::symlink_status(path, status_error);
  if (!status_error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    const std::filesystem::path temporary =
        std::filesystem::temp_directory_path() / temporary_output_path(path).filename();
    std::error_code ignored;
    try {
      write(temporary);
      copy_into(temporary, path);
    } catch (const InputError&) {
      std::filesystem::remove(temporary, ignored);
      throw;
    } catch (const std::exception& e) {
      std::filesystem::remove(temporary, ignored);
      throw OutputError(path, e.what());
    }
    std::filesystem::remove(temporary, ignored);
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
