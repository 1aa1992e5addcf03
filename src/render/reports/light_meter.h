// Light meters for tests and tools: what a light delivers to a point (an illuminance meter with a flat, cosine-
// corrected receptor) and what the camera sees (luminance from an XYZ film).
#pragma once

#include <cstdint>

#include "render/film/film.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "transport/integrators/path_integrator.h"

namespace rimu {

/// A Monte Carlo reading: the mean and its standard error (the sample standard deviation / √n).
struct MeterReading {
  double value = 0;
  double standard_error = 0;
  int samples = 0;
};

/// Direct illuminance in lx at `position_m` on the side of `normal` (unit): E_v = K_m ∫ V(λ) Σ_lights ∫ L cos θ dω dλ,
/// estimated per sample with one hero-wavelength set (stratified over the visible sampling pdf) and one sample_li per
/// light, with shadow rays that pass glazing panes (thin dielectrics) with their straight-through transmittance, as
/// the path integrator's do. Only light arriving straight from the lights counts (no reflections), like a lux meter
/// in a black room. `v` is V(λ) (SpectralLibrary::photopic_v()). Cost: `samples` × lights shadow rays.
MeterReading measure_illuminance_lx(const TransportScene& scene, Vec3 position_m, Vec3 normal,
                                    const TabulatedSpectrum& v, int samples, uint64_t seed);

/// The luminance in nits an XYZ film recorded in `window`: the mean over its pixels of Y × 683·∫ȳ dλ
/// (SpectralResponse::luminance_nits_per_unit_y), with the standard error of that mean across pixels (pixels are
/// independent estimates of the same luminance when the window sees a uniform surface). InputError for camera films.
MeterReading measure_luminance_nt(const Film& film, const PixelBounds& window);

}  // namespace rimu
