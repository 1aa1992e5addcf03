// Accuracy against speed of the RGB → spectrum upsampler (issue 3). A plain main() that prints a table: it
// reports round-trip accuracy as well as time, which Google Benchmark's counters do not fit.
//
//   build/bin/rimu-upsampler-bench        (Release build; RIMU_DATA if not run from the build tree)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "spectral/cielab.h"
#include "spectral/colorimetry.h"
#include "spectral/delta_e.h"
#include "spectral/rgb_upsampler.h"
#include "spectral/smoothest_spectrum.h"

using namespace rimu;

namespace {

struct Stats {
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  void print(const char* label) {
    if (values.empty()) return (void)std::printf("    %-34s (none)\n", label);
    std::sort(values.begin(), values.end());
    double sum = 0;
    for (double v : values) sum += v;
    std::printf("    %-34s n %6zu  mean %.2e  p99 %.2e  max %.2e\n", label, values.size(), sum / values.size(),
                values[size_t(0.99 * (values.size() - 1))], values.back());
  }
};

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double delta_e_xyz(const Xyz& a, const Xyz& b, const Xyz& white) {
  return delta_e_2000(lab_of(a, white), lab_of(b, white));
}

}  // namespace

int main() {
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const Observer& observer = library.observer(StandardObserver::cie1931_2deg);
  constexpr int kSteps = 33;
  for (const char* name : {"srgb-linear", "acescg", "rec2020"}) {
    const double setup_start = now_s();
    const RgbUpsampler up(library, RgbColourSpace::named(name));
    const double setup_s = now_s() - setup_start;
    Stats unmapped, unmapped_cie, mapped, rough;
    int in_unit_range = 0, total = 0;
    const Xyz white = up.colorimetry().white_xyz();
    const double start = now_s();
    std::vector<UpsampledReflectance> results;
    results.reserve(kSteps * kSteps * kSteps);
    for (int r = 0; r < kSteps; ++r)
      for (int g = 0; g < kSteps; ++g)
        for (int b = 0; b < kSteps; ++b)
          results.push_back(up.upsample_reflectance({r / 32.0, g / 32.0, b / 32.0}));
    const double per_setup_ns = (now_s() - start) / results.size() * 1e9;
    for (int r = 0, n = 0; r < kSteps; ++r)
      for (int g = 0; g < kSteps; ++g)
        for (int b = 0; b < kSteps; ++b, ++n) {
          const UpsampledReflectance& u = results[n];
          ++total;
          if (u.gamut_mapped) {
            mapped.add(u.delta_e2000);
            continue;
          }
          ++in_unit_range;
          unmapped.add(u.delta_e2000);
          rough.add(roughness(u.spectrum.samples().knots()));
          // Independent path: CIE 15 1 nm sum under the illuminant's own table (colorimetry.h), subsampled 1:7.
          if (n % 7 == 0) {
            const Xyz in = up.space().to_xyz({r / 32.0, g / 32.0, b / 32.0});
            const Xyz cie = reflectance_xyz(u.spectrum, *up.illuminant(), observer);
            unmapped_cie.add(delta_e_xyz(in, {cie.x / 100, cie.y / 100, cie.z / 100}, white));
          }
        }
    std::printf("%s (33^3 = %d colours; table %s)\n", name, total, up.table().white_name.c_str());
    std::printf("  share needing no gamut mapping (smooth spectrum within [0,1]): %.1f %%\n", 100.0 * in_unit_range / total);
    std::printf("  round-trip CIEDE2000, RGB -> spectrum -> XYZ under the space's white -> RGB:\n");
    unmapped.print("not mapped (knot colorimetry)");
    unmapped_cie.print("not mapped (CIE table illuminant)");
    mapped.print("gamut-mapped (distance moved)");
    std::printf("  smoothness, sum (S[i+1]-S[i])^2 over 5 nm knots, not mapped:\n");
    rough.print("roughness");
    std::printf("  setup: construct upsampler %.1f ms; one RGB -> spectrum %.0f ns\n", setup_s * 1e3, per_setup_ns);

    // Hot path: four lanes per call, over 4096 precomputed hero-wavelength sets (as a renderer's per-sample loop
    // would hand them over), so the time is the evaluation alone.
    const ReflectanceSpectrum& spectrum = results[kSteps * kSteps * 20 + kSteps * 9 + 4].spectrum;
    std::vector<SampledWavelengths> lambdas;
    for (int i = 0; i < 4096; ++i) lambdas.push_back(SampledWavelengths::sample_uniform((i * 0.618034f) - int(i * 0.618034f), 360.0f, 830.0f));
    const int iterations = 50'000'000;
    Float4 sum(0.0f);
    const double eval_start = now_s();
    for (int i = 0; i < iterations; ++i) sum += spectrum.evaluate(lambdas[i & 4095]);
    const double eval_ns = (now_s() - eval_start) / iterations * 1e9;
    const UpsampledEmission emission = up.upsample_emission({0.8, 0.2, 0.1});
    Float4 sum_e(0.0f);
    const double emission_start = now_s();
    for (int i = 0; i < iterations; ++i) sum_e += emission.spectrum.evaluate(lambdas[i & 4095]);
    const double emission_ns = (now_s() - emission_start) / iterations * 1e9;
    std::printf("  one 4-lane evaluation: reflectance %.2f ns, emission (x illuminant table) %.2f ns [checksum %g]\n\n",
                eval_ns, emission_ns, double(sum[0] + sum_e[1]));
  }
  return 0;
}
