// Light meters for tests and tools: what a light delivers to a point (an illuminance meter with a flat, cosine-
// corrected receptor) and what the camera sees (luminance from an XYZ film).
#pragma once

#include <cstdint>
#include <span>

#include "render/film/film.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "transport/integrators/path_integrator.h"

namespace rimu {

/// A Monte Carlo reading: the mean and its standard error.
struct MeterReading {
  double value = 0;
  double standard_error = 0;
  int samples = 0;
};

/// The mean of `values`, taken as independent and identically distributed estimates, and its standard error
/// s/√n (0 for fewer than two values); `samples` = their count.
MeterReading mean_and_standard_error(std::span<const double> values);

/// How many independent replicates `samples` are split into by default: samples/16, at least 2 and at most 16 (1 for
/// a single sample). Why replicates: the samples of one point come from a stratified or Owen-scrambled Sobol' design,
/// whose points are not independent, so the textbook standard error s/√n of its n values overstates the error of their
/// mean (3-8× measured on the CIE 171 cases). Randomised quasi-Monte Carlo's remedy (Owen 1997; L'Ecuyer & Lemieux
/// 2002) is R independent scrambles of n/R points each: their R means are independent and identically distributed,
/// so the standard deviation of the means over √R is an unbiased-variance standard error of their average. At least
/// 16 points per replicate keep most of the sequence's stratification; 16 replicates give the error estimate itself
/// ~18 % relative spread (a t distribution of 15 degrees of freedom for the reading's error over it).
int replicates_for(int samples);

/// Direct illuminance in lx at `position_m` on the side of `normal` (unit): E_v = K_m ∫ V(λ) Σ_lights ∫ L cos θ dω dλ,
/// estimated per sample with one hero-wavelength set and one sample_li per light, the samples split into
/// replicates_for(samples) independent batches, each stratifying its hero wavelengths over the visible sampling pdf
/// on its own (so the batch means are independent and alike, and the standard error is their spread), with shadow rays that pass glazing panes (thin dielectrics) with their straight-through transmittance, as
/// the path integrator's do. Only light arriving straight from the lights counts (no reflections), like a lux meter
/// in a black room. `v` is V(λ) (SpectralLibrary::photopic_v()). Cost: `samples` × lights shadow rays.
MeterReading measure_illuminance_lx(const TransportScene& scene, Vec3 position_m, Vec3 normal,
                                    const TabulatedSpectrum& v, int samples, uint64_t seed);

/// The luminance in nits an XYZ film recorded in `window`: the mean over its pixels of Y × 683·∫ȳ dλ
/// (SpectralResponse::luminance_nits_per_unit_y), with the standard error of that mean across pixels (pixels are
/// independent estimates of the same luminance when the window sees a uniform surface). InputError for camera films.
MeterReading measure_luminance_nt(const Film& film, const PixelBounds& window);

}  // namespace rimu
