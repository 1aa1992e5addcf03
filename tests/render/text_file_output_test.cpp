// Text outputs (render/output/text_file_output.h): whole or not at all, and a failed write is an error naming the path.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <unistd.h>

#include "render/output/output_file.h"
#include "render/output/text_file_output.h"
#include "spectral/error.h"

using namespace rimu;

namespace {

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path scratch_folder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() / ("rimu-text-output-" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace

TEST_CASE("text output: a file is written whole and replaces the old one, with no temporary left behind") {
  const auto folder = scratch_folder("whole");
  const auto path = folder / "lamp.json";
  write_text_file(path, "old\n");
  write_text_file(path, "{\"type\": \"point\"}\n");
  CHECK(read_all(path) == "{\"type\": \"point\"}\n");
  CHECK(std::distance(std::filesystem::directory_iterator(folder), std::filesystem::directory_iterator()) == 1);
  std::filesystem::remove_all(folder.parent_path());
}

TEST_CASE("text output: a full disk is an OutputError naming the path and the reason, and the device stays a device") {
  if (!std::filesystem::is_character_file("/dev/full")) return;  // not Linux: nothing to test against
  try {
    write_text_file("/dev/full", "{\"type\": \"point\"}\n");
    FAIL("writing to /dev/full succeeded");
  } catch (const OutputError& e) {
    CHECK(std::string(e.what()).find("/dev/full") != std::string::npos);
    CHECK(std::string(e.what()).find("No space left on device") != std::string::npos);
  }
  // A temporary renamed over it would have replaced the device node with a regular file.
  CHECK(std::filesystem::is_character_file("/dev/full"));
}

TEST_CASE("text output: a missing folder is bad input, a symbolic link is written through and kept") {
  const auto folder = scratch_folder("link");
  CHECK_THROWS_AS(write_text_file(folder / "no_such_folder" / "x.json", "x"), InputError);
  const auto target = folder / "target.json", link = folder / "link.json";
  write_text_file(target, "before\n");
  std::filesystem::create_symlink(target, link);
  write_text_file(link, "after\n");
  CHECK(std::filesystem::is_symlink(link));
  CHECK(read_all(target) == "after\n");
  std::filesystem::remove_all(folder.parent_path());
}
