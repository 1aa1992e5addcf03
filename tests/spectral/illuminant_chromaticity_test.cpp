// Chromaticities of CIE illuminants under both standard observers against CIE 15:2004 Tables T.3 and T.8.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "spectral/colorimetry/colorimetry.h"
#include "test_support.h"

using namespace rimu;

namespace {

struct Row {
  std::string illuminant;
  StandardObserver observer;
  IntegrationGrid grid;
  double x, y;
  double tolerance;  // half a unit in the last published decimal, plus 1e-6 for float rounding
};

void check_rows(const Row* begin, const Row* end) {
  for (const Row* row = begin; row != end; ++row) {
    CAPTURE(row->illuminant);
    CAPTURE(int(row->observer));
    const Observer& o = test::library().observer(row->observer);
    const Chromaticity xy = chromaticity_of(illuminant_xyz(*test::library().illuminant(row->illuminant), o, row->grid));
    CAPTURE(xy.x);
    CAPTURE(xy.y);
    CHECK(std::abs(xy.x - row->x) <= row->tolerance);
    CHECK(std::abs(xy.y - row->y) <= row->tolerance);
  }
}

}  // namespace

TEST_CASE("F2, F7, F11 (2°) match CIE 15:2004 Table T.8 to 4 decimals") {
  // T.8 was computed from the 5 nm tables over 380-780 nm (the 1 nm sum gives F2 y = 0.3753, not 0.3751).
  const auto abridged = IntegrationGrid::cie_5nm_abridged();
  const Row rows[] = {
      {"F2", StandardObserver::cie1931_2deg, abridged, 0.3721, 0.3751, 5.1e-5},
      {"F7", StandardObserver::cie1931_2deg, abridged, 0.3129, 0.3292, 5.1e-5},
      {"F11", StandardObserver::cie1931_2deg, abridged, 0.3805, 0.3769, 5.1e-5},
  };
  check_rows(std::begin(rows), std::end(rows));
}

TEST_CASE("F2, F7, F11 (10°) match colour-science's 5-decimal values, computed at 1 nm") {
  // T.8's own 10° column could not be found in a citable text, so it is not asserted. colour-science's
  // CCS_ILLUMINANTS (colour/colorimetry/datasets/illuminants/chromaticity_coordinates.py @ 60679360) gives
  // FL2 (0.37925, 0.36733), FL7 (0.31569, 0.32960), FL11 (0.38541, 0.37123) for the 10° observer: they are
  // reproduced to 5 decimals by the 5 nm tables interpolated linearly and summed at 1 nm over 360-830 nm
  // (the 5 nm sum gives 0.37927, 0.36723 for F2, 1e-4 off), which is how they must have been computed.
  const auto full = IntegrationGrid::cie_1nm();
  const Row rows[] = {
      {"F2", StandardObserver::cie1964_10deg, full, 0.37925, 0.36733, 6e-6},
      {"F7", StandardObserver::cie1964_10deg, full, 0.31569, 0.32960, 6e-6},
      {"F11", StandardObserver::cie1964_10deg, full, 0.38541, 0.37123, 6e-6},
  };
  check_rows(std::begin(rows), std::end(rows));
}

TEST_CASE("D50 (2° and 10°) matches CIE 15:2004 Table T.3 to 5 decimals") {
  // T.3: D50 2° (0.34567, 0.35851), 10° (0.34773, 0.35952); the 2° pair as quoted in colour-science's
  // chromaticity_coordinates.py note ("as given in CIE 015:2004") and the Hackage Color docs
  // (Graphics.Color.Illuminant.CIE1931), the 10° pair from colour-science's CCS_ILLUMINANTS. Both are
  // reproduced by the 5 nm sum over 380-780 nm (computed 0.3456746, 0.3585103 and 0.3477296, 0.3595228); the
  // 1 nm sum gives 0.34568 and 0.34775, 0.35954, one and two units off in the 5th decimal.
  const auto abridged = IntegrationGrid::cie_5nm_abridged();
  const Row rows[] = {
      {"D50", StandardObserver::cie1931_2deg, abridged, 0.34567, 0.35851, 6e-6},
      {"D50", StandardObserver::cie1964_10deg, abridged, 0.34773, 0.35952, 6e-6},
  };
  check_rows(std::begin(rows), std::end(rows));
}
