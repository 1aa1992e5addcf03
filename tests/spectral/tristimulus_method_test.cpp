// Tristimulus integration at the data's own interval (CIE 15:2004 §7) and by ASTM E308 weights, against
// published chromaticities, CCTs and weighting factors.
#include <doctest/doctest.h>

#include <tuple>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "spectral/colorimetry/astm_e308.h"
#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/error.h"
#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/library/tabulated_colorimetry.h"
#include "test_support.h"

using namespace rimu;

namespace {

struct PublishedXy {
  const char* name;
  double x, y;
};

Chromaticity native_xy(const std::string& name) {
  const auto table = std::dynamic_pointer_cast<const TabulatedSpectrum>(test::library().illuminant(name));
  REQUIRE(table);
  CHECK(default_tristimulus_method(*table) == TristimulusMethod::native);
  return chromaticity_of(light_xyz(*table, StandardObserver::cie1931_2deg, TristimulusMethod::native, test::library()));
}

// "Exact to the published rounding": the value rounds to the printed 4 decimals, |x − published| ≤ 5e-5.
constexpr double kHalfUnitIn4thDecimal = 5e-5;

void check_rounds_to(const PublishedXy& row) {
  CAPTURE(row.name);
  const Chromaticity xy = native_xy(row.name);
  CAPTURE(xy.x);
  CAPTURE(xy.y);
  CHECK(std::abs(xy.x - row.x) <= kHalfUnitIn4thDecimal);
  CHECK(std::abs(xy.y - row.y) <= kHalfUnitIn4thDecimal);
}

}  // namespace

TEST_CASE("F1-F12 summed at their own 5 nm round to CIE 15:2004 Table T.8 xy (4 decimals)") {
  // CIE 15:2004 Table T.8, 2° observer, as carried by colour-science
  // (colour/colorimetry/datasets/illuminants/chromaticity_coordinates.py @ 032c1074, FL1-FL12).
  const PublishedXy rows[] = {{"F1", 0.3131, 0.3371},  {"F2", 0.3721, 0.3751},  {"F3", 0.4091, 0.3941},
                              {"F4", 0.4402, 0.4031},  {"F5", 0.3138, 0.3452},  {"F6", 0.3779, 0.3882},
                              {"F7", 0.3129, 0.3292},  {"F8", 0.3458, 0.3586},  {"F9", 0.3741, 0.3727},
                              {"F10", 0.3458, 0.3588}, {"F11", 0.3805, 0.3769}, {"F12", 0.4370, 0.4042}};
  for (const PublishedXy& row : rows) check_rounds_to(row);
}

TEST_CASE("the old 1 nm interpolation misses Table T.8 for line spectra, which is why native is the default") {
  // F2 interpolated to 1 nm gives y = 0.37529 (issue measurement), two units off the published 0.3751.
  const auto f2 = std::dynamic_pointer_cast<const TabulatedSpectrum>(test::library().illuminant("F2"));
  const Chromaticity xy = chromaticity_of(
      light_xyz(*f2, StandardObserver::cie1931_2deg, TristimulusMethod::interpolate_1nm, test::library()));
  CHECK(std::abs(xy.y - 0.3751) > 1e-4);
}

TEST_CASE("HP1-HP5 and LED-B1...LED-V2 round to CIE 15:2018's published xy (4 decimals)") {
  // CIE 15:2018 Tables 10 and 12 (high-pressure and LED illuminants), as carried by colour-science
  // (chromaticity_coordinates.py @ 032c1074, which cites Carter et al., CIE 015:2018).
  const PublishedXy rows[] = {
      {"HP1", 0.5330, 0.4150},     {"HP2", 0.4778, 0.4158},     {"HP3", 0.4302, 0.4075},
      {"HP4", 0.3812, 0.3797},     {"HP5", 0.3776, 0.3713},     {"LED-B1", 0.4560, 0.4078},
      {"LED-B2", 0.4357, 0.4012},  {"LED-B3", 0.3756, 0.3723},  {"LED-B4", 0.3422, 0.3502},
      {"LED-B5", 0.3118, 0.3236},  {"LED-BH1", 0.4474, 0.4066}, {"LED-RGB1", 0.4557, 0.4211},
      {"LED-V1", 0.4548, 0.4044},  {"LED-V2", 0.3781, 0.3775}};
  for (const PublishedXy& row : rows) check_rounds_to(row);
}

TEST_CASE("CCT of HP1 and the LED illuminants rounds to CIE 15:2018's published kelvin") {
  // CIE 15:2018 Table 12 CCTs of the LED illuminants as listed in the farg crate's README (illuminant features),
  // and HP1 = 1959 K (CIE 15:2018 Table 10). The published values are integers (±0.5 K). CIE 15:2018 does not
  // say how its CCTs were computed; ours (Ohno 2013 on the 1 nm Planckian locus, from the native xy) land within
  // 0.5 K for seven of the ten and 0.53-0.56 K away for LED-B3, LED-B5 and LED-V2 (4102.46, 6597.44, 4069.47 K),
  // so the tolerance is 0.5 K of rounding plus 0.1 K for the unstated method. The 1 nm interpolation gave HP1
  // 1962 K, 3 K off.
  struct Row {
    const char* name;
    double cct_k;
  };
  const Row rows[] = {{"HP1", 1959},     {"LED-B1", 2733}, {"LED-B2", 2998},   {"LED-B3", 4103},
                      {"LED-B4", 5109},  {"LED-B5", 6598}, {"LED-BH1", 2851},  {"LED-RGB1", 2840},
                      {"LED-V1", 2724},  {"LED-V2", 4070}};
  const PlanckianLocus locus(test::library().observer(StandardObserver::cie1931_2deg));
  for (const Row& row : rows) {
    CAPTURE(row.name);
    const CctDuv cct = locus.cct_duv(uv1960_of(native_xy(row.name)));
    CAPTURE(cct.cct_k);
    CHECK(std::abs(cct.cct_k - row.cct_k) <= 0.6);
  }
}

TEST_CASE("E2022 Lagrange coefficients at a tenth of an interval") {
  // ASTM E2022-11's coefficients for 10 nm: inner interval (cubic, 4 samples) and first interval (quadratic).
  const auto inner = e308_lagrange_coefficients(4, 1.1);
  CHECK(inner[0] == doctest::Approx(-0.0285).epsilon(1e-12));
  CHECK(inner[1] == doctest::Approx(0.9405).epsilon(1e-12));
  CHECK(inner[2] == doctest::Approx(0.1045).epsilon(1e-12));
  CHECK(inner[3] == doctest::Approx(-0.0165).epsilon(1e-12));
  const auto boundary = e308_lagrange_coefficients(3, 0.1);
  CHECK(boundary[0] == doctest::Approx(0.855).epsilon(1e-12));
  CHECK(boundary[1] == doctest::Approx(0.19).epsilon(1e-12));
  CHECK(boundary[2] == doctest::Approx(-0.045).epsilon(1e-12));
}

TEST_CASE("E308 weights match published ASTM E308-15 Table 6 entries (3 decimals)") {
  // ASTM E308-15 Table 6 (weights for bandpass-corrected data, 360-830 nm) entries, as reproduced in
  // colour-science's colour/colorimetry/tests/test_tristimulus_values.py @ 03d8c5f3 (TWF_A_CIE_1964_10_10,
  // TWF_A_CIE_1964_10_20, TWF_D65_CIE_1931_2_20, stated there to match E308-15). Printed to 3 decimals: within
  // 5e-4, plus 1e-9 for our own rounding.
  struct Entry {
    const char* illuminant;
    StandardObserver observer;
    int interval;
    double nm, x, y, z;
  };
  const auto two = StandardObserver::cie1931_2deg, ten = StandardObserver::cie1964_10deg;
  const Entry entries[] = {
      {"A", ten, 10, 450, 1.080, 0.259, 5.806},   {"A", ten, 10, 560, 6.200, 8.758, 0.001},
      {"A", ten, 10, 600, 12.746, 7.468, 0.000},  {"A", ten, 10, 700, 0.166, 0.065, 0.000},
      {"A", ten, 20, 440, 1.900, 0.304, 9.755},   {"A", ten, 20, 600, 25.332, 14.896, 0.000},
      {"A", ten, 20, 380, -0.009, -0.001, -0.041}, {"D65", two, 20, 440, 6.670, 0.453, 33.637},
      {"D65", two, 20, 560, 11.301, 18.863, 0.068}, {"D65", two, 20, 620, 14.020, 6.277, 0.003},
  };
  for (const Entry& e : entries) {
    CAPTURE(e.illuminant);
    CAPTURE(e.interval);
    CAPTURE(e.nm);
    const E308WeightTable& table = test::library().e308_weights(e.illuminant, e.observer, e.interval);
    const size_t j = size_t(std::lround((e.nm - table.first_nm) / table.interval_nm));
    const Xyz w = table.weights.at(j);
    CAPTURE(w.x);
    CAPTURE(w.y);
    CAPTURE(w.z);
    CHECK(std::abs(w.x - e.x) <= 5e-4 + 1e-9);
    CHECK(std::abs(w.y - e.y) <= 5e-4 + 1e-9);
    CHECK(std::abs(w.z - e.z) <= 5e-4 + 1e-9);
  }
}

TEST_CASE("the checked-in data/e308 tables are what the generator computes from the CIE 1 nm data") {
  // Files carry 9 decimals: the regenerated values agree to 5e-10.
  for (const std::string& name : SpectralLibrary::e308_illuminant_names()) {
    for (auto observer : {StandardObserver::cie1931_2deg, StandardObserver::cie1964_10deg}) {
      for (int interval : {10, 20}) {
        CAPTURE(name);
        CAPTURE(interval);
        const E308WeightTable fresh =
            compute_e308_weights(*test::library().e308_illuminant(name), test::library().observer(observer), interval, name);
        const E308WeightTable& stored = test::library().e308_weights(name, observer, interval);
        REQUIRE(fresh.weights.size() == stored.weights.size());
        double sum_y = 0, worst = 0;
        for (size_t j = 0; j < fresh.weights.size(); ++j) {
          worst = std::max({worst, std::abs(fresh.weights[j].x - stored.weights[j].x),
                            std::abs(fresh.weights[j].y - stored.weights[j].y),
                            std::abs(fresh.weights[j].z - stored.weights[j].z)});
          sum_y += stored.weights[j].y;
        }
        CHECK(worst <= 5e-10);
        CHECK(sum_y == doctest::Approx(100.0).epsilon(1e-8));  // perfect diffuser: Y = 100
      }
    }
  }
}

TEST_CASE("E308 weights of D55, D75, F2, F7 and F11 sum to ASTM E308's published white points") {
  // The weights of one illuminant sum to its white (X, 100, Z): the Lagrange coefficients of each 1 nm point sum
  // to 1. ASTM E308-01's white points for the CIE 1931 2° observer, as collected from "the ASTM publication" in
  // the R package colorSpec (standardXYZ()) and reproduced in JuliaGraphics/Colors.jl src/cie_data.jl: D55
  // (95.682, 92.149), D75 (94.972, 122.638), F2 (99.186, 67.393), F7 (95.041, 108.747), F11 (100.962, 64.350).
  // No per-wavelength Table 6 entries of these illuminants could be found published outside the standard.
  // Printed to 3 decimals (5e-4), plus 2e-4 for the last digits of the 1 nm tables E308 summed (worst here: F7 Z,
  // 1.05e-4 past the rounding). The choices this rejects miss by more: daylight linearly interpolated to 1 nm by
  // 0.011 (D55 Z) and 0.019 (D75 Z), the F series from the CIE 15:2018 1 nm FL table by up to 0.0019 (F7 Z).
  struct White {
    const char* illuminant;
    double x, z;
  };
  const White whites[] = {{"D55", 95.682, 92.149}, {"D75", 94.972, 122.638}, {"F2", 99.186, 67.393},
                          {"F7", 95.041, 108.747}, {"F11", 100.962, 64.350}};
  for (const White& w : whites) {
    for (int interval : {10, 20}) {
      CAPTURE(w.illuminant);
      CAPTURE(interval);
      const E308WeightTable& table = test::library().e308_weights(w.illuminant, StandardObserver::cie1931_2deg, interval);
      Xyz sum;
      for (const Xyz& weight : table.weights) sum = {sum.x + weight.x, sum.y + weight.y, sum.z + weight.z};
      CAPTURE(sum.x);
      CAPTURE(sum.z);
      CHECK(sum.y == doctest::Approx(100.0).epsilon(1e-9));
      CHECK(std::abs(sum.x - w.x) <= 7e-4);
      CHECK(std::abs(sum.z - w.z) <= 7e-4);
    }
  }
}

TEST_CASE("E2022 interpolation to 1 nm keeps the samples and is exact for a cubic") {
  // Inside, the cubic through four samples reproduces any cubic; the first and last interval use the quadratic
  // through three samples, exact for a quadratic. So a cubic is exact inside and a quadratic everywhere (1e-9).
  auto sampled = [](auto f) {
    std::vector<double> l, v;
    for (int nm = 400; nm <= 450; nm += 5) {
      l.push_back(nm);
      v.push_back(f(double(nm)));
    }
    return TabulatedSpectrum(l, v, Extrapolation::zero, "test");
  };
  auto cubic = [](double nm) { const double t = (nm - 425) / 25; return 2 + t - 0.5 * t * t + 0.75 * t * t * t; };
  auto quadratic = [](double nm) { const double t = (nm - 425) / 25; return 1 + 0.3 * t - 0.8 * t * t; };
  const TabulatedSpectrum c = e308_interpolate_to_1nm(sampled(cubic));
  const TabulatedSpectrum q = e308_interpolate_to_1nm(sampled(quadratic));
  REQUIRE(c.wavelengths_nm().size() == 51);
  for (size_t i = 0; i < c.wavelengths_nm().size(); ++i) {
    const double nm = c.wavelengths_nm()[i];
    CAPTURE(nm);
    if (nm >= 405 && nm <= 445) CHECK(c.values()[i] == doctest::Approx(cubic(nm)).epsilon(1e-9));
    CHECK(q.values()[i] == doctest::Approx(quadratic(nm)).epsilon(1e-9));
  }
  const TabulatedSpectrum uneven({400, 405, 415}, {1, 2, 3}, Extrapolation::zero, "uneven.csv");
  CHECK_THROWS_WITH_AS(e308_interpolate_to_1nm(uneven), doctest::Contains("uneven.csv"), InputError);
}

TEST_CASE("D55 and D75 are CIE daylight at 5503 K and 7504 K") {
  // CIE 15:2004 Table T.3 (CIE 1931 2°): D55 (0.33242, 0.34743), D75 (0.29902, 0.31485), 5 decimals. Summed at
  // the basis' 5 nm over the CMFs' 360-830 nm, which is what reproduces them (over 380-780 nm, D75's y would be
  // 0.31488): within half a unit of the 5th decimal.
  const Observer& o = test::library().observer(StandardObserver::cie1931_2deg);
  for (auto [name, x, y] : {std::tuple{"D55", 0.33242, 0.34743}, std::tuple{"D75", 0.29902, 0.31485}}) {
    CAPTURE(name);
    const SpectrumPtr d = test::library().illuminant(name);
    Xyz sum;
    for (int nm = 360; nm <= 830; nm += 5) {
      const double s = d->value(nm);
      sum = {sum.x + s * o.x_bar.value(nm), sum.y + s * o.y_bar.value(nm), sum.z + s * o.z_bar.value(nm)};
    }
    const double total = sum.x + sum.y + sum.z;
    CHECK(std::abs(sum.x / total - x) <= 5e-6);
    CHECK(std::abs(sum.y / total - y) <= 5e-6);
  }
}

TEST_CASE("E308 range folding keeps the perfect diffuser at Y = 100 (E308-15 §7.3.2)") {
  // colour-science's TWF_D65_CIE_1931_2_20_A (D65 2° 20 nm folded to 400-700 nm): first row 0.170, 0.002, 0.785.
  const E308WeightTable& table = test::library().e308_weights("D65", StandardObserver::cie1931_2deg, 20);
  const E308WeightTable folded = fold_e308_weights(table, 400, 700);
  CHECK(folded.weights.size() == 16);
  // Those folded rows are sums of three or four 3-decimal entries, so they carry up to 4 × 5e-4 of rounding.
  CHECK(std::abs(folded.weights.front().x - 0.170) <= 2e-3);
  CHECK(std::abs(folded.weights.front().z - 0.785) <= 2e-3);
  CHECK(std::abs(folded.weights.back().x - 0.185) <= 2e-3);
  double sum_y = 0;
  for (const Xyz& w : folded.weights) sum_y += w.y;
  CHECK(sum_y == doctest::Approx(100.0).epsilon(1e-9));
}

TEST_CASE("the default method follows the data's spacing") {
  auto table = [](double first, double step, int count) {
    std::vector<double> l, v;
    for (int i = 0; i < count; ++i) {
      l.push_back(first + i * step);
      v.push_back(0.5);
    }
    return TabulatedSpectrum(l, v, Extrapolation::clamp, "test");
  };
  CHECK(default_tristimulus_method(table(380, 5, 81)) == TristimulusMethod::native);
  CHECK(default_tristimulus_method(table(360, 1, 471)) == TristimulusMethod::native);
  CHECK(default_tristimulus_method(table(380, 10, 36)) == TristimulusMethod::astm_e308);
  CHECK(default_tristimulus_method(table(380, 20, 20)) == TristimulusMethod::astm_e308);
  CHECK(default_tristimulus_method(table(400, 4, 76)) == TristimulusMethod::interpolate_1nm);
  const TabulatedSpectrum uneven({400, 410, 430, 700}, {1, 1, 1, 1}, Extrapolation::clamp, "uneven");
  CHECK(default_tristimulus_method(uneven) == TristimulusMethod::interpolate_1nm);
  CHECK(parse_tristimulus_method("astm-e308") == TristimulusMethod::astm_e308);
  CHECK_FALSE(parse_tristimulus_method("trapezoid"));
}

TEST_CASE("E308 refuses 10 nm data that start after 380 nm") {
  std::vector<double> l, v;
  for (int nm = 400; nm <= 730; nm += 10) {
    l.push_back(nm);
    v.push_back(0.5);
  }
  const TabulatedSpectrum late(l, v, Extrapolation::clamp, "late.csv");
  CHECK_THROWS_WITH_AS(
      reflectance_xyz(late, "D50", StandardObserver::cie1931_2deg, TristimulusMethod::astm_e308, test::library()),
      doctest::Contains("380 nm or below"), InputError);
}

TEST_CASE("a flat reflectance of 0.5 gives Y = 50 by every method") {
  std::vector<double> l, v;
  for (int nm = 380; nm <= 730; nm += 10) {
    l.push_back(nm);
    v.push_back(0.5);
  }
  const TabulatedSpectrum grey(l, v, Extrapolation::clamp, "grey");
  for (auto method : {TristimulusMethod::native, TristimulusMethod::interpolate_1nm, TristimulusMethod::astm_e308}) {
    CAPTURE(method_name(method));
    const Xyz xyz = reflectance_xyz(grey, "D50", StandardObserver::cie1931_2deg, method, test::library());
    const Xyz white = perfect_diffuser_xyz(grey, "D50", StandardObserver::cie1931_2deg, method, test::library());
    CHECK(xyz.y == doctest::Approx(50.0).epsilon(1e-9));
    CHECK(xyz.x == doctest::Approx(0.5 * white.x).epsilon(1e-9));
  }
}

TEST_CASE("E308 on 10 nm subsamples of 5 nm ColorChecker data stays within 0.1 dE00 of the 5 nm sum") {
  // The ColorChecker measured at 5 nm (Ohta 1997, 380-780 nm) summed natively is the reference; every other sample
  // of it (10 nm) summed with the E308 weights must land within 0.1 dE00 of it (the bound the BabelColor test
  // holds published values to), under D65 and A (2°). Measured: mean 0.017, worst 0.083 (D65) and 0.057 (A).
  // A plain 10 nm sum is as close for these smooth reflectances (mean 0.017): E308's weights matter for data
  // whose tails are folded or that are sparser, not for smooth 10 nm data in 380-780 nm.
  const CsvTable& table = test::library().table("spectra/reflectances/colorchecker_classic_ohta1997_5nm.csv");
  for (const char* illuminant : {"D65", "A"}) {
    CAPTURE(illuminant);
    double e308_sum = 0, plain_sum = 0, e308_worst = 0;
    for (size_t c = 1; c < table.column_count(); ++c) {
      const TabulatedSpectrum five = TabulatedSpectrum::from_csv(table, table.header()[c], Extrapolation::clamp);
      std::vector<double> l, v;
      for (size_t i = 0; i < five.wavelengths_nm().size(); i += 2) {
        l.push_back(five.wavelengths_nm()[i]);
        v.push_back(five.values()[i]);
      }
      const TabulatedSpectrum ten(l, v, Extrapolation::clamp, table.header()[c]);
      auto lab_by = [&](const TabulatedSpectrum& s, TristimulusMethod m) {
        return lab_of(reflectance_xyz(s, illuminant, StandardObserver::cie1931_2deg, m, test::library()),
                      perfect_diffuser_xyz(s, illuminant, StandardObserver::cie1931_2deg, m, test::library()));
      };
      const Lab reference = lab_by(five, TristimulusMethod::native);
      const double e308 = delta_e_2000(reference, lab_by(ten, TristimulusMethod::astm_e308));
      const double plain = delta_e_2000(reference, lab_by(ten, TristimulusMethod::native));
      e308_sum += e308;
      plain_sum += plain;
      e308_worst = std::max(e308_worst, e308);
    }
    const double n = double(table.column_count() - 1);
    MESSAGE(illuminant << ": mean dE00 to the 5 nm sum, E308 " << e308_sum / n << " (worst " << e308_worst
                       << "), plain 10 nm " << plain_sum / n);
    CHECK(e308_worst <= 0.1);
  }
}
