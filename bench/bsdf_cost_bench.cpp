// The cost of one BSDF evaluation (eval + pdf, what next-event estimation calls) and one sample, for the coated
// materials' closed forms against the layered random walk, with a Lambertian as the unit. Directions are drawn
// cosine-distributed once, before timing; every call gets the next pair.
//
//   build/bin/rimu-bsdf-cost-bench [--benchmark_min_time=0.3]
//
// The layered BSDF runs `samples` walks of up to `max_depth` events per eval()/pdf(): its cost depends on the
// base's albedo (brighter bases bounce longer) and on the slab; the cases below are pbrt-v4's defaults
// (thickness 0.01, albedo 0, maxdepth 10, nsamples 1) on a 0.5 base, and a scattering slab.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "spectral/library/optical_constants.h"
#include "spectral/library/spectral_library.h"
#include "transport/bsdfs/bsdf.h"
#include "transport/bsdfs/measured_brdf_tabulation.h"
#include "transport/sampling/direction_warps.h"
#include "transport/bsdfs/fresnel.h"

using namespace rimu;

namespace {

struct Directions {
  std::vector<Vec3> wo, wi;
  std::vector<float> u;
};

const Directions& directions() {
  static const Directions d = [] {
    Directions out;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 4096; ++i) {
      out.wo.push_back(sample_cosine_hemisphere({u(rng), u(rng)}));
      out.wi.push_back(sample_cosine_hemisphere({u(rng), u(rng)}));
      for (int k = 0; k < 3; ++k) out.u.push_back(u(rng));
    }
    return out;
  }();
  return d;
}

const Float4 kBase(0.5f);
const float kEta = 1.5f;

Bsdf make(int which) {
  const float rough = TrowbridgeReitz::roughness_to_alpha(0.3f);
  static SpectralLibrary library = SpectralLibrary::at_default_location();
  const ComplexIorSpectra gold = conductor_ior(library, "gold");
  const SampledWavelengths lambda(Float4(450.0f, 550.0f, 650.0f, 750.0f), Float4(1.0f));
  const ConductorBsdf metal(gold.n->sample(lambda) / Float4(kEta), gold.k->sample(lambda) / Float4(kEta), TrowbridgeReitz(rough, rough));
  switch (which) {
    case 0: return DiffuseBsdf(kBase);
    case 1: return CoatedDiffuseBsdf(kBase, Float4(kEta), Float4(float(fresnel_diffuse_reflectance(kEta))));
    case 2: return CoatedDiffuseBsdf::absorbing(kBase, Float4(kEta), Float4(float(coat_internal_reflectance(kEta, 0.01))), 0.01f);
    case 3: return LayeredBsdf(kEta, TrowbridgeReitz(0, 0), DiffuseBsdf(kBase), {0.01f, Float4(0.0f), 0.0f}, {10, 1});
    case 4: return LayeredBsdf(kEta, TrowbridgeReitz(rough, rough), DiffuseBsdf(kBase), {0.01f, Float4(0.0f), 0.0f}, {10, 1});
    case 5: return LayeredBsdf(kEta, TrowbridgeReitz(rough, rough), metal, {0.01f, Float4(0.0f), 0.0f}, {10, 1});
    case 6: return LayeredBsdf(kEta, TrowbridgeReitz(rough, rough), DiffuseBsdf(kBase), {0.5f, Float4(0.8f), 0.3f}, {10, 1});
    // pbrt-v4's default hair (β_m = β_n = 0.3, α = 2°, η = 1.55) with a brown σa, the fibre across the frame.
    case 7: return HairBsdf({0.6f, 0.8f}, 0.3f, Float4(0.55f, 0.95f, 1.8f, 2.4f), HairParameters{});
    // The layered walk's parts alone: the rough coat (what every coat event costs) and a rough metal.
    case 9: return DielectricBsdf(Float4(kEta), TrowbridgeReitz(rough, rough));
    case 10: return metal;
    // A measured BRDF (pbrt-v4's `measured`) of the RGL file's size: gold α = 0.09 tabulated at 16 elevations,
    // 64 × 64 grids, 48 wavelengths (as rimu-make-measured-bsdf writes it).
    case 8: {
      static const MeasuredBrdf brdf = [rough] {
        MicrofacetTabulation t = MicrofacetTabulation::conductor(conductor_ior(library, "gold"), rough);
        t.theta_i_count = 16;
        t.vndf_size = 64;
        return MeasuredBrdf::from_tensor_file(TensorFile::parse(TensorFile::serialise(tabulate_microfacet_brdf(t)), "gold"));
      }();
      return MeasuredBsdf(&brdf, lambda.lambda_nm());
    }
    default: return DiffuseBsdf(kBase);
  }
}

const char* const kNames[] = {"diffuse", "coated_diffuse closed form (clear)", "coated_diffuse closed form (thickness 0.01)",
                              "layered: smooth coat, diffuse, thickness 0.01", "layered: rough coat 0.3, diffuse, thickness 0.01",
                              "layered: rough coat 0.3, rough gold 0.3", "layered: rough coat 0.3, diffuse, scattering slab 0.5",
                              "hair (pbrt-v4's defaults, brown)", "measured (GGX gold 0.09 tabulated, RGL layout)",
                              "rough dielectric 0.3 (eta 1.5)", "rough conductor 0.3 (gold)"};

void BM_EvalPdf(benchmark::State& state) {
  const Bsdf bsdf = make(int(state.range(0)));
  const Directions& d = directions();
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & 4095;
    benchmark::DoNotOptimize(bsdf.eval(d.wo[k], d.wi[k]));
    benchmark::DoNotOptimize(bsdf.pdf(d.wo[k], d.wi[k]));
  }
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_EvalPdf)->DenseRange(0, 10);

void BM_Sample(benchmark::State& state) {
  const Bsdf bsdf = make(int(state.range(0)));
  const Directions& d = directions();
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & 4095;
    benchmark::DoNotOptimize(bsdf.sample(d.wo[k], d.u[3 * k], {d.u[3 * k + 1], d.u[3 * k + 2]}));
  }
  state.SetLabel(kNames[state.range(0)]);
}
BENCHMARK(BM_Sample)->DenseRange(0, 10);

}  // namespace

BENCHMARK_MAIN();
