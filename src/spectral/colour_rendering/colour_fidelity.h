// The CIE 2017 colour fidelity index (CIE 224:2017) and the ANSI/IES TM-30-20 gamut index and hue-bin values
// built on it: how faithfully a light renders 99 colour evaluation samples compared with a reference illuminant.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "spectral/colorimetry/cam02_ucs.h"
#include "spectral/colorimetry/observer.h"
#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

inline constexpr int kCesCount = 99;     ///< CIE 224:2017 colour evaluation samples
inline constexpr int kTm30HueBins = 16;  ///< TM-30 hue bins of 22.5° in CAM02-UCS a'b'

/// One TM-30 hue bin: the average CAM02-UCS a', b' of its samples under the reference and the test source, and
/// the local indices derived from them.
struct HueBin {
  int sample_count = 0;
  double reference_a = 0, reference_b = 0, test_a = 0, test_b = 0;
  double fidelity = 0;      ///< R_f,hj: the fidelity formula on the bin's mean ΔE'
  double chroma_shift = 0;  ///< R_cs,hj: test−reference along the bin's middle hue, over the reference chroma (0.1 = +10 %)
  double hue_shift = 0;     ///< R_hs,hj: the same across the hue direction (counter-clockwise positive)
};

struct ColourFidelity {
  double rf = 0;  ///< CIE 224:2017 / TM-30-20 fidelity index R_f (0-100)
  double rg = 0;  ///< TM-30-20 gamut index R_g: 100 × area of the test bin polygon / area of the reference one
  CctDuv cct;     ///< of the test source (CIE 1931 2°)
  std::string reference;             ///< "Planckian", "CIE daylight" or "Planckian/daylight blend, m = …"
  std::array<double, kCesCount> sample_fidelity{};  ///< R_f,CESi
  std::array<HueBin, kTm30HueBins> bins{};
};

/// Holds the 99 samples (data/spectra/reflectances/cie_224_2017_ces_5nm.csv), the CIE 1964 10° observer and the
/// daylight basis, so many sources can be rated.
///
/// Procedure (CIE 224:2017; TM-30-20 shares it): sums at 5 nm over 380-780 nm; CCT of the source by Ohno (2013)
/// on the CIE 1931 2° locus; reference = Planckian below 4000 K, CIE daylight above 5000 K, and between them the
/// two mixed in proportion m = (T − 4000)/1000 after each is scaled to Y = 1; sample colours with the 10°
/// observer, relative to the source's own white at Y = 100, in CAM02-UCS (L_A = 100 cd/m², Y_b = 20, average
/// surround, D = 1); R_f = 10 ln(exp((100 − 6.73 ΔE')/10) + 1) of the mean ΔE'.
class ColourFidelityEvaluator {
 public:
  explicit ColourFidelityEvaluator(SpectralLibrary& library);

  /// Throws InputError if the source does not cover 380-780 nm or its CCT lies outside 1000-25000 K.
  ColourFidelity evaluate(const Spectrum& test_source) const;

  /// The reference illuminant at this CCT, sampled on the 5 nm grid (value at 380, 385, …, 780 nm).
  std::vector<double> reference_power(double cct_k, std::string* description = nullptr) const;

 private:
  Observer observer_10_, observer_2_;
  PlanckianLocus locus_;  // on observer_2_
  DaylightBasis daylight_basis_;
  std::vector<TabulatedSpectrum> samples_;
};

/// A human-readable TM-30 report (R_f, R_g, CCT/Duv, reference, the 16 hue bins), ending with a newline.
std::string colour_fidelity_text(const ColourFidelity& fidelity, const std::string& description);
/// The same as JSON (bins as arrays in bin order, shifts as fractions).
std::string colour_fidelity_json(const ColourFidelity& fidelity, const std::string& description);

/// R_f from a mean CAM02-UCS difference: the CIE 224 scaling 100 − 6.73 ΔE', made positive by a soft plus.
double fidelity_from_delta_e(double mean_delta_e);

}  // namespace rimu
