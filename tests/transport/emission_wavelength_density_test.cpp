// The scene-emission wavelength density: each light's spectrum shape, normalised and weighted by its pick
// probability, and a flat term for a light without one shape.
#include <doctest/doctest.h>

#include <memory>
#include <vector>

#include "spectral/spectra/blackbody_spectrum.h"
#include "test_support.h"
#include "transport/lights/emission_wavelength_density.h"
#include "spectral/colorimetry/light_weighted_wavelength_density.h"
#include "transport/lights/point_light.h"

using namespace rimu;

namespace {

// A light whose spectrum varies over it (like an environment image): no single shape.
class ShapelessLight final : public Light {
 public:
  std::optional<LightSample> sample_li(const LightReference&, const SampledWavelengths&, Vec2) const override {
    return std::nullopt;
  }
  float pdf_li(const LightReference&, Vec3, const SurfaceHit*) const override { return 0.0f; }
  double total_power_w(double) const override { return 3.0; }
};

double integral_360_830(const Spectrum& s) {
  double total = 0.0;
  for (int nm = 360; nm <= 830; ++nm) total += (nm == 360 || nm == 830 ? 0.5 : 1.0) * s.value(nm);
  return total;
}

}  // namespace

TEST_CASE("emission wavelength density: Σ P_i s_i / ∫s_i over the lights, flat for a light without a shape") {
  const SpectrumPtr f11 = test::library().illuminant("F11");
  const auto warm = std::make_shared<BlackbodySpectrum>(2700.0, BlackbodySpectrum::Scale::peak_one);
  std::vector<std::unique_ptr<Light>> lights;
  lights.push_back(std::make_unique<PointLight>(Vec3{0, 1, 0}, LightSpectrum(f11, 0.01)));
  lights.push_back(std::make_unique<PointLight>(Vec3{0, 2, 0}, LightSpectrum(warm, 2.0)));
  lights.push_back(std::make_unique<ShapelessLight>());
  lights.push_back(std::make_unique<PointLight>(Vec3{0, 3, 0}, LightSpectrum(warm, 0.0)));  // black: ignored
  std::vector<const Light*> pointers;
  for (const auto& l : lights) pointers.push_back(l.get());
  const PowerLightSampler sampler(pointers, 10.0);
  REQUIRE(sampler.probability(2) > 0.0f);

  const Observer& cie1931 = test::library().observer(StandardObserver::cie1931_2deg);
  const TabulatedWavelengthDensity d = emission_wavelength_density(lights, sampler, cie1931, 0.25);
  const double i_f11 = integral_360_830(*f11), i_warm = integral_360_830(*warm);
  const TabulatedWavelengthDensity expected = light_weighted_wavelength_density(
      [&](double nm) {
        return sampler.probability(0) * f11->value(nm) / i_f11 + sampler.probability(1) * warm->value(nm) / i_warm +
               sampler.probability(2) / 470.0;
      },
      cie1931, 0.25);
  for (float nm : {380.5f, 435.5f, 487.5f, 544.5f, 611.5f, 700.5f, 820.5f}) {
    CAPTURE(nm);
    CHECK(d.pdf(nm) == doctest::Approx(expected.pdf(nm)).epsilon(1e-6));
  }
  // The F11 line at 544 nm carries more density than its neighbourhood.
  CHECK(d.pdf(544.5f) > 2.0f * d.pdf(530.5f));
}

TEST_CASE("emission wavelength density: no lights is the visible density") {
  std::vector<std::unique_ptr<Light>> none;
  const PowerLightSampler sampler(std::vector<const Light*>{}, 1.0);
  const TabulatedWavelengthDensity d =
      emission_wavelength_density(none, sampler, test::library().observer(StandardObserver::cie1931_2deg));
  CHECK(d.pdf(500.5f) == doctest::Approx(visible_wavelength_pdf(500.5f)).epsilon(1e-4));
}
