#include "spectral/colour_rendering/colour_rendering_index.h"

#include <cmath>
#include <memory>
#include <sstream>

#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/error.h"
#include "spectral/library/spectral_library.h"

namespace rimu {
namespace {

constexpr const char* kTestColourSamplesFile = "spectra/reflectances/cie_13_3_tcs_5nm.csv";
constexpr double kDaylightFromCct_k = 5000.0;  // CIE 13.3 §5.2: daylight reference at and above 5000 K

/// What CIE 13.3 needs of one colour: its luminance factor Y (white = 100) and CIE 1960 (u, v).
struct UvY {
  double u, v, y;
};

UvY uvy_of(const Xyz& xyz) {
  const Uv1960 uv = uv1960_of(xyz);
  return {uv.u, uv.v, xyz.y};
}

/// The c and d of CIE 13.3 eq. (4), the coordinates in which its von Kries transform is linear:
/// c = (4 − u − 10v)/v, d = (1.708v + 0.404 − 1.481u)/v.
double c_of(const UvY& p) { return (4.0 - p.u - 10.0 * p.v) / p.v; }
double d_of(const UvY& p) { return (1.708 * p.v + 0.404 - 1.481 * p.u) / p.v; }

/// CIE 1964 U*V*W* (CIE 13.3 eq. 6) relative to the white (u0, v0): W* = 25·Y^(1/3) − 17,
/// U* = 13·W*·(u − u0), V* = 13·W*·(v − v0).
struct Uvw {
  double u, v, w;
};

Uvw uvw_of(const UvY& p, double white_u, double white_v) {
  const double w = 25.0 * std::cbrt(p.y) - 17.0;
  return {13.0 * w * (p.u - white_u), 13.0 * w * (p.v - white_v), w};
}

}  // namespace

std::vector<TabulatedSpectrum> cie_13_3_test_colour_samples(SpectralLibrary& library) {
  const CsvTable& table = library.table(kTestColourSamplesFile);
  std::vector<TabulatedSpectrum> samples;
  for (int i = 1; i <= 14; ++i) {
    const std::string column = (i < 10 ? "TCS0" : "TCS") + std::to_string(i);
    // Reflectances are extended by their end values (CIE 15:2004 §7.2.2.1); the 5 nm sums never leave the table.
    samples.push_back(TabulatedSpectrum::from_csv(table, column, Extrapolation::clamp));
  }
  return samples;
}

ColourRenderingEvaluator::ColourRenderingEvaluator(SpectralLibrary& library)
    : observer_(library.observer(StandardObserver::cie1931_2deg)),
      locus_(observer_),
      daylight_basis_(library.daylight_basis()),
      samples_(cie_13_3_test_colour_samples(library)) {}

SpectrumPtr ColourRenderingEvaluator::reference_illuminant(double cct_k) const {
  if (cct_k < kDaylightFromCct_k)
    return std::make_shared<BlackbodySpectrum>(cct_k, BlackbodySpectrum::Scale::peak_one);
  // Unrounded M1, M2: the reference is the daylight phase at exactly this CCT, not a tabulated D illuminant.
  return std::make_shared<TabulatedSpectrum>(daylight_spectrum(daylight_basis_, cct_k, DaylightRounding::exact));
}

ColourRenderingIndex ColourRenderingEvaluator::evaluate(const Spectrum& test_source) const {
  // The CCT comes from the source's 5 nm chromaticity on the 1 nm locus, the CIE's definition of the Planckian
  // locus. (A 5 nm locus would match a 5 nm black body exactly, but it moves the CCT of CIE daylight by 1.5 K at
  // 6500 K away from the temperature the daylight equations were built for; the 1 nm locus agrees with them to
  // 0.02 K.)
  const UvY source = uvy_of(illuminant_xyz(test_source, observer_, IntegrationGrid::cie_5nm_abridged()));
  const CctDuv source_cct = locus_.cct_duv({source.u, source.v});
  if (source_cct.validity == CctValidity::below_range || source_cct.validity == CctValidity::above_range) {
    std::ostringstream message;
    message << "the colour rendering index needs a test source with a CCT in " << PlanckianLocus::kMinCct_k << "-"
            << PlanckianLocus::kMaxCct_k << " K; '" << test_source.describe() << "' lies beyond the "
            << source_cct.cct_k << " K end of the Planckian locus";
    throw InputError({}, message.str());
  }
  const SpectrumPtr reference = reference_illuminant(source_cct.cct_k);
  return rate(test_source, *reference, source_cct,
              source_cct.cct_k >= kDaylightFromCct_k ? CriReference::daylight : CriReference::planckian);
}

ColourRenderingIndex ColourRenderingEvaluator::evaluate_against(const Spectrum& test_source,
                                                                const Spectrum& reference) const {
  const Xyz source = illuminant_xyz(test_source, observer_, IntegrationGrid::cie_5nm_abridged());
  return rate(test_source, reference, locus_.cct_duv(uv1960_of(source)), CriReference::caller_supplied);
}

ColourRenderingIndex ColourRenderingEvaluator::rate(const Spectrum& test_source, const Spectrum& reference_spectrum,
                                                    CctDuv source_cct, CriReference kind) const {
  const IntegrationGrid grid = IntegrationGrid::cie_5nm_abridged();
  const UvY source = uvy_of(illuminant_xyz(test_source, observer_, grid));
  const UvY reference = uvy_of(illuminant_xyz(reference_spectrum, observer_, grid));

  ColourRenderingIndex result;
  result.source = source_cct;
  result.reference = kind;
  result.duv_within_cie_limit = std::abs(source_cct.duv) <= kCri_MaxDuv;

  // von Kries adaptation of the test source to the reference (CIE 13.3 eq. 5): in (c, d) each sample is scaled
  // by the ratio of the whites, c' = (c_r/c_k)·c_i, d' = (d_r/d_k)·d_i, then mapped back to (u, v). The test
  // white itself lands exactly on the reference white (u_r, v_r).
  const double c_ratio = c_of(reference) / c_of(source);
  const double d_ratio = d_of(reference) / d_of(source);

  double sum_r1_r8 = 0.0;
  for (size_t i = 0; i < samples_.size(); ++i) {
    const UvY under_reference = uvy_of(reflectance_xyz(samples_[i], reference_spectrum, observer_, grid));
    const UvY under_test = uvy_of(reflectance_xyz(samples_[i], test_source, observer_, grid));

    const double c = c_ratio * c_of(under_test), d = d_ratio * d_of(under_test);
    const double denominator = 16.518 + 1.481 * c - d;
    const UvY adapted{(10.872 + 0.404 * c - 4.0 * d) / denominator, 5.520 / denominator, under_test.y};

    const Uvw r = uvw_of(under_reference, reference.u, reference.v);
    const Uvw t = uvw_of(adapted, reference.u, reference.v);
    const double delta_e = std::sqrt((r.u - t.u) * (r.u - t.u) + (r.v - t.v) * (r.v - t.v) + (r.w - t.w) * (r.w - t.w));
    // CIE 13.3 eq. (8): R_i = 100 − 4.6·ΔE_i. The factor 4.6 made the Ra of the old standard warm-white
    // fluorescent lamp 50.
    result.special[i] = 100.0 - 4.6 * delta_e;
    if (i < 8) sum_r1_r8 += result.special[i];
  }
  result.ra = sum_r1_r8 / 8.0;
  return result;
}

ColourRenderingIndex colour_rendering_index(const Spectrum& test_source, SpectralLibrary& library) {
  return ColourRenderingEvaluator(library).evaluate(test_source);
}

}  // namespace rimu
