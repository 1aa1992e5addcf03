#include "spectral/io/output_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "spectral/error.h"

namespace rimu {

std::filesystem::path folder_of(const std::filesystem::path& path) {
  const std::filesystem::path parent = path.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

namespace {

// True if process `pid` exists (kill with signal 0 only checks; EPERM means it exists but is someone else's).
bool process_alive(long pid) {
  if (pid <= 0 || pid != long(pid_t(pid))) return false;
  return ::kill(pid_t(pid), 0) == 0 || errno == EPERM;
}

// If `name` is `prefix` + "<pid>-<n>" + `suffix`, the pid; otherwise -1.
long pid_in_name(const std::string& name, const std::string& prefix, const std::string& suffix) {
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  const std::string middle = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  const size_t dash = middle.find('-');
  if (dash == 0 || dash == std::string::npos || dash + 1 == middle.size() || dash > 9) return -1;
  const auto digits = [](const std::string& s) {
    return std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
  };
  if (!digits(middle.substr(0, dash)) || !digits(middle.substr(dash + 1))) return -1;
  return std::stol(middle.substr(0, dash));
}

// `text` with every occurrence of `from` replaced by `to`.
std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
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
    : std::runtime_error("cannot write '" + path.string() + "': " + what), path_(std::move(path)) {}

std::filesystem::path temporary_output_path(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  const std::string name = "." + path.filename().string() + ".rimu-incomplete-" + std::to_string(::getpid()) + "-" +
                           std::to_string(counter.fetch_add(1)) + path.extension().string();
  return folder_of(path) / name;
}

int remove_stale_temporaries(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  const std::string current_prefix = "." + path.filename().string() + ".rimu-incomplete-";
  const std::string legacy_prefix = "." + path.stem().string() + ".rimu-tmp-";
  std::error_code error;
  std::filesystem::directory_iterator it(folder_of(path), error), end;
  int removed = 0;
  for (; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    long pid = pid_in_name(name, current_prefix, extension);
    if (pid < 0) pid = pid_in_name(name, legacy_prefix, extension);
    if (pid < 0 || process_alive(pid)) continue;
    std::error_code ignored;
    if (it->is_regular_file(ignored) && std::filesystem::remove(it->path(), ignored)) ++removed;
  }
  return removed;
}

void check_output_path(const std::filesystem::path& path) {
  if (path.empty() || !path.has_filename()) throw InputError({path.string(), 0, ""}, "the output path names no file");
  std::error_code error;
  const std::filesystem::path folder = folder_of(path);
  if (!std::filesystem::is_directory(folder, error))
    throw InputError({path.string(), 0, ""}, "the output folder '" + folder.string() + "' does not exist");
  if (std::filesystem::is_directory(path, error))
    throw InputError({path.string(), 0, ""}, "the output path is a folder, not a file");
  // A device, FIFO or link is written by copying into it (write_atomically): it must be writable itself.
  const auto status = std::filesystem::symlink_status(path, error);
  if (!error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    if (::access(path.c_str(), W_OK) != 0) {
      const int saved = errno;
      throw InputError({path.string(), 0, ""}, std::string("cannot write to it: ") + std::strerror(saved));
    }
    return;
  }
  remove_stale_temporaries(path);
  // Create (and remove) the very temporary a writer would create: permissions, read-only or pseudo file systems
  // (/proc) and full inode tables all show up here, before the render rather than after it.
  const std::filesystem::path probe = temporary_output_path(path);
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int saved = errno;
    throw InputError({path.string(), 0, ""},
                     "cannot create a file in the output folder '" + folder.string() + "': " + std::strerror(saved));
  }
  ::close(fd);
  std::filesystem::remove(probe, error);
}

bool same_output_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  if (std::filesystem::exists(a, error) && std::filesystem::exists(b, error) &&
      std::filesystem::equivalent(a, b, error))
    return true;
  const auto normal = [](const std::filesystem::path& p) {
    std::error_code e;
    const std::filesystem::path absolute = std::filesystem::absolute(p, e);
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(absolute, e);
    return (e ? absolute : canonical).lexically_normal();
  };
  return normal(a) == normal(b);
}

namespace {

// The device and inode of the existing regular file `path` names (symbolic links followed); false for anything
// else. Devices and FIFOs are left out: writing to /dev/stdout destroys nothing, even when /dev/stdin is the same
// terminal.
bool regular_file_identity(const std::filesystem::path& path, dev_t& device, ino_t& inode) {
  struct stat s {};
  if (::stat(path.c_str(), &s) != 0 || !S_ISREG(s.st_mode)) return false;
  device = s.st_dev;
  inode = s.st_ino;
  return true;
}

}  // namespace

void check_output_not_input(const std::filesystem::path& output, const std::string& option,
                            const std::vector<InputFile>& inputs) {
  dev_t output_device = 0;
  ino_t output_inode = 0;
  if (!regular_file_identity(output, output_device, output_inode)) return;  // a new file is no input
  for (const InputFile& input : inputs) {
    dev_t device = 0;
    ino_t inode = 0;
    if (input.path.empty() || !regular_file_identity(input.path, device, inode) || device != output_device ||
        inode != output_inode)
      continue;
    const std::string named = input.path.string() == output.string() ? "" : " '" + input.path.string() + "'";
    throw InputError({output.string(), 0, option},
                     "the output is the input" + named +
                         (input.option.empty() ? std::string() : " (" + input.option + ")") +
                         " (the same file, perhaps through a link): writing it would destroy what is being read; "
                         "choose another output name");
  }
}

std::string lower_case_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  if (!extension.empty()) extension.erase(0, 1);
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
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
  // A library's message names the file it was given, the temporary: the user knows only `path`.
  const auto user_message = [&](const std::string& what) {
    return replace_all(replace_all(what, temporary.string(), path.string()), temporary.filename().string(),
                       path.filename().string());
  };
  try {
    write(temporary);
  } catch (const InputError&) {
    std::filesystem::remove(temporary, ignored);
    throw;
  } catch (const std::exception& e) {
    std::filesystem::remove(temporary, ignored);
    throw OutputError(path, user_message(e.what()));
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, ignored);
    throw OutputError(path, "renaming the finished temporary file failed: " + error.message());
  }
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    // C stdio rather than a stream: fwrite and fclose report why a write failed (ENOSPC, EIO) through errno.
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) throw std::runtime_error(std::string("cannot create the file: ") + std::strerror(errno));
    errno = 0;
    const bool written = std::fwrite(text.data(), 1, text.size(), file) == text.size() && std::fflush(file) == 0;
    const int write_errno = errno;
    const bool closed = std::fclose(file) == 0;
    const int close_errno = errno;
    if (!written || !closed)
      throw std::runtime_error(std::strerror(!written && write_errno != 0 ? write_errno : close_errno));
  });
}

}  // namespace rimu
