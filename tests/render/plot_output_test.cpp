// rimu_render's plots (render/output/plot_output.h, light_definition.h, ies_report.h): titles show file names, not paths;
// bad destinations are InputError and a missing gnuplot a RenderError (exit codes 1 and 2 in the tools).
#include <doctest/doctest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "render/scene/light_definition.h"
#include "render/output/plot_output.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/error.h"

using namespace rimu;

TEST_CASE("spectrum_plot_title: a CSV spectrum by its file name and column, anything else as described") {
  CHECK(spectrum_plot_title("/home/someone/lamps/warm white.csv [power]") == "warm white.csv [power]");
  CHECK(spectrum_plot_title("/data/spectra/cie_a_1nm.csv") == "cie_a_1nm.csv");
  CHECK(spectrum_plot_title("lamp.csv [power]") == "lamp.csv [power]");
  CHECK(spectrum_plot_title("blackbody 2700 K") == "blackbody 2700 K");
}

TEST_CASE("plot_spectrum_png: a missing folder is an InputError, a missing gnuplot a RenderError") {
  const BlackbodySpectrum shape(2700.0, BlackbodySpectrum::Scale::peak_one);
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "rimu-no-such-folder-4711" / "p.png";
  CHECK_THROWS_AS(plot_spectrum_png(shape, 1.0, "relative", "t", missing), InputError);
  const std::filesystem::path png =
      std::filesystem::temp_directory_path() / ("rimu-plot-output-test-" + std::to_string(::getpid()) + ".png");
  const char* saved = std::getenv("RIMU_GNUPLOT");
  const std::string saved_value = saved ? saved : "";
  ::setenv("RIMU_GNUPLOT", "/nonexistent/gnuplot", 1);
  CHECK_THROWS_AS(check_plot_png(png, {"", 0, "--plot"}), RenderError);
  CHECK_THROWS_AS(plot_spectrum_png(shape, 1.0, "relative", "t", png), RenderError);
  if (saved) ::setenv("RIMU_GNUPLOT", saved_value.c_str(), 1);
  else ::unsetenv("RIMU_GNUPLOT");
  CHECK_FALSE(std::filesystem::exists(png));
}
