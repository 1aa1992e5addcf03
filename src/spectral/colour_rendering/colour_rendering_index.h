// The CIE 1995 colour rendering index (CIE 13.3-1995, "test-colour method").
#pragma once

#include <array>
#include <vector>

#include "spectral/colorimetry/daylight.h"
#include "spectral/colorimetry/observer.h"
#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/spectra/spectrum.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

class SpectralLibrary;

/// CIE 13.3 Duv limit: beyond a distance of 5.4e-3 in CIE 1960 (u, v) from the Planckian locus the test source
/// is not "white" enough for its colour rendering to be compared with a reference illuminant (CIE 13.3 §5.3).
inline constexpr double kCri_MaxDuv = 5.4e-3;

/// Which reference illuminant a colour rendering index was computed against.
enum class CriReference {
  planckian,        ///< a black body at the test source's CCT (CCT < 5000 K, CIE 13.3 §5.2)
  daylight,         ///< CIE daylight at the test source's CCT (CCT >= 5000 K)
  caller_supplied,  ///< whatever ColourRenderingEvaluator::evaluate_against() was given
};

/// The outcome of CIE 13.3 for one test source.
struct ColourRenderingIndex {
  double ra = 0.0;                   ///< general colour rendering index, the mean of R1..R8
  std::array<double, 14> special{};  ///< special indices R1..R14 (special[0] is R1)
  CctDuv source;                     ///< the test source's CCT and Duv (CIE 1931 2°; (u, v) from the 5 nm sum)
  CriReference reference = CriReference::planckian;
  bool duv_within_cie_limit = false;  ///< |Duv| <= 5.4e-3: otherwise CIE 13.3 calls the result not meaningful
};

/// The 14 CIE 13.3 test colour samples (reflectance factors, 360-830 nm at 5 nm; TCS01 first), read from
/// data/spectra/reflectances/cie_13_3_tcs_5nm.csv through the library's cache.
std::vector<TabulatedSpectrum> cie_13_3_test_colour_samples(SpectralLibrary& library);

/// Holds what every CRI evaluation needs (2° observer, its Planckian locus, the daylight basis, the 14 samples),
/// so that many sources can be rated without rebuilding the locus.
///
/// Sums run at 5 nm over 380-780 nm, the practice CIE 13.3 §5 prescribes and that the published Ra of the CIE
/// illuminants (CIE 15:2004 Table T.8) were computed with.
class ColourRenderingEvaluator {
 public:
  /// Loads the CIE 1931 2° observer, the daylight basis and the test colour samples from `library`.
  explicit ColourRenderingEvaluator(SpectralLibrary& library);

  /// Ra and R1..R14 of `test_source` (relative spectral power; its scale cancels). Throws InputError when the
  /// source's CCT is outside 1000-25000 K, where CIE 13.3 defines no reference illuminant.
  ColourRenderingIndex evaluate(const Spectrum& test_source) const;

  /// The same computation against a reference the caller chooses instead of the one CIE 13.3 §5.2 assigns:
  /// to rate a source against a fixed reference, or to reproduce tables computed with another choice (CIE
  /// 15:2004 Table T.8 rates F8 and F10, whose CCTs lie 1-3 K below 5000 K, against daylight). CCT and Duv are
  /// still those of the test source.
  ColourRenderingIndex evaluate_against(const Spectrum& test_source, const Spectrum& reference) const;

  /// The reference illuminant CIE 13.3 §5.2 pairs with a CCT: Planckian below 5000 K, CIE daylight at and above.
  SpectrumPtr reference_illuminant(double cct_k) const;

  const PlanckianLocus& locus() const { return locus_; }

 private:
  ColourRenderingIndex rate(const Spectrum& test_source, const Spectrum& reference, CctDuv source_cct,
                            CriReference kind) const;

  Observer observer_;
  PlanckianLocus locus_;
  DaylightBasis daylight_basis_;
  std::vector<TabulatedSpectrum> samples_;
};

/// Convenience: a ColourRenderingEvaluator built for one source (~10 ms; hold an evaluator for many sources).
ColourRenderingIndex colour_rendering_index(const Spectrum& test_source, SpectralLibrary& library);

}  // namespace rimu
