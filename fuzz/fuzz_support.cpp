#include "fuzz_support.h"

#include <unistd.h>

#include <fstream>

namespace rimu::fuzz {

namespace {

// A folder only this process uses (mkdtemp makes it 0700), removed at exit.
struct PrivateFolder {
  std::filesystem::path path;
  PrivateFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "rimu-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) {
      std::perror("rimu fuzz: mkdtemp");
      std::abort();
    }
    path = pattern;
  }
  ~PrivateFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

const std::filesystem::path& private_folder() {
  static PrivateFolder folder;
  return folder.path;
}

std::filesystem::path write_private_file(const uint8_t* data, size_t size, const std::string& extension) {
  const std::filesystem::path file = private_folder() / ("input" + extension);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  out.close();
  if (!out) {
    std::perror("rimu fuzz: writing the private input file");
    std::abort();
  }
  return file;
}

}  // namespace rimu::fuzz
