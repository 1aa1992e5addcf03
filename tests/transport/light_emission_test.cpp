// Emission sampling (Light::sample_emission), which light tracing starts from (transport/integrators/
// caustic_light_tracer.h): the weights' mean is each light's spectral power Φ(λ) (a point light's 4πI, a spot's
// 2π(1 − (cos θi + cos θo)/2) I, a Lambertian emitter's πAL per side, a luminaire's ∫I dω), and the power falls in the
// right directions: half a point light's above its equator, 3/4 of a Lambertian emitter's within 60° of its normal,
// the spot's inner cone its share. Means within 5 standard errors (2e5 samples; a deviation of 5σ has probability
// 6e-7); where every weight is the same (the light's power does not depend on the sample), they must be exact to
// float rounding.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "spectral/spectra/spectrum.h"
#include "transport/lights/area_light.h"
#include "transport/lights/candela_distribution.h"
#include "transport/lights/goniometric_light.h"
#include "transport/lights/point_light.h"
#include "transport/lights/sphere_light.h"
#include "transport/lights/spot_light.h"
#include "transport/sampling/sampler.h"

namespace rimu {
namespace {

constexpr double kPiDouble = std::numbers::pi;

LightSpectrum flat(double value) { return LightSpectrum(std::make_shared<ConstantSpectrum>(1.0), value); }

struct PowerCheck {
  double total = 0.0, total_se = 0.0;   // mean weight (lane 0) and its standard error
  double share = 0.0, share_se = 0.0;   // mean weight · 1[in region] / total
  double support = 0.0, support_se = 0.0;  // mean 1/p_ω: the solid angle the directions are drawn over
};

// The mean weight (lane 0 at 550 nm) and the share of it whose direction satisfies `in_region`.
PowerCheck emitted_power(const Light& light, const std::function<bool(const EmissionSample&)>& in_region) {
  const SampledWavelengths lambda(Float4(550.0f, 450.0f, 650.0f, 500.0f), Float4(1.0f / 470.0f));
  IndependentSampler sampler(17);
  const int n = 200000;
  double sum = 0, sum2 = 0, in = 0, in2 = 0, support = 0, support2 = 0;
  for (int i = 0; i < n; ++i) {
    sampler.start_pixel_sample(i, 0, 0);
    const float u_part = sampler.next_1d();
    const Vec2 u_position = sampler.next_2d(), u_direction = sampler.next_2d();
    const auto s = light.sample_emission(u_part, u_position, u_direction, lambda);
    if (!s) continue;
    REQUIRE(std::fabs(length(s->direction) - 1.0f) < 1e-5f);
    const double w = s->weight[0];
    REQUIRE(std::isfinite(w));
    REQUIRE(w >= 0.0);
    sum += w;
    sum2 += w * w;
    // The densities the sample reports are the ones emission_density gives for its ray (the bidirectional
    // integrator's MIS weights read both).
    const EmissionDensity d = light.emission_density(s->normal, s->direction);
    REQUIRE(d.position == doctest::Approx(s->pdf_position).epsilon(1e-5));
    REQUIRE(d.direction == doctest::Approx(s->pdf_direction).epsilon(1e-4));
    REQUIRE(s->pdf_direction > 0.0f);
    const double inverse = 1.0 / double(s->pdf_direction);
    support += inverse;
    support2 += inverse * inverse;
    if (in_region(*s)) {
      in += w;
      in2 += w * w;
    }
  }
  PowerCheck c;
  c.total = sum / n;
  c.total_se = std::sqrt(std::max(0.0, sum2 / n - c.total * c.total) / n);
  const double in_mean = in / n;
  c.share = in_mean / c.total;
  c.share_se = std::sqrt(std::max(0.0, in2 / n - in_mean * in_mean) / n) / c.total;
  c.support = support / n;
  c.support_se = std::sqrt(std::max(0.0, support2 / n - c.support * c.support) / n);
  return c;
}

// E[1/p_ω] over the drawn directions is the solid angle they are drawn over, if p_ω is their density.
void check_support(const PowerCheck& c, double solid_angle) {
  CAPTURE(c.support);
  CAPTURE(solid_angle);
  CHECK(std::fabs(c.support - solid_angle) <= 5.0 * c.support_se + 1e-5 * solid_angle);
}

void check_power(const PowerCheck& c, double power, double share) {
  CAPTURE(c.total);
  CAPTURE(power);
  CAPTURE(c.share);
  CAPTURE(share);
  CHECK(std::fabs(c.total - power) <= 5.0 * c.total_se + 1e-5 * power);
  CHECK(std::fabs(c.share - share) <= 5.0 * c.share_se + 1e-4);
}

}  // namespace

TEST_CASE("Emission sampling: each light's weights average to its power, spread as it emits") {
  SUBCASE("point light: 4πI, half above the equator") {
    const PointLight light({1, 2, 3}, flat(2.0));
    CHECK(light.samples_emission());
    const PowerCheck c = emitted_power(light, [](const EmissionSample& s) { return s.direction.z > 0.0f; });
    check_power(c, 4 * kPiDouble * 2.0, 0.5);
    check_support(c, 4 * kPiDouble);
  }
  SUBCASE("spot light: 2π(1 − (cos θi + cos θo)/2) I, the inner cone its share") {
    const double inner = 20.0, outer = 35.0, ci = std::cos(inner * kPiDouble / 180), co = std::cos(outer * kPiDouble / 180);
    const Vec3 axis = normalize(Vec3{1, -1, 0});
    const SpotLight light({0, 0, 0}, axis, inner, outer, flat(3.0));
    const double power = 2 * kPiDouble * (1 - 0.5 * (ci + co)) * 3.0;
    const PowerCheck c = emitted_power(light, [&](const EmissionSample& s) { return dot(s.direction, axis) >= float(ci); });
    check_power(c, power, 2 * kPiDouble * (1 - ci) * 3.0 / power);
    check_support(c, 2 * kPiDouble * (1 - co));
  }
  SUBCASE("sphere light: π·4πr²·L, 3/4 within 60° of the normal (one and two sides)") {
    for (const bool two_sided : {false, true}) {
      CAPTURE(two_sided);
      const SphereLight light({0.5f, 0, 0}, 0.2f, flat(1.5), two_sided);
      const double power = (two_sided ? 2 : 1) * kPiDouble * 4 * kPiDouble * 0.04 * 1.5;
      check_power(emitted_power(light, [](const EmissionSample& s) { return dot(s.direction, s.normal) >= 0.5f; }),
                  power, 0.75);
    }
  }
  SUBCASE("area light: πAL per side over two triangles of unequal area, 3/4 within 60° of the normal") {
    const std::vector<Vec3> vertices = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 3, 0}};
    const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};  // areas 1 and 3, normal +z
    for (const bool two_sided : {false, true}) {
      CAPTURE(two_sided);
      const AreaLight light(vertices, indices, flat(0.5), two_sided);
      CHECK(light.samples_emission());
      const double power = (two_sided ? 2 : 1) * kPiDouble * 4.0 * 0.5;
      check_power(emitted_power(light, [](const EmissionSample& s) { return dot(s.direction, s.normal) >= 0.5f; }),
                  power, 0.75);
      // The points cover the triangles by area: a quarter on the first (x > y/... : the triangle (0,0),(2,0),(2,1)).
      const auto on_first = emitted_power(light, [](const EmissionSample& s) { return 2.0f * s.origin_m.y < s.origin_m.x; });
      CHECK(std::fabs(on_first.share - 0.25) <= 5.0 * on_first.share_se);
    }
  }
  SUBCASE("goniometric light: ∫I dω, the table's share below its equator") {
    // 1 cd from γ = 0 to 90° (the axis −y side), 0.25 beyond, one C plane.
    const GoniometricLight light({0, 3, 0}, Vec3{0, -1, 0}, Vec3{1, 0, 0}, flat(1.0),
                                 std::make_shared<CandelaDistribution>(std::vector<double>{0, 90, 91, 180},
                                                                       std::vector<double>{0, 360},
                                                                       std::vector<double>{1, 1, 0.25, 0.25, 1, 1, 0.25, 0.25}));
    CHECK(light.samples_emission());
    const double power = light.total_power_w(1.0) / 470.0;  // flat(1) over 360-830 nm: ∫I dω per nm
    const auto c = emitted_power(light, [](const EmissionSample& s) { return s.direction.y < 0.0f; });
    const CandelaDistribution table({0, 90, 91, 180}, {0, 360}, {1, 1, 0.25, 0.25, 1, 1, 0.25, 0.25});
    check_power(c, power, 2 * kPiDouble * 1.0 / table.integral_sr());
  }
}

}  // namespace rimu
