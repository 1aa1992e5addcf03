// Fresnel equations against closed-form special cases and the metal tables' published values.
#include <doctest/doctest.h>

#include <cmath>

#include "spectral/library/optical_constants.h"
#include "test_support.h"
#include "transport/bsdfs/fresnel.h"

using namespace rimu;

TEST_CASE("Fresnel: glass at normal incidence reflects ((n-1)/(n+1))^2") {
  // Born & Wolf §1.5.3: at θ = 0 both polarisations give ((n−1)/(n+1))²; 0.04 for n = 1.5. Float arithmetic of a
  // handful of operations: 1e-7 absolute.
  for (float n : {1.33f, 1.5f, 1.7847f}) {
    const float expected = ((n - 1) / (n + 1)) * ((n - 1) / (n + 1));
    CHECK(fresnel_dielectric(Float4(1.0f), Float4(n))[0] == doctest::Approx(expected).epsilon(1e-6));
    // From inside, normal incidence reflects the same (the formula is symmetric in n_i, n_t).
    CHECK(fresnel_dielectric(Float4(-1.0f), Float4(n))[0] == doctest::Approx(expected).epsilon(1e-6));
  }
  CHECK(fresnel_dielectric(1.0, 1.5) == doctest::Approx(0.04).epsilon(1e-12));
}

TEST_CASE("Fresnel: at Brewster's angle r_p vanishes and F = ((n^2-1)/(n^2+1))^2 / 2") {
  // tan θ_B = n (Born & Wolf §1.5.3); there r_s = (1 − n²)/(1 + n²), so F = r_s²/2.
  const double n = 1.5, theta_b = std::atan(n);
  const double expected = 0.5 * std::pow((n * n - 1) / (n * n + 1), 2);
  CHECK(fresnel_dielectric(std::cos(theta_b), n) == doctest::Approx(expected).epsilon(1e-12));
  CHECK(fresnel_dielectric(Float4(float(std::cos(theta_b))), Float4(float(n)))[0] == doctest::Approx(expected).epsilon(1e-5));
}

TEST_CASE("Fresnel: total internal reflection beyond the critical angle, and grazing incidence, give exactly 1") {
  const float n = 1.5f;
  const float cos_critical = std::sqrt(1.0f - 1.0f / (n * n));  // sin θc = 1/n from inside
  CHECK(fresnel_dielectric(Float4(-(cos_critical - 1e-3f)), Float4(n))[0] == 1.0f);
  CHECK(fresnel_dielectric(Float4(-0.01f), Float4(n))[0] == 1.0f);
  CHECK(fresnel_dielectric(Float4(-(cos_critical + 1e-3f)), Float4(n))[0] < 1.0f);
  CHECK(fresnel_dielectric(-(cos_critical - 1e-3), 1.5) == 1.0);
  // Grazing (cos θ = 0, from either side, any η including the index-matched η = 1) is 1 and never NaN.
  for (float eta : {1.0f, 1.5f, 0.5f}) {
    for (float c : {0.0f, -0.0f, 1e-8f, -1e-8f}) {
      const float f = fresnel_dielectric(Float4(c), Float4(eta))[0];
      CAPTURE(eta);
      CAPTURE(c);
      CHECK(std::isfinite(f));
      CHECK(f >= 0.0f);
      CHECK(f <= 1.0f);
    }
    CHECK(fresnel_dielectric(Float4(0.0f), Float4(eta))[0] == 1.0f);
  }
}

TEST_CASE("Fresnel: a conductor with k = 0 is a dielectric, on every lane and angle") {
  // Two independent code paths (complex and real arithmetic) for the same physics; float rounding: 2e-6.
  const Float4 n(1.2f, 1.5f, 2.0f, 3.0f);
  for (float c : {1.0f, 0.8f, 0.5f, 0.2f, 0.05f, 0.0f}) {
    const Float4 conductor = fresnel_conductor(Float4(c), n, Float4(0.0f));
    const Float4 dielectric = fresnel_dielectric(Float4(c), n);
    for (int lane = 0; lane < 4; ++lane) CHECK(conductor[lane] == doctest::Approx(dielectric[lane]).epsilon(2e-6));
  }
  // n = 1, k = 0 is no interface: nothing reflects except exactly at grazing, where the limit is 1 (no NaN).
  CHECK(fresnel_conductor(Float4(0.7f), Float4(1.0f), Float4(0.0f))[0] == doctest::Approx(0.0).epsilon(1e-7));
  CHECK(fresnel_conductor(Float4(0.0f), Float4(1.0f), Float4(0.0f))[0] == 1.0f);
}

TEST_CASE("Fresnel: gold at 600 nm from Johnson and Christy's n, k") {
  // data/spectra/README checks: J&C gold at 600 nm, linearly interpolated, n = 0.249, k = 3.074 (3 decimals:
  // ±5e-4). Normal-incidence reflectance ((n−1)² + k²)/((n+1)² + k²) (Born & Wolf §14.2, Eq. 22) = 0.9095.
  const ComplexIorSpectra gold = conductor_ior(test::library(), "gold");
  const double n = gold.n->value(600.0), k = gold.k->value(600.0);
  CHECK(std::abs(n - 0.249) <= 5e-4);
  CHECK(std::abs(k - 3.074) <= 5e-4);
  const double expected = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
  const SampledWavelengths lambda(Float4(600.0f), Float4(1.0f));
  const float reflectance = fresnel_conductor(Float4(1.0f), gold.n->sample(lambda), gold.k->sample(lambda))[0];
  CHECK(reflectance == doctest::Approx(expected).epsilon(1e-5));  // float lanes and 1 nm resampling of the table
  CHECK(reflectance == doctest::Approx(0.9095).epsilon(2e-4));
  // Away from normal incidence a metal's unpolarised reflectance dips slightly then rises to 1 at grazing.
  CHECK(fresnel_conductor(Float4(0.0f), Float4(float(n)), Float4(float(k)))[0] == doctest::Approx(1.0).epsilon(1e-6));
}

TEST_CASE("Fresnel: hemispherical diffuse reflectance obeys reciprocity across the interface") {
  // Light from outside (η) and from inside (1/η) are two different integrals; reciprocity of the interface for
  // diffuse flux requires 1 − F̄(1/η) = (1 − F̄(η))/η² (e.g. Judd 1942). Both are quadratures with errors < 1e-7.
  for (double eta : {1.333, 1.5, 1.8}) {
    CAPTURE(eta);
    const double outside = fresnel_diffuse_reflectance(eta), inside = fresnel_diffuse_reflectance(1.0 / eta);
    CHECK(1.0 - inside == doctest::Approx((1.0 - outside) / (eta * eta)).epsilon(1e-6));
  }
  // Egan & Hilgeman's fit for the internal diffuse reflectance (as used by Jensen et al. 2001, Eq. 7),
  // −1.440/η² + 0.710/η + 0.668 + 0.0636 η, is a curve fit, not a table: 1% agreement at η = 1.5 is its claim.
  const double fit = -1.440 / 2.25 + 0.710 / 1.5 + 0.668 + 0.0636 * 1.5;
  CHECK(fresnel_diffuse_reflectance(1.0 / 1.5) == doctest::Approx(fit).epsilon(0.01));
}
