// The TM-30 colour vector graphic's normalised coordinates: the reference on the unit circle, the test vertices
// offset by exactly the hue-bin shifts the fidelity report prints.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "spectral/colour_rendering/colour_vector_graphic.h"
#include "spectral/error.h"
#include "test_support.h"

using namespace rimu;

namespace colour_vector_graphic_test {

const ColourFidelityEvaluator& evaluator() {
  static const ColourFidelityEvaluator e(test::library());
  return e;
}

double bisector_rad(int j) { return (j + 0.5) * 2.0 * std::numbers::pi / kTm30HueBins; }

TEST_CASE("the graphic of a source rated against itself lies on the unit circle") {
  // CIE A is a Planckian radiator, and below 4000 K its reference is the Planckian at its own CCT: R_g = 100 and
  // every shift is 0, so both polygons are the unit circle's vertices. The test vertices stay off it only by the
  // CCT search's residual (Ohno 2013), measured 6e-6 of the reference chroma for A: 1e-4 leaves room and still fails a real shift.
  const ColourFidelity cf = evaluator().evaluate(*test::library().illuminant("A"));
  REQUIRE(cf.rg == doctest::Approx(100.0).epsilon(1e-3));
  const auto bins = colour_vector_graphic_bins(cf);
  for (int j = 0; j < kTm30HueBins; ++j) {
    CAPTURE(j + 1);
    const CvgBin& b = bins[size_t(j)];
    CHECK(std::hypot(b.reference_x, b.reference_y) == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(std::hypot(b.test_x, b.test_y) == doctest::Approx(1.0).epsilon(1e-4));
    CHECK(std::abs(b.test_x - b.reference_x) <= 1e-4);
    CHECK(std::abs(b.test_y - b.reference_y) <= 1e-4);
    // Bins are numbered from hue 0° counter-clockwise: bin j's reference hue lies in its own 22.5° sector.
    double hue = std::atan2(b.reference_y, b.reference_x);
    if (hue < 0) hue += 2.0 * std::numbers::pi;
    CHECK(std::abs(hue - bisector_rad(j)) <= std::numbers::pi / kTm30HueBins);
  }
}

TEST_CASE("the graphic's test vertices are offset from the reference by the reported chroma and hue shifts") {
  // R_cs,hj and R_hs,hj are (Δa', Δb') / C_r,hj along and across the bin's bisecting hue; the graphic plots
  // reference/C_r + (Δa', Δb')/C_r, so projecting its offset gives them back (to rounding, 1e-12). CIE F2 has
  // shifts of up to 25 %, so a graphic that plotted anything else would fail here.
  const ColourFidelity cf = evaluator().evaluate(*test::library().illuminant("F2"));
  const auto bins = colour_vector_graphic_bins(cf);
  for (int j = 0; j < kTm30HueBins; ++j) {
    CAPTURE(j + 1);
    const CvgBin& b = bins[size_t(j)];
    const HueBin& h = cf.bins[size_t(j)];
    const double dx = b.test_x - b.reference_x, dy = b.test_y - b.reference_y, angle = bisector_rad(j);
    CHECK(dx * std::cos(angle) + dy * std::sin(angle) == doctest::Approx(h.chroma_shift).epsilon(1e-12).scale(1));
    CHECK(-dx * std::sin(angle) + dy * std::cos(angle) == doctest::Approx(h.hue_shift).epsilon(1e-12).scale(1));
    // Scaled back by the reference chroma, the vertices are the bin averages the JSON reports.
    const double chroma = std::hypot(h.reference_a, h.reference_b);
    CHECK(b.test_x * chroma == doctest::Approx(h.test_a).epsilon(1e-12).scale(1));
    CHECK(b.test_y * chroma == doctest::Approx(h.test_b).epsilon(1e-12).scale(1));
  }
}

TEST_CASE("the graphic refuses a destination in a missing folder and writes nothing") {
  const ColourFidelity cf = evaluator().evaluate(*test::library().illuminant("F2"));
  const std::filesystem::path png = std::filesystem::temp_directory_path() / "rimu-no-such-folder" / "cvg.png";
  CHECK_THROWS_AS(write_colour_vector_graphic(cf, "CIE F2", png), InputError);
  CHECK_FALSE(std::filesystem::exists(png.parent_path()));
}

}  // namespace colour_vector_graphic_test
