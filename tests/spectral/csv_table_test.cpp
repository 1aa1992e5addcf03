// Malformed CSV input: every error must say which file and which line.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "spectral/io/csv_table.h"
#include "spectral/error.h"
#include "spectral/spectra/tabulated_spectrum.h"

using namespace rimu;

namespace {

// Runs `action`, expects an InputError located at `file`:`line` (line 0 = no line), and returns its message.
// Checks the structured location and that the printed message carries it, as a user would read it.
template <typename Action>
std::string expect_error_at(Action&& action, const std::string& file, int line) {
  try {
    action();
  } catch (const InputError& e) {
    CHECK(e.where().file == file);
    CHECK(e.where().line == line);
    const std::string what = e.what();
    const std::string location = line > 0 ? file + ":" + std::to_string(line) : file;
    CHECK_MESSAGE(what.rfind(location + ":", 0) == 0, "message: " << what);
    return what;
  }
  FAIL("expected an InputError at " << file << ":" << line);
  return {};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a missing file names its path") {
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "rimu-no-such-dir" / "absent.csv";
  const std::string what = expect_error_at([&] { (void)CsvTable::read(missing); }, missing.string(), 0);
  CHECK(contains(what, "cannot open"));
}

TEST_CASE("comments, blank lines and CRLF keep line numbers and values right") {
  const CsvTable t = CsvTable::parse("# a comment\r\n\r\nwavelength_nm, v \r\n400,1.5\r\n# mid\r\n410 , +2e1\r\n", "crlf.csv");
  REQUIRE(t.row_count() == 2);
  CHECK(t.header()[1] == "v");  // trimmed, no '\r'
  CHECK(t.line_of_row(0) == 4);
  CHECK(t.line_of_row(1) == 6);
  const auto v = t.numbers(t.column_index("v"));
  CHECK(v[0] == 1.5);
  CHECK(v[1] == 20.0);
}

TEST_CASE("a non-numeric cell is reported at its line") {
  // Line 1 comment, 2 header, 3 first row, 4 blank, 5 the bad row.
  const CsvTable t = CsvTable::parse("# units: nm\nwavelength_nm,v\n400,1\n\n410,abc\n420,2\n", "letters.csv");
  const std::string what = expect_error_at([&] { (void)t.numbers(1); }, "letters.csv", 5);
  CHECK(contains(what, "'abc'"));
  CHECK(contains(what, "column 'v'"));
  // Trailing garbage after a number, and an empty cell, are not numbers either.
  expect_error_at([] { (void)CsvTable::parse("l,v\n400,1.5nm\n", "suffix.csv").numbers(1); }, "suffix.csv", 2);
  expect_error_at([] { (void)CsvTable::parse("l,v\n400,1\n410,\n", "empty.csv").numbers(1); }, "empty.csv", 3);
}

TEST_CASE("NaN and infinite cells are rejected by numbers()") {
  // from_chars accepts "nan" and "inf", and 1e999 overflows: none may reach a spectrum.
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "Infinity", "1e999"}) {
    CAPTURE(bad);
    const CsvTable t = CsvTable::parse(std::string("wavelength_nm,v\n400,1\n410,2\n420,") + bad + "\n", "special.csv");
    expect_error_at([&] { (void)t.numbers(1); }, "special.csv", 4);
  }
  double x = 0;
  CHECK(parse_finite_number(" -1.25e-3 ", x));
  CHECK(x == -1.25e-3);
  CHECK_FALSE(parse_finite_number("nan", x));
  CHECK_FALSE(parse_finite_number("", x));
  CHECK_FALSE(parse_finite_number("+", x));
  CHECK_FALSE(parse_finite_number("1,5", x));
}

TEST_CASE("a row with the wrong cell count is reported at its line") {
  const std::string what_few =
      expect_error_at([] { (void)CsvTable::parse("l,a,b\n400,1,2\n410,1\n", "few.csv"); }, "few.csv", 3);
  CHECK(contains(what_few, "expected 3"));
  CHECK(contains(what_few, "found 2"));
  const std::string what_many = expect_error_at(
      [] { (void)CsvTable::parse("# c\nl,a\n400,1\n\n# c\n410,1,2\n", "many.csv"); }, "many.csv", 6);
  CHECK(contains(what_many, "found 3"));
}

TEST_CASE("empty files and header-only files are refused") {
  const std::string empty = expect_error_at([] { (void)CsvTable::parse("# only a comment\n\n", "empty.csv"); }, "empty.csv", 0);
  CHECK(contains(empty, "empty"));
  const std::string header = expect_error_at([] { (void)CsvTable::parse("l,v\n", "header.csv"); }, "header.csv", 0);
  CHECK(contains(header, "no data rows"));
}

TEST_CASE("an unknown column lists the columns that exist") {
  const CsvTable t = CsvTable::parse("wavelength_nm,n,k\n400,1,2\n", "metal.csv");
  const std::string what = expect_error_at([&] { (void)t.column_index("eta"); }, "metal.csv", 1);
  CHECK(contains(what, "'eta'"));
  CHECK(contains(what, "wavelength_nm, n, k"));
}

TEST_CASE("non-monotonic wavelengths are reported at the offending row") {
  // 420 after 430 on line 5 (line 1 is a comment).
  const CsvTable down = CsvTable::parse("# c\nwavelength_nm,v\n410,1\n430,2\n420,3\n440,4\n", "down.csv");
  const std::string what = expect_error_at(
      [&] { (void)TabulatedSpectrum::from_csv(down, "v", Extrapolation::zero); }, "down.csv", 5);
  CHECK(contains(what, "420"));
  CHECK(contains(what, "430"));
  // A repeated wavelength is not strictly increasing either.
  const CsvTable repeat = CsvTable::parse("wavelength_nm,v\n410,1\n420,2\n420,3\n", "repeat.csv");
  expect_error_at([&] { (void)TabulatedSpectrum::from_csv(repeat, "v", Extrapolation::zero); }, "repeat.csv", 4);
  // A bad value in the value column is found by from_csv with its line, too.
  const CsvTable bad_value = CsvTable::parse("wavelength_nm,v\n410,1\n420,x\n", "value.csv");
  expect_error_at([&] { (void)TabulatedSpectrum::from_csv(bad_value, "v", Extrapolation::zero); }, "value.csv", 3);
}

TEST_CASE("a first line of numbers is data, not a header") {
  // A header-less table used to lose its first row to the header.
  const CsvTable t = CsvTable::parse("400,0.5\n410,0.6\n420,0.7\n", "bare.csv");
  CHECK(t.headerless());
  REQUIRE(t.row_count() == 3);
  CHECK(t.line_of_row(0) == 1);
  CHECK(t.header() == std::vector<std::string>{"wavelength_nm", "value"});
  CHECK(t.numbers(t.column_index("value"))[0] == 0.5);
  const TabulatedSpectrum s = TabulatedSpectrum::from_csv(t, "value", Extrapolation::zero);
  CHECK(s.value(400.0) == 0.5);
  const CsvTable wide = CsvTable::parse("# no header\n400,1,2,3\n410,1,2,3\n", "wide.csv");
  CHECK(wide.header() == std::vector<std::string>{"wavelength_nm", "column_2", "column_3", "column_4"});
  CHECK(wide.line_of_row(0) == 2);
  // A header with one numeric cell is still a header.
  CHECK_FALSE(CsvTable::parse("wavelength_nm,5\n400,1\n", "h.csv").headerless());
  const std::string what = expect_error_at([&] { (void)t.column_index("red"); }, "bare.csv", 0);
  CHECK(contains(what, "no header line"));
}

TEST_CASE("semicolons, tabs and micrometres get a message that says what a spectrum CSV is") {
  for (const char* text : {"wavelength_nm;value\n400;0,5\n", "400;0.5\n410;0.6\n", "wavelength_nm\tvalue\n400\t1\n"}) {
    CAPTURE(text);
    const std::string what = expect_error_at([&] { (void)CsvTable::parse(text, "sep.csv"); }, "sep.csv", 1);
    CHECK(contains(what, "separated by"));
    CHECK(contains(what, "wavelength_nm,value"));
    CHECK(contains(what, "nanometres"));
    CHECK(contains(what, "commas"));
  }
  // The same table in micrometres (as optics databases publish n and k).
  const CsvTable um = CsvTable::parse("wavelength_um,n\n0.38,1.5\n0.58,1.49\n0.78,1.48\n", "um.csv");
  const std::string what =
      expect_error_at([&] { (void)TabulatedSpectrum::from_csv(um, "n", Extrapolation::clamp); }, "um.csv", 4);
  CHECK(contains(what, "micrometres"));
  CHECK(contains(what, "nanometres"));
  CHECK_NOTHROW(TabulatedSpectrum::from_csv(CsvTable::parse("l,n\n50,1\n380,1.5\n", "nm.csv"), "n", Extrapolation::clamp));
}

TEST_CASE("a CSV that is not a regular file, or holds a NUL byte, is refused by name") {
  const std::string dir = std::filesystem::temp_directory_path().string();
  const std::string what = expect_error_at([&] { (void)CsvTable::read(dir); }, dir, 0);
  CHECK(contains(what, "is a directory"));
  CHECK(contains(expect_error_at([] { (void)CsvTable::read("/dev/urandom"); }, "/dev/urandom", 0), "device"));
  CHECK(contains(expect_error_at([] { (void)CsvTable::parse(std::string("l,v\n400,1\n4\0" "10,2\n", 17), "nul.csv"); },
                                 "nul.csv", 3),
                 "NUL"));
}

TEST_CASE("spectral values must be 0 or 1e-30 to 1e30 in magnitude, numbers beyond a double say so") {
  // Before: a flat 1e-310 W/nm light gave XYZ "inf 100 inf" and xy "nan"; 1.7e308 an unrelated blackbody error.
  for (const char* bad : {"1e-310", "1e-31", "-1e-31", "1e31", "1.7e308"}) {
    CAPTURE(bad);
    const CsvTable t = CsvTable::parse(std::string("wavelength_nm,p\n400,1\n410,") + bad + "\n420,1\n", "range.csv");
    const std::string what = expect_error_at(
        [&] { (void)TabulatedSpectrum::from_csv(t, "p", Extrapolation::zero); }, "range.csv", 3);
    CHECK(contains(what, "column 'p'"));
    CHECK(contains(what, "1e-30 to 1e30"));
  }
  for (const char* edge : {"0", "1e-30", "-1e-30", "1e30"}) {
    CAPTURE(edge);
    const CsvTable t = CsvTable::parse(std::string("wavelength_nm,p\n400,1\n410,") + edge + "\n420,1\n", "edge.csv");
    CHECK_NOTHROW((void)TabulatedSpectrum::from_csv(t, "p", Extrapolation::zero));
  }
  // A number a double cannot hold is not "not a number": the message says it is out of range.
  for (const char* beyond : {"1e-400", "1e400", "+1e-400"}) {
    CAPTURE(beyond);
    const CsvTable t = CsvTable::parse(std::string("wavelength_nm,p\n400,1\n410,") + beyond + "\n", "beyond.csv");
    const std::string what = expect_error_at([&] { (void)t.numbers(1); }, "beyond.csv", 3);
    CHECK(contains(what, "beyond the range of double-precision numbers"));
  }
}
