// CIE 224:2017 colour fidelity and TM-30-20 gamut/hue-bin values against the official calculators' outputs.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/colour_rendering/colour_fidelity.h"
#include "spectral/io/csv_table.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;

namespace {

const ColourFidelityEvaluator& evaluator() {
  static const ColourFidelityEvaluator e(test::library());
  return e;
}

}  // namespace

TEST_CASE("Rf of CIE F1, F2 and the CIE 224 example LED match the CIE 2017 calculator to its 0.1") {
  // Outputs of the CIE's official CIE 224:2017 spreadsheet (TC 1-90, files.cie.co.at/933_TC1-90.zip) as quoted
  // in colour-science's colour/quality/tests/test_cfi2017.py @ 9d743142: F1 80.6, F2 70.1, the calculator's
  // example spectrum 81.6 (with R_f,CES1..20). Published to 1 decimal: within 0.05, plus 0.05 for the
  // calculator's own choices we cannot see (its 1 nm interpolation of 5 nm data).
  CHECK(std::abs(evaluator().evaluate(*test::library().illuminant("F1")).rf - 80.6) <= 0.1);
  CHECK(std::abs(evaluator().evaluate(*test::library().illuminant("F2")).rf - 70.1) <= 0.1);
  const CsvTable table = CsvTable::read(test::test_data("cie224_calculator_example_5nm.csv"));
  const TabulatedSpectrum led = TabulatedSpectrum::from_csv(table, "power", Extrapolation::zero);
  const ColourFidelity cf = evaluator().evaluate(led);
  CHECK(std::abs(cf.rf - 81.6) <= 0.1);
  const double published[20] = {89.5, 80.5, 81.5, 79.4, 65.9, 79.4, 73.2, 68.5, 95.9, 76.3,
                                71.9, 71.8, 83.3, 93.0, 89.2, 72.9, 75.1, 85.8, 75.1, 63.4};
  for (int i = 0; i < 20; ++i) {
    CAPTURE(i + 1);
    CAPTURE(cf.sample_fidelity[size_t(i)]);
    CHECK(std::abs(cf.sample_fidelity[size_t(i)] - published[i]) <= 0.1);
  }
}

TEST_CASE("TM-30 Rg, hue-bin fidelity and chroma/hue shifts of F2 match the IES TM-30-18 calculator") {
  // IES TM-30-18 Excel calculator (media.ies.org/docs/errata/TM-30-18_tools_etc.zip) output for CIE F2, as
  // quoted in colour-science's colour/quality/tests/test_tm3018.py @ 9d743142: R_f 70, R_g 86, CCT 4225 K,
  // Duv 0.0019, and per bin R_f,hj, R_cs,hj (%), R_hs,hj. TM-30-20 computes these the same way. Printed as
  // integers (R_hs to 2 decimals): within half a unit, plus 0.25 for the calculator's 1 nm interpolation.
  const ColourFidelity cf = evaluator().evaluate(*test::library().illuminant("F2"));
  CHECK(std::abs(cf.rf - 70) <= 0.75);
  CHECK(std::abs(cf.rg - 86) <= 0.75);
  CHECK(std::abs(cf.cct.cct_k - 4225) <= 1.0);
  // Duv: the calculator interpolates the 5 nm F2 to 1 nm, which moves its chromaticity (y by 1.7e-4, see
  // tristimulus_method_test.cpp); our sums stay at 5 nm and give 0.00179. Half a unit of 0.0019 plus that shift.
  CHECK(std::abs(cf.cct.duv - 0.0019) <= 1.5e-4);
  const double bin_rf[16] = {60, 61, 53, 68, 80, 88, 77, 73, 76, 62, 70, 77, 81, 71, 64, 65};
  const double bin_rcs[16] = {-25, -18, -9, 5, 11, 4, -8, -15, -17, -15, -4, 5, 11, 7, -6, -16};
  const double bin_rhs[16] = {-0.02, 0.14, 0.24, 0.20, 0.09, -0.07, -0.12, -0.08,
                              0.01, 0.17, 0.19, 0.11, -0.08, -0.15, -0.26, -0.17};
  for (int j = 0; j < 16; ++j) {
    CAPTURE(j + 1);
    const HueBin& b = cf.bins[size_t(j)];
    CAPTURE(b.fidelity);
    CAPTURE(b.chroma_shift);
    CAPTURE(b.hue_shift);
    CHECK(std::abs(b.fidelity - bin_rf[j]) <= 0.75);
    CHECK(std::abs(100 * b.chroma_shift - bin_rcs[j]) <= 0.75);
    CHECK(std::abs(b.hue_shift - bin_rhs[j]) <= 0.0075);
  }
}

TEST_CASE("a source rated against itself has Rf = 100 and Rg = 100") {
  // The reference of a Planckian source is the same Planckian: every ΔE' is 0, so R_f = 10 ln(e^10 + 1).
  const ColourFidelity cf = evaluator().evaluate(*test::library().illuminant("A"));
  CHECK(cf.rf == doctest::Approx(100.0).epsilon(1e-3));
  CHECK(cf.rg == doctest::Approx(100.0).epsilon(1e-3));
  int samples = 0;
  for (const HueBin& b : cf.bins) samples += b.sample_count;
  CHECK(samples == kCesCount);
}

TEST_CASE("the colour fidelity index refuses a source that misses 380-780 nm") {
  const TabulatedSpectrum narrow({400, 500, 600, 700}, {1, 1, 1, 1}, Extrapolation::zero, "narrow.csv");
  CHECK_THROWS_WITH_AS(evaluator().evaluate(narrow), doctest::Contains("380 to 780 nm"), InputError);
}
