// Colour differences: CIEDE2000 against Sharma, Wu & Dalal's test data, and ΔE*ab.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/delta_e.h"
#include "test_support.h"

using namespace rimu;

TEST_CASE("CIEDE2000 reproduces all 34 pairs of Sharma, Wu & Dalal (2005) Table 1") {
  // Sharma, Wu & Dalal, Color Res. Appl. 30(1):21-30 (2005), Table 1: the inputs are exact as printed and
  // ΔE00 is printed to 4 decimals, so a correct implementation lands within half a unit of the 4th decimal
  // (5e-5). Pairs 7-16 probe the hue-angle edge cases (neutral colours, |Δh| at 180°, mean hue across 0°).
  const CsvTable table = CsvTable::read(test::test_data("sharma2005_ciede2000.csv"));
  REQUIRE(table.row_count() == 34);
  const auto column = [&](const char* name) { return table.numbers(table.column_index(name)); };
  const auto l1 = column("L1"), a1 = column("a1"), b1 = column("b1");
  const auto l2 = column("L2"), a2 = column("a2"), b2 = column("b2");
  const auto expected = column("dE00");
  for (size_t i = 0; i < table.row_count(); ++i) {
    const Lab first{l1[i], a1[i], b1[i]};
    const Lab second{l2[i], a2[i], b2[i]};
    const double forward = delta_e_2000(first, second);
    const double backward = delta_e_2000(second, first);
    CAPTURE(i + 1);
    CAPTURE(forward);
    CAPTURE(expected[i]);
    CHECK(std::abs(forward - expected[i]) <= 5e-5 + 1e-12);
    // ΔE00 is symmetric in exact arithmetic (every swapped term changes sign in pairs); only rounding remains.
    CHECK(std::abs(forward - backward) <= 1e-12);
  }
}

TEST_CASE("CIEDE2000 of a pure lightness difference scales with 1/kL") {
  // With a* = b* = 0 for both colours, ΔC' = ΔH' = 0 and ΔE00 = |ΔL'|/(kL·SL): doubling kL halves it.
  // At L̄' = 50, SL = 1, so the difference equals |ΔL| itself.
  const Lab dark{45.0, 0.0, 0.0}, light{55.0, 0.0, 0.0};
  CHECK(delta_e_2000(dark, light) == doctest::Approx(10.0).epsilon(1e-14));
  CHECK(delta_e_2000(dark, light, {.k_l = 2.0}) == doctest::Approx(5.0).epsilon(1e-14));
  // kC and kH do not touch a pure lightness difference.
  CHECK(delta_e_2000(dark, light, {.k_c = 3.0, .k_h = 7.0}) == doctest::Approx(10.0).epsilon(1e-14));
  CHECK(delta_e_2000(light, light) == 0.0);
}

TEST_CASE("CIE76 is the Euclidean distance in CIELAB") {
  CHECK(delta_e_1976({50.0, 0.0, 0.0}, {53.0, 4.0, 12.0}) == doctest::Approx(13.0).epsilon(1e-15));
  CHECK(delta_e_1976({50.0, 2.0, -3.0}, {50.0, 2.0, -3.0}) == 0.0);
}
