#include "render/text_file_output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "render/output_file.h"

namespace rimu {

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
