// RGB → spectrum upsampler: the exact path (table + colour-correcting solve per colour) beside the fast path
// (basis coefficients interpolated at the table's grid points, docs/upsampling.md "Fast path").
//
//   build/bin/rimu-upsampler-bench [--accuracy-only | --timing-only] [Google Benchmark flags]   (--help: usage)
//
// First a round-trip accuracy report (a plain table: Google Benchmark's counters do not fit it) on the 33³ RGB
// grids of sRGB, ACEScg and Rec.2020: CIEDE2000 mean / p99 / max of both paths, unmapped and mapped, and the
// spectral RMS of both against the exact smoothest spectrum (the QP optimum, smoothest_spectrum.h). Then the
// timings through Google Benchmark: setup of one colour, one 4-lane evaluation, one bilinear texture lookup.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "bench_support.h"
#include "render/image/image_texture.h"
#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "spectral/upsampling/smoothest_spectrum.h"

using namespace rimu;

namespace {

struct Stats {
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  void print(const char* label) {
    if (values.empty()) return (void)std::printf("    %-44s (none)\n", label);
    std::sort(values.begin(), values.end());
    double sum = 0;
    for (double v : values) sum += v;
    std::printf("    %-44s n %6zu  mean %.2e  p99 %.2e  max %.2e\n", label, values.size(), sum / values.size(),
                values[size_t(0.99 * (values.size() - 1))], values.back());
  }
};

double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double delta_e_xyz(const Xyz& a, const Xyz& b, const Xyz& white) {
  return delta_e_2000(lab_of(a, white), lab_of(b, white));
}

double rms(const KnotValues& a, const KnotValues& b) {
  double s = 0;
  for (int i = 0; i < kUpsampleKnotCount; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / kUpsampleKnotCount);
}

// What the rendering evaluation (UpsamplingBasis::evaluate: clamp after interpolating between knots) adds to the
// colour of the knot-clamped spectrum (evaluate_clamped: clamp the knots, then interpolate), whose colour the knot
// colorimetry gives: the two differ only on knot intervals where the unclamped spectrum crosses 0 or 1, and there
// the difference is integrated against W·x̄, W·ȳ, W·z̄ at 0.05 nm, normalised so that Y(white) = 1.
Xyz render_clamp_offset(const KnotValues& raw, double lower, double upper, const TabulatedSpectrum& w,
                        const Observer& observer, double white_y) {
  Xyz out;
  constexpr int kSteps = 100;
  for (int i = 0; i + 1 < kUpsampleKnotCount; ++i) {
    const double a = raw[i], b = raw[i + 1];
    const bool crosses = (a < lower) != (b < lower) || (a > upper) != (b > upper);
    if (!crosses) continue;
    const double ca = std::clamp(a, lower, upper), cb = std::clamp(b, lower, upper);
    const double step_nm = kUpsampleKnotSpacingNm / kSteps;
    for (int s = 0; s < kSteps; ++s) {
      const double t = (s + 0.5) / kSteps;
      const double l = kUpsampleFirstKnotNm + (i + t) * kUpsampleKnotSpacingNm;
      const double d = std::clamp(a + t * (b - a), lower, upper) - (ca + t * (cb - ca));
      const double k = d * w.value(l) * step_nm / white_y;
      out.x += k * observer.x_bar.value(l), out.y += k * observer.y_bar.value(l), out.z += k * observer.z_bar.value(l);
    }
  }
  return out;
}

SpectralLibrary& library() {
  static SpectralLibrary l = SpectralLibrary::at_default_location();
  return l;
}

const RgbUpsampler& upsampler(const char* space) {
  static std::unique_ptr<RgbUpsampler> srgb, acescg, rec2020;
  auto& slot = std::strcmp(space, "acescg") == 0 ? acescg : std::strcmp(space, "rec2020") == 0 ? rec2020 : srgb;
  if (!slot) slot = std::make_unique<RgbUpsampler>(library(), RgbColourSpace::named(space));
  return *slot;
}

void accuracy_report() {
  constexpr int kSteps = 33;
  for (const char* name : {"srgb-linear", "acescg", "rec2020"}) {
    const double setup_start = now_s();
    const RgbUpsampler up(library(), RgbColourSpace::named(name));
    const double exact_setup_s = now_s() - setup_start;
    up.basis();  // built on first use
    const double setup_s = now_s() - setup_start;
    Stats exact_unmapped, exact_unmapped_cie, fast_unmapped, fast_render_unmapped, render_vs_knot, exact_mapped, fast_mapped, exact_rms, fast_rms,
        fast_vs_exact_rms, ringing, rough;
    const Observer& observer = library().observer(StandardObserver::cie1931_2deg);
    int unmapped_count = 0, total = 0, flag_mismatch = 0;
    const Xyz white = up.colorimetry().white_xyz();
    const double white_y = integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) {
      return up.illuminant()->value(l) * observer.y_bar.value(l);
    });
    for (int r = 0, n = 0; r < kSteps; ++r)
      for (int g = 0; g < kSteps; ++g)
        for (int b = 0; b < kSteps; ++b, ++n) {
          const Rgb rgb{r / 32.0, g / 32.0, b / 32.0};
          const Xyz in = up.space().to_xyz(rgb);
          const UpsampledReflectance exact = up.upsample_reflectance(rgb);
          bool fast_moved = false;
          const BasisCoefficients c = up.reflectance_coefficients(rgb, &fast_moved);
          const KnotValues raw = up.basis().knots(c);
          double most_negative = 0;
          for (double v : raw) most_negative = std::fmin(most_negative, v);
          const KnotValues fast = up.fast_reflectance_spectrum(rgb).samples().knots();
          const double fast_delta_e = delta_e_xyz(in, up.colorimetry().xyz_of(fast), white);
          ++total;
          flag_mismatch += fast_moved != exact.gamut_mapped;
          if (exact.gamut_mapped) {
            exact_mapped.add(exact.delta_e2000);
            fast_mapped.add(fast_delta_e);
            continue;
          }
          ++unmapped_count;
          exact_unmapped.add(exact.delta_e2000);
          fast_unmapped.add(fast_delta_e);
          {
            const Xyz knot_colour = up.colorimetry().xyz_of(fast);
            const Xyz offset = render_clamp_offset(raw, 0.0, 1.0, *up.illuminant(), observer, white_y);
            const Xyz rendered{knot_colour.x + offset.x, knot_colour.y + offset.y, knot_colour.z + offset.z};
            fast_render_unmapped.add(delta_e_xyz(in, rendered, white));
            render_vs_knot.add(delta_e_xyz(knot_colour, rendered, white));
          }
          ringing.add(-most_negative);
          const KnotValues exact_knots = exact.spectrum.samples().knots();
          rough.add(roughness(exact_knots));
          // Independent check of the exact path: CIE 15 1 nm sum under the illuminant's own table (colorimetry.h),
          // every 7th colour.
          if (n % 7 == 0) {
            const Xyz cie = reflectance_xyz(exact.spectrum, *up.illuminant(), observer);
            exact_unmapped_cie.add(delta_e_xyz(in, {cie.x / 100, cie.y / 100, cie.z / 100}, white));
          }
          fast_vs_exact_rms.add(rms(fast, exact_knots));
          // The exact smoothest spectrum (QP optimum) of the same colour: every 5th colour (0.2 ms each).
          if (n % 5 == 0 && (r + g + b) > 0) {
            if (const auto optimum = smoothest_knot_spectrum(up.colorimetry(), in)) {
              exact_rms.add(rms(exact_knots, optimum->knots));
              fast_rms.add(rms(fast, optimum->knots));
            }
          }
        }
    std::printf("%s (33^3 = %d colours; %.1f %% need no gamut mapping; upsampler setup %.1f ms, incl. basis %.1f ms)\n",
                name, total, 100.0 * unmapped_count / total, exact_setup_s * 1e3, setup_s * 1e3);
    std::printf("  round-trip CIEDE2000, RGB -> spectrum -> XYZ under the space's white -> RGB, not mapped:\n");
    exact_unmapped.print("exact path (table + solve)");
    exact_unmapped_cie.print("exact path, via the CIE table illuminant");
    fast_unmapped.print("fast path (basis, knots clamped to [0,1])");
    fast_render_unmapped.print("fast path as rendered (clamp after lerp)");
    render_vs_knot.print("  rendered vs knot-clamped fast spectrum");
    std::printf("  CIEDE2000 moved by gamut mapping:\n");
    exact_mapped.print("exact path");
    fast_mapped.print("fast path");
    std::printf("  colours whose mapped flag differs between the paths: %d\n", flag_mismatch);
    std::printf("  spectral RMS over the 95 knots (reflectance units), not mapped:\n");
    exact_rms.print("exact path vs smoothest (QP optimum)");
    fast_rms.print("fast path vs smoothest (QP optimum)");
    fast_vs_exact_rms.print("fast path vs exact path");
    ringing.print("fast path: depth of negative ringing");
    std::printf("  smoothness of the exact path, sum (S[i+1]-S[i])^2 over 5 nm knots, not mapped:\n");
    rough.print("roughness");
    std::printf("\n");
  }
}

// ---- timings ---------------------------------------------------------------------------------------------

std::vector<Rgb> random_colours() {
  std::vector<Rgb> out;
  uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) * (1.0 / 16777216.0);
  };
  for (int i = 0; i < 4096; ++i) out.push_back({next(), next(), next()});
  return out;
}

std::vector<SampledWavelengths> wavelength_sets() {
  std::vector<SampledWavelengths> out;
  for (int i = 0; i < 4096; ++i) out.push_back(SampledWavelengths::sample_visible((i * 0.618034f) - int(i * 0.618034f)));
  return out;
}

// One timing loop: DoNotOptimize(call(i)) for i = 0, 1, 2, … (callers index their 4096-entry inputs by i & 4095).
template <class Call>
void time_each(benchmark::State& state, Call call) {
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(call(i++));
}

// The fast path's coefficients of random_colours(): what the evaluation benchmarks evaluate.
std::vector<BasisCoefficients> random_coefficients(const RgbUpsampler& up) {
  std::vector<BasisCoefficients> out;
  for (const Rgb& rgb : random_colours()) out.push_back(up.reflectance_coefficients(rgb));
  return out;
}

void BM_Setup_Exact(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto colours = random_colours();
  time_each(state, [&](size_t i) { return up.reflectance_spectrum(colours[i & 4095]); });
}
BENCHMARK(BM_Setup_Exact);

void BM_Setup_FastCoefficients(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto colours = random_colours();
  time_each(state, [&](size_t i) { return up.reflectance_coefficients(colours[i & 4095]); });
}
BENCHMARK(BM_Setup_FastCoefficients);

// Muted colours (each channel in [0.25, 0.55]): no ringing, far from the brightness limit, so no 95-knot pass.
void BM_Setup_FastCoefficients_Muted(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  auto colours = random_colours();
  for (Rgb& c : colours) c = {0.25 + 0.3 * c.r, 0.25 + 0.3 * c.g, 0.25 + 0.3 * c.b};
  time_each(state, [&](size_t i) { return up.reflectance_coefficients(colours[i & 4095]); });
}
BENCHMARK(BM_Setup_FastCoefficients_Muted);

void BM_Setup_FastKnotSpectrum(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto colours = random_colours();
  time_each(state, [&](size_t i) { return up.fast_reflectance_spectrum(colours[i & 4095]); });
}
BENCHMARK(BM_Setup_FastKnotSpectrum);

void BM_Setup_FastEmissionCoefficients(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto colours = random_colours();
  time_each(state, [&](size_t i) { return up.emission_coefficients(colours[i & 4095]); });
}
BENCHMARK(BM_Setup_FastEmissionCoefficients);

void BM_Eval4_KnotSpectrum(benchmark::State& state) {
  const ReflectanceSpectrum s = upsampler("srgb-linear").reflectance_spectrum({0.6, 0.3, 0.1});
  const auto lambdas = wavelength_sets();
  time_each(state, [&](size_t i) { return s.evaluate(lambdas[i & 4095]); });
}
BENCHMARK(BM_Eval4_KnotSpectrum);

// The knot-clamped evaluation (evaluate_clamped: clamp the two knots, then interpolate), the reference.
void BM_Eval4_BasisCoefficients_KnotClamped(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto cs = random_coefficients(up);
  const auto lambdas = wavelength_sets();
  time_each(state, [&](size_t i) {
    return up.basis().evaluate_clamped(cs[i & 4095], lambdas[(i >> 3) & 4095].lambda_nm(), Float4(0.0f), Float4(1.0f));
  });
}
BENCHMARK(BM_Eval4_BasisCoefficients_KnotClamped);

// The rendering evaluation (evaluate: the basis interpolated at the path's wavelengths from the per-thread cache,
// one 16-term dot product per lane). A path evaluates every texture it meets at its four wavelengths; here 8
// evaluations of different colours per wavelength set.
void BM_Eval4_BasisCoefficients(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto cs = random_coefficients(up);
  const auto lambdas = wavelength_sets();
  time_each(state, [&](size_t i) {
    return up.basis().evaluate(cs[i & 4095], lambdas[(i >> 3) & 4095].lambda_nm(), Float4(0.0f), Float4(1.0f));
  });
}
BENCHMARK(BM_Eval4_BasisCoefficients);

// The same with new wavelengths at every evaluation: the cache refilled each time (the worst case; the first
// evaluation of every path pays it).
void BM_Eval4_BasisCoefficients_NewWavelengths(benchmark::State& state) {
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto cs = random_coefficients(up);
  const auto lambdas = wavelength_sets();
  time_each(state, [&](size_t i) {
    return up.basis().evaluate(cs[i & 4095], lambdas[i & 4095].lambda_nm(), Float4(0.0f), Float4(1.0f));
  });
}
BENCHMARK(BM_Eval4_BasisCoefficients_NewWavelengths);

void BM_Eval4_EmissionExact(benchmark::State& state) {
  const UpsampledEmission e = upsampler("srgb-linear").upsample_emission({0.8, 0.2, 0.1});
  const auto lambdas = wavelength_sets();
  time_each(state, [&](size_t i) { return e.spectrum.evaluate(lambdas[i & 4095]); });
}
BENCHMARK(BM_Eval4_EmissionExact);

std::shared_ptr<const RgbImage> random_image(int size) {
  const auto colours = random_colours();
  std::vector<float> rgb;
  for (int i = 0; i < size * size; ++i) {
    const Rgb c = colours[size_t(i) & 4095];
    rgb.insert(rgb.end(), {float(c.r), float(c.g), float(c.b)});
  }
  return std::make_shared<const RgbImage>(size, size, std::move(rgb));
}

std::vector<Vec2> random_uvs() {
  std::vector<Vec2> out;
  uint32_t state = 777;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float((state >> 8) * (1.0 / 16777216.0));
  };
  for (int i = 0; i < 4096; ++i) out.push_back({next(), next()});
  return out;
}

// The texture lookup before the fast path: bilinear RGB, then the exact upsampling per lookup.
void BM_TextureLookup_PerLookupExact(benchmark::State& state) {
  const auto image = random_image(256);
  const RgbUpsampler& up = upsampler("srgb-linear");
  const auto uvs = random_uvs();
  const auto lambdas = wavelength_sets();
  time_each(state, [&](size_t i) {
    return up.reflectance_spectrum(image->bilinear(uvs[i & 4095])).evaluate(lambdas[i & 4095]);
  });
}
BENCHMARK(BM_TextureLookup_PerLookupExact);

// The texture lookup as rendered (ImageTexture::evaluate): the bilinear RGB of 4 texels, that colour's coefficients by
// the fast path (reflectance_coefficients, once per lookup: a texture keeps RGB, not coefficients), evaluated at the
// path's wavelengths. 2^`shift` lookups per wavelength set: 1 refills the per-thread basis cache at every lookup (the
// worst case), 8 is what a path that meets textures several times pays per lookup.
void time_texture_lookups(benchmark::State& state, int shift) {
  auto shared = std::make_shared<const RgbUpsampler>(library(), RgbColourSpace::named("srgb-linear"));
  const ImageTexture texture(random_image(int(state.range(0))), shared, 1.0f);
  const auto uvs = random_uvs();
  const auto lambdas = wavelength_sets();
  time_each(state, [&](size_t i) { return texture.evaluate(uvs[i & 4095], lambdas[(i >> shift) & 4095]); });
}
void BM_TextureLookup_PerLookupFast(benchmark::State& state) { time_texture_lookups(state, 0); }
BENCHMARK(BM_TextureLookup_PerLookupFast)->Arg(64)->Arg(1024);
void BM_TextureLookup_PerLookupFast_SameWavelengths(benchmark::State& state) { time_texture_lookups(state, 3); }
BENCHMARK(BM_TextureLookup_PerLookupFast_SameWavelengths)->Arg(64);

void BM_TextureConversion_PerTexel(benchmark::State& state) {
  auto shared = std::make_shared<const RgbUpsampler>(library(), RgbColourSpace::named("srgb-linear"));
  const auto image = random_image(256);
  for (auto _ : state) benchmark::DoNotOptimize(ImageTexture(image, shared, 1.0f));
  state.SetItemsProcessed(state.iterations() * 256 * 256);
}
BENCHMARK(BM_TextureConversion_PerTexel)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"RGB -> spectrum upsampler: round-trip accuracy of the exact and fast paths on the 33^3 grids of "
               "sRGB, ACEScg and Rec.2020, then Google Benchmark timings (setup, 4-lane evaluation, texture lookup). "
               "Options it does not know (--benchmark_filter=..., --benchmark_min_time=...) go to Google Benchmark.",
               "rimu-upsampler-bench"};
  bool accuracy_only = false, timing_only = false;
  CLI::Option* accuracy_flag = app.add_flag("--accuracy-only", accuracy_only, "the accuracy report alone");
  app.add_flag("--timing-only", timing_only, "the timings alone")->excludes(accuracy_flag);
  app.allow_extras();
  bench::parse_command_line(app, argc, argv);
  std::vector<std::string> extras = app.remaining();
  std::vector<char*> rest = {argv[0]};
  for (std::string& e : extras) rest.push_back(e.data());
  std::printf("build: %s\n\n", RIMU_BENCH_BUILD);
  if (!timing_only) accuracy_report();
  if (!accuracy_only) {
    int count = int(rest.size());
    benchmark::Initialize(&count, rest.data());
    if (benchmark::ReportUnrecognizedArguments(count, rest.data())) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
  }
  return 0;
}
