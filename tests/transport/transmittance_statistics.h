// The mean of many ratio-tracking transmittance estimates along one ray: what the grid-medium tests compare with
// exp(−σ_t ∫ d) (dense, trilinear and NanoVDB grids alike).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "transport/media/medium.h"
#include "transport/media/spectral_distance_sampling.h"
#include "transport/sampling/sampler.h"

namespace rimu::test {

struct TransmittanceStatistics {
  double mean = 0.0, standard_error = 0.0;
};

/// `count` spectral-MIS estimates of the transmittance of `medium` along `ray` up to t_max, at the first lane of the
/// wavelengths 450, 520, 600, 680 nm, with one IndependentSampler of `seed`.
inline TransmittanceStatistics transmittance_statistics(const Medium& medium, const Ray& ray, float t_max, int count,
                                                        uint64_t seed = 17) {
  const SampledWavelengths lambda(Float4(450.0f, 520.0f, 600.0f, 680.0f), Float4(1.0f));
  IndependentSampler sampler(seed);
  sampler.start_pixel_sample(0, 0, 0);
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < count; ++i) {
    SampledSpectrum throughput = Float4(1.0f);
    const double t =
        estimate_transmittance(medium, ray, t_max, lambda, DistanceSampling::spectral_mis, sampler, throughput)
            .transmittance[0];
    sum += t;
    sum2 += t * t;
  }
  TransmittanceStatistics s;
  s.mean = sum / count;
  s.standard_error = std::sqrt(std::max(sum2 / count - s.mean * s.mean, 0.0) / count);
  return s;
}

}  // namespace rimu::test
