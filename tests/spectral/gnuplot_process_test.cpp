// The plotting runner (spectral/io/gnuplot_process.h): no user text is expanded, the PNG lands at exactly the given
// path, and the private temporary folder is gone afterwards whether gnuplot succeeded or failed.
#include <doctest/doctest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "spectral/error.h"
#include "spectral/io/gnuplot_process.h"

using namespace rimu;
namespace fs = std::filesystem;

namespace {

// A fresh folder holding `out/` (where plots go) and `tmp/` (this process's $TMPDIR while the test runs), removed
// with the previous $TMPDIR and $RIMU_GNUPLOT restored at the end.
class Sandbox {
 public:
  Sandbox() {
    std::string pattern = (fs::temp_directory_path() / "rimu-gnuplot-test-XXXXXX").string();
    REQUIRE(::mkdtemp(pattern.data()) != nullptr);
    root_ = pattern;
    fs::create_directory(out());
    fs::create_directory(tmp());
    for (const char* name : {"TMPDIR", "RIMU_GNUPLOT"})
      if (const char* v = std::getenv(name)) saved_.emplace_back(name, std::string(v));
      else saved_.emplace_back(name, std::nullopt);
    ::setenv("TMPDIR", tmp().c_str(), 1);
    ::unsetenv("RIMU_GNUPLOT");
  }
  ~Sandbox() {
    for (const auto& [name, value] : saved_)
      if (value) ::setenv(name.c_str(), value->c_str(), 1);
      else ::unsetenv(name.c_str());
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }
  fs::path out() const { return root_ / "out"; }
  fs::path tmp() const { return root_ / "tmp"; }

 private:
  fs::path root_;
  std::vector<std::pair<std::string, std::optional<std::string>>> saved_;
};

size_t entries_in(const fs::path& folder) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++n;
  return n;
}

GnuplotJob line_plot(const std::string& title) {
  GnuplotJob job;
  job.data_files = {{"line.dat", "1 1\n2 4\n3 9\n"}};
  job.commands = "set title " + gnuplot_text(title) + " noenhanced\nplot 'line.dat' using 1:2 with lines notitle";
  return job;
}

}  // namespace

TEST_CASE("gnuplot_text: a single-quoted string with no character gnuplot could expand or end it with") {
  const std::string hostile = "a'b\"c`touch x`$(y)@m{z}^_~&\\\n\r";
  const std::string quoted = gnuplot_text(hostile);
  CHECK(quoted.front() == '\'');
  CHECK(quoted.back() == '\'');
  const std::string inside = quoted.substr(1, quoted.size() - 2);
  CHECK(inside.size() == hostile.size());
  for (char c : std::string("'\"`$@{}^~&\\\n\r")) CHECK_MESSAGE(inside.find(c) == std::string::npos, "found " << c);
  // Ordinary titles pass unchanged, including UTF-8 and file names with underscores.
  CHECK(gnuplot_text("cie_a_1nm.csv [power], C 0-180°") == "'cie_a_1nm.csv [power], C 0-180°'");
  CHECK(plot_file_name("/home/someone/lamps/warm.csv") == "warm.csv");
}

TEST_CASE("run_gnuplot draws to exactly the given path and leaves no temporary file") {
  Sandbox box;
  const fs::path marker = box.out() / "INJECTED";
  // A destination and a title that would run commands if they reached a shell or gnuplot's backquote expansion.
  const fs::path png = box.out() / "x';touch P;'`touch Q`.png";
  run_gnuplot(line_plot("`touch " + marker.string() + "` $(touch " + marker.string() + ")"), png);
  CHECK(fs::is_regular_file(png));
  CHECK(fs::file_size(png) > 1000);
  CHECK_FALSE(fs::exists(marker));
  CHECK(entries_in(box.out()) == 1);  // the PNG and nothing else (no .gp, .dat, .log, hidden temporary)
  CHECK(entries_in(box.tmp()) == 0);  // the private folder is gone
  // A second run replaces the file.
  run_gnuplot(line_plot("again"), png);
  CHECK(entries_in(box.out()) == 1);
}

TEST_CASE("run_gnuplot: a broken script is a PlotError carrying gnuplot's message, nothing is left behind") {
  Sandbox box;
  GnuplotJob job;
  job.commands = "plot 'line.dat' using 1:2 with lines\nthis_is_not_a_gnuplot_command";
  job.data_files = {{"line.dat", "1 1\n2 2\n"}};
  const fs::path png = box.out() / "broken.png";
  std::string message;
  try {
    run_gnuplot(job, png);
  } catch (const PlotError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(message.find("gnuplot") != std::string::npos);
  CHECK(message.find("broken.png") != std::string::npos);
  CHECK(message.find("invalid command") != std::string::npos);  // gnuplot's own words, from its stderr
  CHECK_FALSE(fs::exists(png));
  CHECK(entries_in(box.out()) == 0);
  CHECK(entries_in(box.tmp()) == 0);
}

TEST_CASE("run_gnuplot: missing gnuplot and a missing folder are refused before anything is written") {
  Sandbox box;
  SUBCASE("missing gnuplot (RIMU_GNUPLOT)") {
    ::setenv("RIMU_GNUPLOT", (box.tmp() / "no-such-gnuplot").c_str(), 1);
    std::string message;
    try {
      run_gnuplot(line_plot("t"), box.out() / "p.png");
    } catch (const PlotError& e) {
      message = e.what();
    }
    CAPTURE(message);
    CHECK(message.find("gnuplot not found at") != std::string::npos);
    CHECK(message.find("no-such-gnuplot") != std::string::npos);
  }
  SUBCASE("missing folder") {
    CHECK_THROWS_AS(check_plot_destination(box.out() / "nope" / "p.png", {"", 0, "--plot"}), InputError);
    CHECK_THROWS_AS(run_gnuplot(line_plot("t"), box.out() / "nope" / "p.png"), InputError);
  }
  SUBCASE("a folder as the destination") {
    CHECK_THROWS_AS(check_plot_destination(box.out(), {"", 0, "--plot"}), InputError);
  }
  CHECK(entries_in(box.out()) == 0);
  CHECK(entries_in(box.tmp()) == 0);
}
