// Robertson's (1968) CCT against the Planckian locus it tabulates, Ohno's method and CIE illuminant A.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/colorimetry/robertson_cct.h"
#include "spectral/error.h"
#include "spectral/io/csv_table.h"
#include "test_support.h"

using namespace rimu;

namespace {

const RobertsonCct& robertson() {
  static const RobertsonCct method =
      RobertsonCct::from_csv(test::library().table("cmf/robertson_1968_isotemperature_lines.csv"));
  return method;
}

const PlanckianLocus& locus_2deg() {
  static const PlanckianLocus locus(test::library().observer(StandardObserver::cie1931_2deg));
  return locus;
}

/// The locus at infinite temperature: Planck's law tends to Rayleigh-Jeans, radiance ∝ λ⁻⁴, summed like uv_at().
Uv1960 infinite_temperature_uv() {
  const Observer& o = test::library().observer(StandardObserver::cie1931_2deg);
  Xyz xyz;
  for (int nm = 360; nm <= 830; ++nm) {
    const double w = std::pow(double(nm), -4.0);
    xyz.x += w * o.x_bar.value(nm);
    xyz.y += w * o.y_bar.value(nm);
    xyz.z += w * o.z_bar.value(nm);
  }
  return uv1960_of(xyz);
}

Uv1960 locus_at_line(const IsotemperatureLine& line) {
  return line.reciprocal_temperature_per_mk > 0.0 ? locus_2deg().uv_at(1e6 / line.reciprocal_temperature_per_mk)
                                                   : infinite_temperature_uv();
}

/// The largest distance between the chord of two neighbouring lines' locus points and the locus itself (at the
/// middle reciprocal temperature): how far Robertson's interpolated locus point can fall from the true one.
double worst_sagitta() {
  double worst = 0.0;
  const auto& lines = robertson().lines();
  for (size_t i = 1; i < lines.size(); ++i) {
    const Uv1960 a = locus_at_line(lines[i - 1]), b = locus_at_line(lines[i]);
    const Uv1960 middle = locus_2deg().uv_at(
        2e6 / (lines[i - 1].reciprocal_temperature_per_mk + lines[i].reciprocal_temperature_per_mk));
    worst = std::max(worst, std::hypot(middle.u - 0.5 * (a.u + b.u), middle.v - 0.5 * (a.v + b.v)));
  }
  return worst;
}

}  // namespace

TEST_CASE("every isotemperature line of the table sits on the Planckian locus, perpendicular to it") {
  // The check that the 31 rows were carried over right (and that W&S's 0.24702 at 325 MK⁻¹ is a misprint): each
  // row's (u, v) is today's locus at its temperature (infinity for the first: the λ⁻⁴ limit). The table has 5
  // decimals (±5e-6 per coordinate, 7.1e-6 in the plane) and Robertson summed the observer at a coarser step than
  // our 1 nm, which moves (u, v) by a few 1e-6 (CIE 15: the interval matters at that level): bound 1.1e-5;
  // measured 6.9e-6. That the rows fit today's c2 = 1.438777e-2 (and not 1.4380e-2, IPTS-48's, which would move
  // them by up to 1.1e-4) shows the table used IPTS-68's 1.4388e-2.
  // Slopes, to 5 significant digits (angle rounding <= 2.5e-6 rad), against the locus normal: bound 5e-5 rad;
  // measured 2.1e-5.
  REQUIRE(robertson().lines().size() == 31);
  for (const IsotemperatureLine& line : robertson().lines()) {
    CAPTURE(line.reciprocal_temperature_per_mk);
    const Uv1960 on = locus_at_line(line);
    CHECK(std::hypot(on.u - line.uv.u, on.v - line.uv.v) < 1.1e-5);
    if (line.reciprocal_temperature_per_mk > 0.0) {
      const Uv1960 normal = locus_2deg().normal_at(1e6 / line.reciprocal_temperature_per_mk);
      CHECK(std::abs(std::atan(line.slope) - std::atan(normal.v / normal.u)) < 5e-5);
    }
  }
}

TEST_CASE("points on and off the locus: CCT within 0.1 MK⁻¹, Duv within the chord's sagitta") {
  // Built on the locus normal at T, so the exact answer is (T, Duv). Robertson interpolates linearly between lines
  // 10-25 MK⁻¹ apart, along straight isotemperature lines: measured at most 0.077 MK⁻¹ (near 8900 K) over
  // 1700-25000 K and |Duv| <= 0.02; bound 0.1 MK⁻¹, 4 K at 6500 K. Duv is measured from the chord between two
  // lines' locus points, which lies inside the curved locus by at most the largest sagitta (computed here from
  // the locus, ~1e-4 near 6100 K), plus the table's rounding (1.1e-5 as above).
  const double duv_bound = worst_sagitta() + 1.1e-5;
  CHECK(duv_bound < 1.2e-4);  // the documented figure
  for (double t_k = 1700.0; t_k <= 25000.0; t_k *= 1.01) {
    for (double duv : {-0.02, -0.005, 0.0, 0.005, 0.02}) {
      CAPTURE(t_k);
      CAPTURE(duv);
      const Uv1960 p = locus_2deg().uv_at(t_k), n = locus_2deg().normal_at(t_k);
      const CctDuv result = robertson().cct_duv({p.u + duv * n.u, p.v + duv * n.v});
      REQUIRE(result.valid());
      CHECK(std::abs(1e6 / result.cct_k - 1e6 / t_k) < 0.1);
      CHECK(std::abs(result.duv - duv) < duv_bound);
    }
  }
}

TEST_CASE("CIE illuminant A: 2848 K on c2 = 1.435e-2 is 2855.5 K, within 0.1 MK⁻¹") {
  // CIE 15:2004 §3.1 defines A as a Planckian radiator of 2848 K with c2 = 1.435e-2 m·K, i.e. 2855.5 K on today's
  // c2; its xy, summed at 1 nm (data/cmf/README.md), is (0.44757, 0.40744). 0.1 MK⁻¹ is 0.82 K at this temperature.
  const CctDuv a = robertson().cct_duv(uv1960_of(Chromaticity{0.44757, 0.40744}));
  REQUIRE(a.valid());
  CHECK(std::abs(1e6 / a.cct_k - 1e6 / (2848.0 * 1.438777e-2 / 1.435e-2)) < 0.1);
  CHECK(std::abs(a.duv) < 1.2e-4);
}

TEST_CASE("Robertson and Ohno agree within Robertson's interpolation error") {
  // D65 (0.31271, 0.32902): Ohno gives 6503.5 K within 0.011 K; Robertson within 0.1 MK⁻¹ (4.2 K here).
  const Uv1960 d65 = uv1960_of(Chromaticity{0.31271, 0.32902});
  const CctDuv ohno = locus_2deg().cct_duv(d65);
  const CctDuv rob = robertson().cct_duv(d65);
  CHECK(std::abs(1e6 / rob.cct_k - 1e6 / ohno.cct_k) < 0.1);
  CHECK(std::abs(rob.duv - ohno.duv) < 1.2e-4);
}
TEST_CASE("outside the table and non-finite input: defined answers, flagged") {
  // Warmer than 1667 K (600 MK⁻¹): the last line's temperature, below_range.
  const Uv1960 warm = locus_2deg().uv_at(1200.0);
  const CctDuv below = robertson().cct_duv(warm);
  CHECK(below.validity == CctValidity::below_range);
  CHECK(below.cct_k == doctest::Approx(1e6 / 600.0));
  CHECK(std::isfinite(below.duv));
  // Bluer than the infinite-temperature line: above_range, an infinite CCT reported as the largest double.
  const CctDuv above = robertson().cct_duv({0.17, 0.25});
  CHECK(above.validity == CctValidity::above_range);
  CHECK(std::isfinite(above.duv));
  // Far from the locus.
  const Uv1960 p = locus_2deg().uv_at(4000.0), n = locus_2deg().normal_at(4000.0);
  CHECK(robertson().cct_duv({p.u + 0.08 * n.u, p.v + 0.08 * n.v}).validity == CctValidity::far_from_locus);
  // NaN and infinity.
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (Uv1960 bad : {Uv1960{nan, 0.3}, Uv1960{0.2, inf}}) {
    const CctDuv r = robertson().cct_duv(bad);
    CHECK(r.validity == CctValidity::far_from_locus);
    CHECK(r.cct_k == 0.0);
  }
}

TEST_CASE("a malformed isotemperature table is refused by name") {
  const CsvTable not_increasing = CsvTable::parse(
      "reciprocal_temperature_per_mk,u,v,slope\n0,0.18006,0.26352,-0.24341\n0,0.18066,0.26589,-0.25479\n",
      "lines.csv");
  CHECK_THROWS_WITH_AS(RobertsonCct::from_csv(not_increasing), doctest::Contains("lines.csv:3"), InputError);
  const CsvTable one_line =
      CsvTable::parse("reciprocal_temperature_per_mk,u,v,slope\n0,0.18006,0.26352,-0.24341\n", "one.csv");
  CHECK_THROWS_AS(RobertsonCct::from_csv(one_line), InputError);
}
