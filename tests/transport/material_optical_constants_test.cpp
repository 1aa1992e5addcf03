// Optical constants: Sellmeier indices against the glass and water datasheets, metal tables, named lookup.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/io/csv_table.h"
#include "spectral/error.h"
#include "spectral/library/optical_constants.h"
#include "test_support.h"
#include "transport/bsdfs/dielectric_bsdf.h"

using namespace rimu;

TEST_CASE("Sellmeier: n_d of N-BK7, N-SF11 and fused silica match their datasheets") {
  // n_d at the helium d line, 587.56 nm: SCHOTT datasheets N-BK7 1.51680, N-SF11 1.78472; Malitson 1965 fused
  // silica 1.45846 (data/spectra/README checks). Published to 5 decimals: ±5e-6 plus the coefficients' rounding.
  struct Row {
    const char* name;
    double n_d;
  };
  for (const Row& row : {Row{"bk7", 1.51680}, Row{"sf11", 1.78472}, Row{"fused-silica", 1.45846}}) {
    CAPTURE(row.name);
    CHECK(std::abs(dielectric_ior(test::library(), row.name)->value(587.56) - row.n_d) <= 6e-6);
  }
}

TEST_CASE("Sellmeier: glass and water indices equal the tables evaluated from the same coefficients") {
  // glass_n_from_sellmeier_5nm.csv and water_n_daimon2007_20C_5nm.csv were computed by the data curator from
  // the same coefficients (6 decimals: ±5e-7); this checks the formula, the µm units and the squared C's.
  // Water: Daimon & Masumura 2007 at 20 °C gives n(590 nm) = 1.33333 (README).
  auto& lib = test::library();
  const CsvTable& glasses = lib.table("spectra/materials/glass_n_from_sellmeier_5nm.csv");
  const struct {
    const char* name;
    const char* column;
  } columns[] = {{"bk7", "N-BK7"}, {"sf11", "N-SF11"}, {"fused-silica", "fused_silica"}};
  const auto lambda = glasses.numbers(0);
  for (const auto& c : columns) {
    const SpectrumPtr n = dielectric_ior(lib, c.name);
    const auto expected = glasses.numbers(glasses.column_index(c.column));
    for (size_t i = 0; i < lambda.size(); ++i) CHECK(std::abs(n->value(lambda[i]) - expected[i]) <= 6e-7);
  }
  const CsvTable& water_table = lib.table("spectra/materials/water_n_daimon2007_20C_5nm.csv");
  const SpectrumPtr water = dielectric_ior(lib, "water");
  const auto water_lambda = water_table.numbers(0), water_n = water_table.numbers(1);
  for (size_t i = 0; i < water_lambda.size(); ++i) CHECK(std::abs(water->value(water_lambda[i]) - water_n[i]) <= 6e-7);
  CHECK(std::abs(water->value(590.0) - 1.33333) <= 1e-5);
}

TEST_CASE("Sellmeier: the float lanes agree with the double evaluation") {
  // float has 24 bits: relative 1e-7 per operation, a few operations: 1e-6.
  const SpectrumPtr sf11 = dielectric_ior(test::library(), "sf11");
  const SampledWavelengths lambda(Float4(360.0f, 486.1f, 589.3f, 830.0f), Float4(1.0f));
  const Float4 n = sf11->sample(lambda);
  for (int lane = 0; lane < 4; ++lane) CHECK(n[lane] == doctest::Approx(sf11->value(lambda.lambda_nm(lane))).epsilon(1e-6));
  CHECK(sf11->max_value() == doctest::Approx(sf11->value(360.0)));  // normal dispersion: largest at the blue end
}

TEST_CASE("dispersion: smooth BK7 refracts at 486.1, 589.3 and 656.3 nm by Snell's law with the Sellmeier index") {
  // θt = asin(sin θi / n(λ)) (Snell). Float directions carry ~1e-7 relative error: 1e-5 rad is generous for
  // float and far below the 8e-4 rad that separates the F and C lines at this angle.
  const SpectrumPtr bk7 = dielectric_ior(test::library(), "bk7");
  const float theta_i = 0.9f;  // 51.6°
  const Vec3 wo{std::sin(theta_i), 0.0f, std::cos(theta_i)};
  const float lines[3] = {486.1f, 589.3f, 656.3f};
  for (int hero = 0; hero < 3; ++hero) {
    const SampledWavelengths lambda(Float4(lines[hero], lines[(hero + 1) % 3], lines[(hero + 2) % 3], 700.0f),
                                    Float4(1.0f));
    const DielectricBsdf glass(bk7->sample(lambda), TrowbridgeReitz(0.0f, 0.0f));
    const auto s = glass.sample(wo, 0.999f, {0.5f, 0.5f});  // u_lobe above R ≈ 0.05: refraction
    REQUIRE(s);
    REQUIRE(s->wi.z < 0.0f);
    const double n = bk7->value(lines[hero]);
    const double expected = std::asin(std::sin(double(theta_i)) / n);
    const double sin_t = std::hypot(double(s->wi.x), double(s->wi.y));
    CAPTURE(lines[hero]);
    CHECK(std::abs(std::asin(sin_t) - expected) <= 1e-5);
    CHECK(s->wi.x < 0.0f);  // the refracted ray continues across the normal
    // The partners had other indices: they could not have produced this direction.
    CHECK(s->wavelength_dependent_direction);
    for (int lane = 1; lane < 4; ++lane) {
      CHECK(s->pdf[lane] == 0.0f);
      CHECK(s->f[lane] == 0.0f);
    }
  }
}

TEST_CASE("optical constants: named lookup, and errors that list what exists") {
  auto& lib = test::library();
  for (const auto& name : conductor_names()) {
    const ComplexIorSpectra nk = conductor_ior(lib, name);
    CHECK(nk.n->value(550.0) > 0.0);
    // Every metal we ship is strongly absorbing in the visible; pbrt's metal-MgO and metal-TiO2 are oxides
    // (transparent there: k = 0 at 550 nm in pbrt's tables).
    if (name == "pbrt-mgo" || name == "pbrt-tio2") {
      CHECK(nk.k->value(550.0) == 0.0);
    } else {
      CHECK(nk.k->value(550.0) > 1.0);
    }
  }
  // Aluminium comes from McPeak et al. 2015: at 600 nm the table lists n = 0.992466, k = 6.368986.
  const ComplexIorSpectra al = conductor_ior(lib, "aluminium");
  CHECK(al.n->value(600.0) == doctest::Approx(0.992465612).epsilon(1e-9));
  CHECK(al.k->value(600.0) == doctest::Approx(6.368986418).epsilon(1e-9));
  for (const auto& name : dielectric_names()) CHECK(dielectric_ior(lib, name)->value(550.0) > 1.3);

  CHECK_THROWS_WITH_AS(conductor_ior(lib, "brass"), doctest::Contains("gold, silver, copper, aluminium"), InputError);
  CHECK_THROWS_WITH_AS(dielectric_ior(lib, "crown"), doctest::Contains("bk7, sf11, fused-silica, water"), InputError);
  CHECK_THROWS_AS(SellmeierSpectrum({{1.0, 0.25}}, "pole at 500 nm"), InputError);  // λ² = C inside 360-830 nm
}
