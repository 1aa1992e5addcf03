#include "spectral/io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <sstream>

#include "spectral/error.h"

namespace rimu {
namespace {

// An open file descriptor, closed on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

// The logs alive on this thread, innermost last.
thread_local std::vector<InputFileLog*> active_logs;

void record_in_active_logs(const std::filesystem::path& path, const std::optional<std::uint64_t>& digest) {
  if (active_logs.empty()) return;
  std::error_code error;
  std::filesystem::path absolute = std::filesystem::absolute(path, error);
  if (error) absolute = path;
  for (InputFileLog* log : active_logs) log->record(absolute.lexically_normal(), digest);
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw InputError({path.string(), 0, ""}, what);
}

// Opens `path` without blocking (a FIFO with no writer would block a plain open) and checks what fstat says about
// the very file opened, so nothing can be swapped in between the check and the read.
int open_checked(const std::filesystem::path& path, std::uintmax_t max_bytes, std::uintmax_t& size) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR) fail(path, "cannot open the file: it does not exist");
    if (error == EACCES) fail(path, "cannot open the file: permission denied");
    fail(path, std::string("cannot open the file: ") + std::strerror(error));
  }
  struct stat info {};
  if (::fstat(fd, &info) != 0) {
    const int error = errno;
    ::close(fd);
    fail(path, std::string("cannot inspect the file: ") + std::strerror(error));
  }
  if (!S_ISREG(info.st_mode)) {
    ::close(fd);
    if (S_ISDIR(info.st_mode)) fail(path, "is a directory; expected a file");
    const char* kind = S_ISFIFO(info.st_mode)  ? "a FIFO (named pipe)"
                       : S_ISCHR(info.st_mode) ? "a character device"
                       : S_ISBLK(info.st_mode) ? "a block device"
                       : S_ISSOCK(info.st_mode) ? "a socket"
                                                : "not a regular file";
    fail(path, std::string("is ") + kind + "; Rimu reads its inputs only from regular files (whose end is known)");
  }
  size = std::uintmax_t(info.st_size);
  if (size > max_bytes) {
    ::close(fd);
    fail(path, "the file is " + format_bytes(size) + "; the limit for this kind of input is " + format_bytes(max_bytes));
  }
  // Regular files ignore O_NONBLOCK; clear it anyway so reads behave as documented everywhere.
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

}  // namespace

InputFileLog::InputFileLog() { active_logs.push_back(this); }

InputFileLog::~InputFileLog() { std::erase(active_logs, this); }

void InputFileLog::record(const std::filesystem::path& path, const std::optional<std::uint64_t>& digest) {
  auto [it, inserted] = files_.emplace(path, digest);
  if (!inserted && digest) it->second = digest;  // read after being admitted: the read bytes' digest wins
}

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string format_bytes(std::uintmax_t bytes) {
  std::ostringstream out;
  if (bytes < 1024) {
    out << bytes << " bytes";
  } else {
    const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double value = double(bytes) / 1024.0;
    int unit = 0;
    while (value >= 1024.0 && unit < 5) value /= 1024.0, ++unit;
    out.precision(value < 10.0 ? 2 : 3);
    out << value << ' ' << units[unit] << " (" << bytes << " bytes)";
  }
  return out.str();
}

std::uintmax_t check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  std::uintmax_t size = 0;
  const Descriptor fd(open_checked(path, max_bytes, size));
  record_in_active_logs(path, std::nullopt);
  return size;
}

std::string read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  std::uintmax_t size = 0;
  const Descriptor fd(open_checked(path, max_bytes, size));
  std::string bytes;
  bytes.reserve(size_t(size));
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path, std::string("reading the file failed: ") + std::strerror(errno));
    }
    if (n == 0) break;
    if (bytes.size() + size_t(n) > max_bytes)
      fail(path, "the file grew past the limit for this kind of input (" + format_bytes(max_bytes) + ") while read");
    bytes.append(buffer, size_t(n));
  }
  if (!active_logs.empty()) record_in_active_logs(path, fnv1a(bytes));
  return bytes;
}

void reject_nul_bytes(std::string_view text, const std::string& name) {
  const size_t nul = text.find('\0');
  if (nul == std::string_view::npos) return;
  int line = 1;
  size_t line_start = 0;
  for (size_t i = 0; i < nul; ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  throw InputError({name, line, ""}, "column " + std::to_string(nul - line_start + 1) +
                                         ": a NUL byte (a binary file, or a text file damaged in transfer?); "
                                         "expected text");
}


}  // namespace rimu
