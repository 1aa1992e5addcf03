// Luminous efficacy of radiation and radiometric <-> photometric conversions.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/error.h"
#include "spectral/photometry/photometry.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "test_support.h"

using namespace rimu;

namespace {

// A line at `centre_nm` (a whole nm): a triangle one sample wide on each side. On a 1 nm grid the rectangle
// rule sees only the centre sample, so Σ S Δλ = 1 and Σ S V Δλ = V(centre): a delta integrated exactly.
TabulatedSpectrum line_at(double centre_nm) {
  return TabulatedSpectrum({centre_nm - 1.0, centre_nm, centre_nm + 1.0}, {0.0, 1.0, 0.0}, Extrapolation::zero,
                           "line at " + std::to_string(centre_nm) + " nm");
}

// `shape` scaled by `factor`, to turn a relative spectral shape into an absolute spectral quantity.
class ScaledSpectrum final : public Spectrum {
 public:
  ScaledSpectrum(const Spectrum& shape, double factor) : shape_(shape), factor_(factor) {}
  double value(double lambda_nm) const override { return factor_ * shape_.value(lambda_nm); }
  double max_value() const override { return factor_ * shape_.max_value(); }
  std::string describe() const override { return "scaled " + shape_.describe(); }

 private:
  const Spectrum& shape_;
  double factor_;
};

}  // namespace

TEST_CASE("a monochromatic 555 nm source has the maximum luminous efficacy, 683 lm/W") {
  // V(555) = 1 exactly in the CIE 1924 table (CIE 15:2004 Table T.4, ȳ column), and K_m = 683 lm/W, so the
  // only error is the division Σ S V / Σ S of two exactly representable sums: 1e-12 is generous.
  const auto k = luminous_efficacy_of_radiation_lm_W(line_at(555.0), test::library().photopic_v());
  CHECK(k.lm_W == doctest::Approx(683.0).epsilon(1e-12));
  // A line away from the peak is weighted by V there: V(600) = 0.631 (same table).
  const auto k600 = luminous_efficacy_of_radiation_lm_W(line_at(600.0), test::library().photopic_v());
  CHECK(k600.lm_W == doctest::Approx(683.0 * test::library().photopic_v().value(600.0)).epsilon(1e-12));
  CHECK(k600.lm_W == doctest::Approx(683.0 * 0.631).epsilon(1e-12));
}

TEST_CASE("luminous efficacy of radiation of CIE illuminants A, D65 and E over 360-830 nm at 1 nm") {
  // Reference values: data/README.md "Checks" (683 Σ V S / Σ S from the CIE 1 nm tables, 360-830 nm), published
  // to 2 decimals, so a correct computation lies within half a unit of the 2nd decimal (0.005 lm/W).
  // (A evaluates to 122.66502, 0.00498 from its rounded value: the bound is tight but honest.)
  // The range matters: over the tables' full 300-830 nm, A is 122.31 and D65 176.67 lm/W (ultraviolet
  // power counts in Σ S but not in Σ S V), which the last rows check.
  struct Row {
    const char* illuminant;
    IntegrationGrid grid;
    double efficacy_lm_W;
  };
  const IntegrationGrid full_table{300.0, 830.0, 1.0};
  const Row rows[] = {
      {"A", IntegrationGrid::cie_1nm(), 122.67},  {"D65", IntegrationGrid::cie_1nm(), 184.17},
      {"E", IntegrationGrid::cie_1nm(), 154.95},  {"A", full_table, 122.31},
      {"D65", full_table, 176.67},
  };
  for (const Row& row : rows) {
    CAPTURE(row.illuminant);
    CAPTURE(row.grid.start_nm);
    const auto k = luminous_efficacy_of_radiation_lm_W(*test::library().illuminant(row.illuminant),
                                                       test::library().photopic_v(), row.grid);
    CHECK(std::abs(k.lm_W - row.efficacy_lm_W) <= 0.005);
  }
  // E is flat, so its efficacy is K_m Σ ȳ / 471 nm = 683 · 106.856917 / 471 (colorimetry_test's Σ ȳ, whose
  // 9 significant figures bound the relative error to 1e-8).
  const auto k_e = luminous_efficacy_of_radiation_lm_W(*test::library().illuminant("E"), test::library().photopic_v());
  CHECK(k_e.lm_W == doctest::Approx(683.0 * 106.856917 / 471.0).epsilon(1e-8));
}

TEST_CASE("scotopic: a 507 nm line has efficacy K'_m V'(507) = 1700 lm/W") {
  // V'(507) = 1.000 in the CIE 1951 table (CIE 15:2004; data/cmf/cie1951_scotopic_vprime_1nm.csv, 3 decimals)
  // and K'_m = 1700 lm/W. The table's values are exact as stored, so only division rounding remains.
  const auto& v_prime = test::library().scotopic_v_prime();
  CHECK(scotopic_luminous_efficacy_lm_W(line_at(507.0), v_prime).lm_W == doctest::Approx(1700.0).epsilon(1e-12));
  // At 555 nm the rods see V'(555) = 0.402 of their peak: 683.4 scotopic lm/W, about the photopic peak.
  CHECK(scotopic_luminous_efficacy_lm_W(line_at(555.0), v_prime).lm_W ==
        doctest::Approx(1700.0 * 0.402).epsilon(1e-12));
}

TEST_CASE("efficacy is refused for spectra with no radiant or no visible power") {
  const auto& v = test::library().photopic_v();
  // Nothing at all on the grid.
  CHECK_THROWS_AS(luminous_efficacy_of_radiation_lm_W(ConstantSpectrum(0.0), v), InputError);
  // Power only beyond 830 nm: Σ S > 0 on a grid that reaches it, but V is zero there (zero extrapolation).
  const TabulatedSpectrum infrared({850.0, 900.0}, {1.0, 1.0}, Extrapolation::zero, "infrared");
  CHECK_THROWS_AS(luminous_efficacy_of_radiation_lm_W(infrared, v, IntegrationGrid{300.0, 1000.0, 1.0}), InputError);
  // Power only at 360-370 nm: V' is tabulated from 380 nm, so the rods see nothing.
  const TabulatedSpectrum ultraviolet({360.0, 370.0}, {1.0, 1.0}, Extrapolation::zero, "ultraviolet");
  try {
    (void)scotopic_luminous_efficacy_lm_W(ultraviolet, test::library().scotopic_v_prime());
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("ultraviolet") != std::string::npos);
  }
}

TEST_CASE("conversions through the efficacy agree with direct integration and round-trip") {
  // Scale the D65 shape to a radiant power of 10 W over 360-830 nm: S = 10 W · D65(λ) / Σ D65 Δλ (per nm).
  // Its luminous power is then K_m Σ S ȳ Δλ = emission_xyz's Y (ȳ of CIE 1931 2° equals V(λ); data/README.md).
  // Both sides are the same sums in a different order: agreement to 1e-12 relative.
  const auto& v = test::library().photopic_v();
  const Observer& observer = test::library().observer(StandardObserver::cie1931_2deg);
  const auto d65 = test::library().illuminant("D65");
  const double shape_integral = integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) { return d65->value(l); });
  const double radiant_power_w = 10.0;
  const ScaledSpectrum source(*d65, radiant_power_w / shape_integral);
  const double direct_lm = emission_xyz(source, observer).y;

  const LuminousEfficacy k = luminous_efficacy_of_radiation_lm_W(*d65, v);
  const LuminousPower luminous = to_luminous(RadiantPower(radiant_power_w), k);
  CHECK(luminous.lm == doctest::Approx(direct_lm).epsilon(1e-12));
  // The efficacy does not depend on the scale of the spectrum.
  CHECK(luminous_efficacy_of_radiation_lm_W(source, v).lm_W == doctest::Approx(k.lm_W).epsilon(1e-12));

  SUBCASE("round trips lm <-> W, cd <-> W/sr, lx <-> W/m², nt <-> W/(m²·sr)") {
    // Multiplying and dividing by the same double: at most 2 roundings, 1e-15 relative.
    for (const double x : {1e-6, 0.5, 10.0, 1.0e5}) {
      CAPTURE(x);
      CHECK(to_radiant(to_luminous(RadiantPower(x), k), k).w == doctest::Approx(x).epsilon(1e-15));
      CHECK(to_luminous(to_radiant(LuminousPower(x), k), k).lm == doctest::Approx(x).epsilon(1e-15));
      CHECK(to_radiant(to_luminous(Irradiance(x), k), k).w_m2 == doctest::Approx(x).epsilon(1e-15));
      CHECK(to_luminous(to_radiant(Illuminance(x), k), k).lx == doctest::Approx(x).epsilon(1e-15));
      CHECK(to_radiant(to_luminous(RadiantIntensity(x), k), k).w_sr == doctest::Approx(x).epsilon(1e-15));
      CHECK(to_luminous(to_radiant(LuminousIntensity(x), k), k).cd == doctest::Approx(x).epsilon(1e-15));
      CHECK(to_radiant(to_luminous(Radiance(x), k), k).w_m2_sr == doctest::Approx(x).epsilon(1e-15));
      CHECK(to_luminous(to_radiant(Luminance(x), k), k).nt == doctest::Approx(x).epsilon(1e-15));
    }
  }

  SUBCASE("1000 lx of D65 is 1000/184.17 W/m² of irradiance") {
    // E_e = E_v / K with K from the table above (data/README.md "Checks"); 0.005 lm/W of rounding in 184.17
    // is 2.7e-5 relative.
    CHECK(to_radiant(Illuminance(1000.0), k).w_m2 == doctest::Approx(1000.0 / 184.17).epsilon(3e-5));
  }
}
