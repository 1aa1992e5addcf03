// Cost of the spectral basics: per-sample evaluation (the render loop) and per-spectrum colorimetry (setup).
//
// Inputs cycle through a precomputed set (random wavelengths, several patches/illuminants) so nothing is
// constant-folded; results go through benchmark::DoNotOptimize. Build Release and run
//   build/bin/rimu-spectral-bench
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "spectral/colorimetry/colorimetry.h"
#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/wavelengths/sampled_wavelengths.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "spectral/wavelengths/wavelength_density.h"
#include "spectral/colorimetry/light_weighted_wavelength_density.h"

namespace {

using namespace rimu;

SpectralLibrary& library() {
  static SpectralLibrary instance = SpectralLibrary::at_default_location();
  return instance;
}

// 4096 random hero-wavelength sets (a power of two, so the index wraps with a mask).
const std::vector<SampledWavelengths>& wavelength_sets() {
  static const std::vector<SampledWavelengths> sets = [] {
    std::mt19937 rng(1);
    std::vector<SampledWavelengths> s;
    for (int i = 0; i < 4096; ++i) s.push_back(SampledWavelengths::sample_visible(float(rng() >> 8) * 0x1p-24f));
    return s;
  }();
  return sets;
}

// One 4-lane sample() of a tabulated spectrum, given the spectrum.
void sample_spectrum(benchmark::State& state, const TabulatedSpectrum& spectrum) {
  const auto& sets = wavelength_sets();
  size_t i = 0;
  for (auto _ : state) {
    SampledSpectrum v = spectrum.sample(sets[i++ & 4095]);
    benchmark::DoNotOptimize(v);
  }
  state.SetItemsProcessed(state.iterations());
}

// Knots on whole nm (CIE 1931 ȳ, 1 nm): indexes the dense 1 nm copy.
void BM_TabulatedSample_Dense(benchmark::State& state) {
  sample_spectrum(state, library().observer(StandardObserver::cie1931_2deg).y_bar);
}
BENCHMARK(BM_TabulatedSample_Dense);

// Non-integer knots (pbrt's gold k on an even-energy grid, 57 knots): a binary search per lane.
void BM_TabulatedSample_Search(benchmark::State& state) {
  static const TabulatedSpectrum k = TabulatedSpectrum::from_csv(
      library().table("spectra/materials/pbrt_metal_au_nk.csv"), "k", Extrapolation::clamp);
  sample_spectrum(state, k);
}
BENCHMARK(BM_TabulatedSample_Search);

// All three CMFs of an observer at once (what a camera/film splat does per sample).
void BM_ObserverSample(benchmark::State& state) {
  const Observer& observer = library().observer(StandardObserver::cie1931_2deg);
  const auto& sets = wavelength_sets();
  size_t i = 0;
  for (auto _ : state) {
    Response4 r = observer.sample(sets[i++ & 4095]);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ObserverSample);

// Hero + three partners with their pdfs from one uniform number.
void BM_SampleVisible(benchmark::State& state) {
  float u = 0.0f;
  for (auto _ : state) {
    SampledWavelengths w = SampledWavelengths::sample_visible(u);
    benchmark::DoNotOptimize(w);
    u += 0.6180339887f;  // golden-ratio sequence: a different u every iteration, always in [0, 1)
    if (u >= 1.0f) u -= 1.0f;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleVisible);

// The same from the emission density of an F11-lit scene (spectral/wavelengths/wavelength_density.h): guide table + scan.
void BM_SampleLightsDensity(benchmark::State& state) {
  static const TabulatedWavelengthDensity density = [] {
    const SpectrumPtr f11 = library().illuminant("F11");
    return light_weighted_wavelength_density([&](double nm) { return f11->value(nm); },
                                             library().observer(StandardObserver::cie1931_2deg), 0.25);
  }();
  float u = 0.0f;
  for (auto _ : state) {
    SampledWavelengths w = density.sample_wavelengths(u);
    benchmark::DoNotOptimize(w);
    u += 0.6180339887f;
    if (u >= 1.0f) u -= 1.0f;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SampleLightsDensity);

// A ColorChecker patch under D65, 1 nm over 360-830 nm (CIE 15 recommended practice), cycling the 24 patches.
void BM_ReflectanceXyz_1nm(benchmark::State& state) {
  const Observer& observer = library().observer(StandardObserver::cie1931_2deg);
  const auto d65 = library().illuminant("D65");
  std::vector<SpectrumPtr> patches;
  for (const auto& name : library().colorchecker_patch_names()) patches.push_back(library().colorchecker_patch(name));
  size_t i = 0;
  for (auto _ : state) {
    Xyz xyz = reflectance_xyz(*patches[i++ % patches.size()], *d65, observer, IntegrationGrid::cie_1nm());
    benchmark::DoNotOptimize(xyz);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ReflectanceXyz_1nm);

// Relative XYZ of an illuminant, 1 nm over 360-830 nm, cycling A, D65, D50, F2, F11, LED-B3.
void BM_IlluminantXyz_1nm(benchmark::State& state) {
  const Observer& observer = library().observer(StandardObserver::cie1931_2deg);
  std::vector<SpectrumPtr> illuminants;
  for (const char* name : {"A", "D65", "D50", "F2", "F11", "LED-B3"}) illuminants.push_back(library().illuminant(name));
  size_t i = 0;
  for (auto _ : state) {
    Xyz xyz = illuminant_xyz(*illuminants[i++ % illuminants.size()], observer, IntegrationGrid::cie_1nm());
    benchmark::DoNotOptimize(xyz);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_IlluminantXyz_1nm);

// CCT and Duv of a chromaticity with a prebuilt locus (Ohno 2013), cycling points near the locus 1500-20000 K.
void BM_CctDuv(benchmark::State& state) {
  const PlanckianLocus locus(library().observer(StandardObserver::cie1931_2deg));
  std::vector<Uv1960> points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> cct(1500.0, 20000.0), duv(-0.02, 0.02);
  for (int i = 0; i < 64; ++i) {
    const double t = cct(rng), d = duv(rng);
    const Uv1960 on = locus.uv_at(t), normal = locus.normal_at(t);
    points.push_back({on.u + d * normal.u, on.v + d * normal.v});
  }
  size_t i = 0;
  for (auto _ : state) {
    CctDuv result = locus.cct_duv(points[i++ & 63]);
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CctDuv);

// Building the locus table for one observer (done once per observer at setup).
void BM_PlanckianLocusConstruction(benchmark::State& state) {
  const Observer& observer = library().observer(StandardObserver::cie1931_2deg);
  for (auto _ : state) {
    PlanckianLocus locus(observer);
    benchmark::DoNotOptimize(locus);
  }
}
BENCHMARK(BM_PlanckianLocusConstruction)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
