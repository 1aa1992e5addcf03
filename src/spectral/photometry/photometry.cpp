#include "spectral/photometry/photometry.h"

#include <cmath>

#include "spectral/error.h"
#include "spectral/colorimetry/photometry_constants.h"

namespace rimu {
namespace {

// K = K_m Σ S V Δλ / Σ S Δλ. Both sums use the same grid and the same rectangle rule as the colorimetric
// sums (colorimetry.h), so a spectrum's efficacy and its emission_xyz() Y agree exactly: Y = K · Σ S Δλ
// when V = ȳ.
LuminousEfficacy efficacy(const Spectrum& spectrum, const TabulatedSpectrum& response, double max_efficacy_lm_W,
                          const IntegrationGrid& grid, const char* which) {
  const double radiant = integrate_on_grid(grid, [&](double l) { return spectrum.value(l); });
  if (!(radiant > 0.0) || !std::isfinite(radiant))
    throw InputError({}, std::string("cannot compute the ") + which + " luminous efficacy of '" +
                             spectrum.describe() + "': its radiant integral over " + std::to_string(grid.start_nm) +
                             "-" + std::to_string(grid.end_nm) + " nm is " + std::to_string(radiant) +
                             " (it must be positive and finite)");
  const double weighted = integrate_on_grid(grid, [&](double l) { return spectrum.value(l) * response.value(l); });
  if (!(weighted > 0.0))
    throw InputError({}, std::string("cannot compute the ") + which + " luminous efficacy of '" +
                             spectrum.describe() + "': it has no power where " + response.describe() +
                             " is non-zero, so a luminous quantity cannot fix its radiant scale");
  return LuminousEfficacy(max_efficacy_lm_W * weighted / radiant);
}

}  // namespace

LuminousEfficacy luminous_efficacy_of_radiation_lm_W(const Spectrum& spectrum, const TabulatedSpectrum& v,
                                                     IntegrationGrid grid) {
  return efficacy(spectrum, v, kMaxLuminousEfficacy_lm_W, grid, "photopic");
}

LuminousEfficacy scotopic_luminous_efficacy_lm_W(const Spectrum& spectrum, const TabulatedSpectrum& v_prime,
                                                 IntegrationGrid grid) {
  return efficacy(spectrum, v_prime, kMaxScotopicLuminousEfficacy_lm_W, grid, "scotopic");
}

double melanopic_daylight_efficacy_ratio(const Spectrum& spectrum, const TabulatedSpectrum& v,
                                         const TabulatedSpectrum& s_mel, IntegrationGrid grid) {
  // Both efficacies share the radiant sum, so K_mel / K = Σ S s_mel / (K_m Σ S V) without it.
  const double photopic_lm_W = luminous_efficacy_of_radiation_lm_W(spectrum, v, grid).lm_W;
  const double radiant = integrate_on_grid(grid, [&](double l) { return spectrum.value(l); });
  const double melanopic = integrate_on_grid(grid, [&](double l) { return spectrum.value(l) * s_mel.value(l); });
  return melanopic / radiant / photopic_lm_W / kMelanopicEfficacyD65_W_lm;
}

}  // namespace rimu
