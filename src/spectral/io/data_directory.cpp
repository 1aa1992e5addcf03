#include "spectral/io/data_directory.h"

#include <cstdlib>
#include <string>
#include <vector>

#include "spectral/error.h"

namespace rimu {
namespace {

std::filesystem::path executable_directory() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

bool looks_like_data(const std::filesystem::path& dir) {
  std::error_code ec;
  return !dir.empty() && std::filesystem::is_directory(dir / "cmf", ec);
}

}  // namespace

std::filesystem::path find_data_directory() {
  std::vector<std::filesystem::path> tried;
  if (const char* env = std::getenv("RIMU_DATA"); env && *env) {
    // An explicit setting wins, and a wrong one is an error rather than a silent fallback.
    if (looks_like_data(env)) return env;
    // Appended rather than built with operator+ ("'" + std::string): GCC 12 warns falsely (-Wrestrict, a known
    // false positive) on a string literal concatenated in front of a std::string.
    std::string message(1, '\'');
    message.append(env).append("' is not a Rimu data folder (it has no cmf/)");
    throw InputError({"", 0, "RIMU_DATA"}, message);
  }
  const auto exe_dir = executable_directory();
  for (const auto& candidate : {exe_dir / ".." / "share" / "rimu" / "data", exe_dir / "data"}) {
    if (looks_like_data(candidate)) return std::filesystem::weakly_canonical(candidate);
    tried.push_back(candidate);
  }
  std::string list;
  for (const auto& t : tried) list += "\n  " + t.string();
  throw InputError({}, "cannot find Rimu's data folder; set RIMU_DATA, or install it beside the binary. Looked in:" +
                           list);
}

std::filesystem::path data_file(const std::filesystem::path& relative) { return find_data_directory() / relative; }

}  // namespace rimu
