// The Planckian locus in CIE 1960 UCS and correlated colour temperature (CCT) with Duv, after Ohno (2013).
#pragma once

#include <vector>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/colorimetry/observer.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

/// Whether a CCT/Duv pair is meaningful. Outside `ok` the numbers are still defined (never NaN), but they
/// describe the nearest end of the tabulated locus or a point too far from it for "colour temperature" to mean
/// anything, so a caller must not present them as a CCT.
enum class CctValidity {
  ok,
  below_range,     ///< nearest locus point is at the low end (1000 K): cct_k = 1000, duv = distance to that point
  above_range,     ///< nearest locus point is at the high end (25000 K): cct_k = 25000, duv likewise
  far_from_locus,  ///< |Duv| > 0.05: CCT is computed but ill-defined (Ohno 2013 and CIE 15 limit it to 0.05)
};

/// "ok", "below 1000 K", "above 25000 K" or "|Duv| > 0.05": how every report names a CctValidity.
const char* cct_validity_name(CctValidity validity);

/// Correlated colour temperature and distance from the Planckian locus in CIE 1960 (u, v).
struct CctDuv {
  double cct_k = 0.0;
  /// Signed distance in (u, v) from the locus: positive above it (greenish), negative below (pinkish),
  /// following Ohno (2013) and ANSI C78.377.
  double duv = 0.0;
  CctValidity validity = CctValidity::ok;
  bool valid() const { return validity == CctValidity::ok; }
};

/// The blackbody locus of one observer, with the inverse map (u, v) -> (CCT, Duv).
///
/// uv_at(T) integrates Planck's law (SI 2019 constants, so c2 = hc/k = 1.438777e-2 m·K) against the observer,
/// by default at 1 nm over 360-830 nm (CIE 15:2004 §7.1). cct_duv() follows Ohno, "Practical use and calculation
/// of CCT and Duv", LEUKOS 10(1):47-55 (2013): a precomputed table in 1 % temperature steps from 1000 K to
/// 25000 K locates the nearest locus point, three cascade levels of exact locus points narrow the step to
/// 0.008 %, and the triangular solution (|Duv| < 0.002) or the parabolic one (otherwise) interpolates between
/// the last three.
/// Measured against points built on the locus normal (tests/spectral/cct_test.cpp): CCT within 0.011 K (worst
/// just inside the triangular range, |Duv| ~ 0.0019, near 24000 K) and Duv within 3e-9, over 1000-25000 K and
/// |Duv| <= 0.05. Ohno's 1 % table alone, without the cascade, gives ~1 K.
///
/// Construction costs 325 locus evaluations (~5 ms); cct_duv() 33 more (~0.5 ms). Not for the per-sample loop.
class PlanckianLocus {
 public:
  static constexpr double kMinCct_k = 1000.0;
  static constexpr double kMaxCct_k = 25000.0;
  static constexpr double kMaxAbsDuv = 0.05;

  /// Builds the table for `observer` summed over `grid` (the observer's values are copied: no reference is kept).
  /// The grid matters at the 1e-6 level in (u, v): a source's CCT on the 5 nm abridged locus differs from the one
  /// on the 1 nm locus by 0.03 K at 2856 K and 1.4 K at 6500 K (measured with A and D65; a kelvin is a smaller
  /// step in (u, v) the hotter the source).
  explicit PlanckianLocus(const Observer& observer, IntegrationGrid grid = IntegrationGrid::cie_1nm());

  /// CIE 1960 (u, v) of a black body at `temperature_k` (any T > 0).
  Uv1960 uv_at(double temperature_k) const;
  /// Unit normal to the locus at `temperature_k`, pointing to +Duv (increasing v side). Used to build points
  /// at a known Duv: uv_at(T) + duv·normal_at(T).
  Uv1960 normal_at(double temperature_k) const;
  /// CCT and Duv of a chromaticity (see CctValidity for what happens off the table or far from the locus).
  CctDuv cct_duv(Uv1960 uv) const;
  /// CIE 1931 (x, y) of the point `duv` off the locus at `temperature_k` along its normal (CCT -> xy, the
  /// inverse of cct_duv within its accuracy).
  Chromaticity chromaticity_at(double temperature_k, double duv = 0.0) const;

 private:
  struct Node {
    double temperature_k;
    Uv1960 uv;
    double distance;  // to the query point, filled during a search
  };
  std::vector<double> wavelengths_nm_;          // the integration grid's wavelengths
  std::vector<double> x_bar_, y_bar_, z_bar_;  // the observer at those wavelengths
  std::vector<Node> table_;                    // 1 % steps from kMinCct_k to kMaxCct_k
};

/// CCT and Duv of a light source's spectrum under `observer` (1 nm over 360-830 nm, CIE 15:2004 §7.1).
/// Builds a PlanckianLocus each call: hold one and use cct_duv() when computing many.
CctDuv cct_duv_of(const Spectrum& source, const Observer& observer);

}  // namespace rimu
