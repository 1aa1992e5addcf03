// Bad spectrum descriptions give a clear InputError naming the file, line or option (the rimu-colour contract).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "spectral/error.h"
#include "spectral/library/spectrum_source.h"
#include "test_support.h"

using namespace rimu;

namespace {

std::filesystem::path write_temp_csv(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("rimu_test_" + name + ".csv");
  std::ofstream(path) << text;
  return path;
}

SpectrumSource csv_source(const std::filesystem::path& path) {
  SpectrumSource s;
  s.kind = SpectrumSource::Kind::csv_file;
  s.name = path.string();
  return s;
}

// Runs `make` and returns the InputError's message (fails the test if nothing was thrown).
std::string error_of(const SpectrumSource& source) {
  try {
    make_emission_spectrum(source, test::library());
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("expected an InputError for " << source.describe());
  return {};
}

}  // namespace

TEST_CASE("a valid CSV spectrum loads and keeps its values") {
  const auto path = write_temp_csv("valid", "wavelength_nm,power\n400,1\n500,2\n600,3\n");
  const SpectrumPtr s = make_emission_spectrum(csv_source(path), test::library());
  CHECK(s->value(450.0) == doctest::Approx(1.5));
  CHECK(s->value(300.0) == 0.0);  // emission: zero outside the measured range
}

TEST_CASE("bad CSV spectra name the file and the line") {
  SUBCASE("missing file") {
    const std::string msg = error_of(csv_source("/nonexistent/lamp.csv"));
    CHECK(msg.find("/nonexistent/lamp.csv") != std::string::npos);
    CHECK(msg.find("cannot open") != std::string::npos);
  }
  SUBCASE("non-numeric value") {
    const auto path = write_temp_csv("text", "wavelength_nm,power\n400,1\n500,bright\n600,3\n");
    const std::string msg = error_of(csv_source(path));
    CHECK(msg.find(path.string() + ":3") != std::string::npos);
    CHECK(msg.find("bright") != std::string::npos);
  }
  SUBCASE("NaN value") {
    const auto path = write_temp_csv("nan", "wavelength_nm,power\n400,1\n500,2\n600,nan\n");
    CHECK(error_of(csv_source(path)).find(path.string() + ":4") != std::string::npos);
  }
  SUBCASE("non-monotonic wavelengths") {
    const auto path = write_temp_csv("order", "wavelength_nm,power\n400,1\n500,2\n450,3\n");
    const std::string msg = error_of(csv_source(path));
    CHECK(msg.find(path.string() + ":4") != std::string::npos);
    CHECK(msg.find("increase") != std::string::npos);
  }
  SUBCASE("negative power") {
    const auto path = write_temp_csv("negative", "wavelength_nm,power\n400,1\n500,-2\n600,3\n");
    const std::string msg = error_of(csv_source(path));
    CHECK(msg.find(path.string() + ":3") != std::string::npos);
    CHECK(msg.find("negative") != std::string::npos);
  }
  SUBCASE("wrong number of cells") {
    const auto path = write_temp_csv("cells", "wavelength_nm,power\n400,1\n500\n");
    CHECK(error_of(csv_source(path)).find(path.string() + ":3") != std::string::npos);
  }
  SUBCASE("no visible power") {
    const auto path = write_temp_csv("infrared", "wavelength_nm,power\n900,1\n1000,2\n");
    const std::string msg = error_of(csv_source(path));
    CHECK(msg.find("no power in 360-830 nm") != std::string::npos);
    // The message leads with the file (it named none).
    CHECK(msg.rfind(path.string() + ": ", 0) == 0);
  }
}

TEST_CASE("bad named, blackbody and daylight spectra name the option") {
  SpectrumSource s;
  s.kind = SpectrumSource::Kind::named_illuminant;
  s.name = "D66";
  CHECK(error_of(s).find("unknown illuminant 'D66'") != std::string::npos);

  s.kind = SpectrumSource::Kind::blackbody;
  s.number = -5;
  s.where.key = "--blackbody";
  CHECK(error_of(s).find("--blackbody") != std::string::npos);

  s.kind = SpectrumSource::Kind::daylight;
  s.number = 3000;
  s.where.key = "--daylight";
  const std::string msg = error_of(s);
  CHECK(msg.find("--daylight") != std::string::npos);
  CHECK(msg.find("4000-25000 K") != std::string::npos);
}
