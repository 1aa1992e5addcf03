#include "spectral/library/tabulated_colorimetry.h"

#include <cmath>

#include "spectral/colorimetry/astm_e308.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/error.h"

namespace rimu {
namespace {

void require_even_spacing(const TabulatedSpectrum& s) {
  if (!uniform_interval_nm(s))
    throw InputError({}, "'" + s.describe() + "' is not evenly spaced, so it has no native summation interval; "
                         "use --method 1nm");
}

bool inside_cmf_range(double nm) { return nm >= kCmfFirst_nm - 1e-9 && nm <= kCmfLast_nm + 1e-9; }

/// Σ over the data's wavelengths in the CMF range of weight(λ)·(x̄, ȳ, z̄)(λ).
template <typename F>
Xyz native_sum(const TabulatedSpectrum& data, const Observer& o, F&& weight) {
  Xyz sum;
  for (double nm : data.wavelengths_nm()) {
    if (!inside_cmf_range(nm)) continue;
    const double w = weight(nm);
    sum.x += w * o.x_bar.value(nm);
    sum.y += w * o.y_bar.value(nm);
    sum.z += w * o.z_bar.value(nm);
  }
  return sum;
}

Xyz scaled_to_y100(const Xyz& raw) {
  if (raw.y == 0.0) return {};
  const double k = 100.0 / raw.y;
  return {k * raw.x, 100.0, k * raw.z};
}

/// A table with the data's wavelengths and value 1: the perfect diffuser sampled like the data.
TabulatedSpectrum unit_like(const TabulatedSpectrum& data) {
  return TabulatedSpectrum(data.wavelengths_nm(), std::vector<double>(data.wavelengths_nm().size(), 1.0),
                           Extrapolation::clamp, "perfect diffuser");
}

}  // namespace

Xyz light_xyz(const TabulatedSpectrum& light, StandardObserver observer, TristimulusMethod method,
              SpectralLibrary& library, E308Table e308_table) {
  const Observer& o = library.observer(observer);
  switch (method) {
    case TristimulusMethod::native:
      require_even_spacing(light);
      return scaled_to_y100(native_sum(light, o, [&](double nm) { return light.value(nm); }));
    case TristimulusMethod::interpolate_1nm:
      return illuminant_xyz(light, o, IntegrationGrid::cie_1nm());
    case TristimulusMethod::astm_e308: {
      const auto step = uniform_interval_nm(light);
      const E308WeightTable& weights = library.e308_weights("E", observer, step ? *step : 0.0, e308_table);
      return scaled_to_y100(apply_e308_weights(light, weights));
    }
  }
  return {};
}

Xyz reflectance_xyz(const TabulatedSpectrum& reflectance, std::string_view illuminant, StandardObserver observer,
                    TristimulusMethod method, SpectralLibrary& library, E308Table e308_table) {
  const Observer& o = library.observer(observer);
  switch (method) {
    case TristimulusMethod::native: {
      require_even_spacing(reflectance);
      const SpectrumPtr s = library.illuminant(illuminant);
      const double white_y = native_sum(reflectance, o, [&](double nm) { return s->value(nm); }).y;
      if (white_y == 0.0) return {};
      const Xyz raw = native_sum(reflectance, o, [&](double nm) { return reflectance.value(nm) * s->value(nm); });
      const double k = 100.0 / white_y;
      return {k * raw.x, k * raw.y, k * raw.z};
    }
    case TristimulusMethod::interpolate_1nm:
      return reflectance_xyz(reflectance, *library.illuminant(illuminant), o, IntegrationGrid::cie_1nm());
    case TristimulusMethod::astm_e308: {
      const auto step = uniform_interval_nm(reflectance);
      return apply_e308_weights(reflectance, library.e308_weights(illuminant, observer, step ? *step : 0.0, e308_table));
    }
  }
  return {};
}

Xyz perfect_diffuser_xyz(const TabulatedSpectrum& reflectance, std::string_view illuminant,
                         StandardObserver observer, TristimulusMethod method, SpectralLibrary& library,
                         E308Table e308_table) {
  return reflectance_xyz(unit_like(reflectance), illuminant, observer, method, library, e308_table);
}

}  // namespace rimu
