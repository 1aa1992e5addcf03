// How a camera path's four lanes are chosen in each WavelengthMode, and the lanes of the RGB transport baseline.
//
// The integrator and the render loop share one code path for every mode; what differs is (a) how the four lane
// wavelengths are drawn (here) and (b) how the per-lane densities of each sampling decision enter the estimator
// (LaneTechniques, below; docs/transport.md "Wavelength modes").
#pragma once

#include <optional>
#include <string_view>

#include "spectral/wavelengths/sampled_wavelengths.h"
#include "spectral/wavelengths/wavelength_density.h"
#include "transport/sampling/sampler.h"

namespace rimu {

/// How the four lanes are used.
enum class WavelengthMode {
  hero,    ///< hero + three partners, combined by spectral MIS (the default)
  single,  ///< the hero alone: partners carry nothing (a baseline, and a reference for unbiasedness tests)
  independent,  ///< four independently drawn wavelengths, each weighted by the hero's path density (no spectral MIS)
  rgb,     ///< RGB transport baseline: lanes carry linear sRGB (rgb_transport_lanes() below, docs/transport.md)
};

/// The lanes of rgb transport: lanes 0, 1, 2 carry linear sRGB R, G, B; lane 3 is dead (pdf 0) and ignored.
///
/// The "wavelengths" are nominal (612, 549, 465, 549 nm, near the dominant wavelengths of the sRGB primaries): an
/// input that was not converted to RGB at load (a named metal's n, k) is point-sampled there, the classic way RGB
/// renderers treat measured optical constants. The pdf ¼ makes the film's lane average ¼ Σⱼ Lⱼ cₖⱼ / pⱼ equal
/// Σⱼ Lⱼ cₖⱼ, which with the rgb-transport response cₖⱼ = M_sRGB→XYZ[k][j] is the film XYZ of the lane RGB.
SampledWavelengths rgb_transport_lanes();

/// Draws the four lanes for `mode` from `sampler` (called by the render loop after film and lens dimensions), with
/// density p(λ) = `density` (the scene's, spectral/wavelengths/wavelength_density.h), or the visible density if it is null:
///   hero, single: hero + three rotated partners from one dimension;
///   independent: four wavelengths each from its own dimension, each with density p(λ) (four dimensions);
///   rgb: one dimension is drawn and discarded (so later dimensions line up with hero mode) and the fixed lanes
///        of rgb_transport_lanes() are returned.
SampledWavelengths sample_path_wavelengths(WavelengthMode mode, Sampler& sampler,
                                          const TabulatedWavelengthDensity* density = nullptr);

/// Parses a mode's name as scenes spell it ("hero", "single", "independent", "rgb"); nullopt if unknown.
std::optional<WavelengthMode> parse_wavelength_mode(std::string_view name);
/// The scene spelling of a mode.
const char* wavelength_mode_name(WavelengthMode mode);

/// What one sampling decision's per-lane densities mean in each mode.
///
/// In hero (and single) mode lane k's density is the density the decision would have had with λₖ as hero:
/// spectral MIS uses all four. Independent and rgb modes have no spectral MIS: every lane's path is weighted by
/// the hero's density alone (fₖ/p₀, pbrt-v4 style), so these modes broadcast the hero lane. A decision whose
/// direction depends on λ (BsdfSample::wavelength_dependent_direction, a dispersive refraction) can be followed
/// by the hero only: independent mode then drops the partners (Rₖ ← 0), and the hero carries the whole estimate.
struct LaneTechniques {
  WavelengthMode mode;

  /// The densities the estimator combines: `pdf` itself under spectral MIS, else the hero's in every lane.
  SampledSpectrum densities(const SampledSpectrum& pdf) const {
    return spectral_mis() ? pdf : Float4(pdf[0]);
  }
  bool spectral_mis() const { return mode == WavelengthMode::hero || mode == WavelengthMode::single; }
  /// The initial ratios Rₖ: single mode has only the hero's technique; the others start with all four lanes.
  SampledSpectrum initial_ratios() const {
    return mode == WavelengthMode::single ? Float4(1.0f, 0.0f, 0.0f, 0.0f) : Float4(1.0f);
  }
  /// Independent mode keeps only the hero after a wavelength-dependent direction (see above).
  bool drops_partners_at_dispersion() const { return mode == WavelengthMode::independent; }
  /// After a sampled decision: where its direction depended on λ and the mode drops the partners, only the hero's
  /// lane of the path's ratios and throughput is kept (the partners' own directions were not followed).
  void keep_followed_lanes(bool wavelength_dependent_direction, SampledSpectrum& ratios, SampledSpectrum& beta) const {
    if (!wavelength_dependent_direction || !drops_partners_at_dispersion()) return;
    const Float4 hero_only(1.0f, 0.0f, 0.0f, 0.0f);
    ratios *= hero_only;
    beta *= hero_only;
  }
};

}  // namespace rimu
