// Output destinations: temporaries a user recognises and that do not outlive a killed render, destinations checked
// before a render (unwritable folders, one file named twice), and library messages that name the user's file.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.h"
#include "render/output/output_file.h"
#include "spectral/error.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace output_file_test {

struct Folder : test::ScratchFolder {
  explicit Folder(const std::string& name) : ScratchFolder("output_file_" + name) {}
  void touch(const std::string& name) const { std::ofstream(path / name) << "partial"; }
  bool has(const std::string& name) const { return std::filesystem::exists(path / name); }
};

// The id of a process that has exited and been reaped: no process has it (until the kernel reuses it, which it
// does only after cycling through pid_max ids).
pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  REQUIRE(child > 0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

TEST_CASE("temporaries are named after their whole destination and marked incomplete") {
  const fs::path t = temporary_output_path(fs::path("shots") / "out.exr");
  CHECK(t.parent_path() == fs::path("shots"));
  const std::string name = t.filename().string();
  CHECK(name.rfind(".out.exr.rimu-incomplete-" + std::to_string(::getpid()) + "-", 0) == 0);
  CHECK(t.extension() == ".exr");  // OpenImageIO still sees the destination's format
}

TEST_CASE("stale temporaries of a killed writer are removed on the next run, live ones and others' are kept") {
  Folder folder("stale");
  const std::string dead = std::to_string(dead_pid()), live = std::to_string(::getpid());
  const std::string stale = ".out.exr.rimu-incomplete-" + dead + "-0.exr";
  const std::string stale_old_name = ".out.rimu-tmp-" + dead + "-3.exr";  // what earlier versions left behind
  // A live writer's temporary: this process's own next name (a fixed counter would be the very name
  // check_output_path's probe takes when this case runs alone in its process, as CTest runs it).
  const std::string running = temporary_output_path(folder.path / "out.exr").filename().string();
  CHECK(running.find("-" + live + "-") != std::string::npos);
  const std::string other_output = ".other.exr.rimu-incomplete-" + dead + "-0.exr";
  const std::string other_extension = ".out.exr.rimu-incomplete-" + dead + "-0.png";
  const std::string user_file = "out.exr.rimu-incomplete-" + dead + "-0.exr";  // not hidden: not ours
  for (const auto& name : {stale, stale_old_name, running, other_output, other_extension, user_file}) folder.touch(name);

  check_output_path(folder.path / "out.exr");
  CHECK_FALSE(folder.has(stale));
  CHECK_FALSE(folder.has(stale_old_name));
  CHECK(folder.has(running));
  CHECK(folder.has(other_output));
  CHECK(folder.has(other_extension));
  CHECK(folder.has(user_file));
  CHECK(remove_stale_temporaries(folder.path / "out.exr") == 0);  // nothing left to remove
}

TEST_CASE("a folder where no file can be created is refused up front, naming the user's path") {
  // /proc exists and is a folder, but no regular file can be created in it (not even by root).
  try {
    check_output_path("/proc/rimu-test.exr");
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.find("/proc/rimu-test.exr") != std::string::npos);
    CHECK(what.find("cannot create a file") != std::string::npos);
    CHECK(what.find("rimu-incomplete") == std::string::npos);
  }
  CHECK_THROWS_AS(check_output_path("/nonexistent-folder/x.exr"), InputError);
  Folder folder("probe");
  check_output_path(folder.path / "fine.exr");
  CHECK(fs::is_empty(folder.path));  // the probe leaves nothing behind
}

TEST_CASE("a library's message about the temporary is reported with the destination's name") {
  Folder folder("message");
  const fs::path path = folder.path / "final.exr";
  try {
    write_atomically(path, [](const fs::path& temporary) {
      throw std::runtime_error("Cannot open image file \"" + temporary.string() + "\". No space left on device.");
    });
    FAIL("expected an OutputError");
  } catch (const OutputError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.find("rimu-incomplete") == std::string::npos);
    CHECK(what.find("Cannot open image file \"" + path.string() + "\"") != std::string::npos);
  }
  CHECK(fs::is_empty(folder.path));
}

TEST_CASE("one file under two names is recognised as one output") {
  Folder folder("same");
  CHECK(same_output_file(folder.path / "a.exr", folder.path / "." / "sub" / ".." / "a.exr"));
  CHECK_FALSE(same_output_file(folder.path / "a.exr", folder.path / "b.exr"));
  const fs::path here = fs::current_path();
  fs::current_path(folder.path);
  CHECK(same_output_file("a.exr", folder.path / "a.exr"));
  fs::current_path(here);
  folder.touch("real.exr");
  fs::create_symlink(folder.path / "real.exr", folder.path / "link.exr");
  CHECK(same_output_file(folder.path / "link.exr", folder.path / "real.exr"));
  CHECK(lower_case_extension("X/Out.EXR") == "exr");
  CHECK(lower_case_extension("noext").empty());
}

TEST_CASE("an output that is an input is refused: by name, symbolic link and hard link, devices and new files pass") {
  Folder folder("not_input");
  folder.touch("scene.json");
  folder.touch("other.json");
  const fs::path scene = folder.path / "scene.json";
  fs::create_symlink(scene, folder.path / "link.exr");
  fs::create_hard_link(scene, folder.path / "hard.exr");
  const std::vector<InputFile> inputs{{folder.path / "other.json", "--csv"}, {scene, "the scene"}};
  for (const char* name : {"scene.json", "link.exr", "hard.exr"}) {
    CAPTURE(name);
    CHECK_THROWS_WITH_AS(check_output_not_input(folder.path / name, "-o", inputs),
                         doctest::Contains("-o: the output is the input"), InputError);
  }
  CHECK_THROWS_WITH_AS(check_output_not_input(folder.path / "link.exr", "-o", inputs),
                       doctest::Contains("(the scene)"), InputError);
  CHECK_NOTHROW(check_output_not_input(folder.path / "new.exr", "-o", inputs));    // does not exist yet
  CHECK_NOTHROW(check_output_not_input(folder.path / "other.json", "-o", {{scene, "the scene"}, {"", "none"}}));
  CHECK_NOTHROW(check_output_not_input("/dev/stdout", "-o", {{"/dev/stdin", "input"}}));  // may be one terminal
  CHECK(fs::file_size(scene) == 7);  // "partial": untouched
}

}  // namespace output_file_test
