// A colour-matching observer: three response curves x̄, ȳ, z̄.
#pragma once

#include <string>

#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

/// The three lane values of an observer's (or a camera's) response at four wavelengths.
struct Response4 {
  Float4 x, y, z;
};

/// A CIE standard observer (or any three-channel response, e.g. a camera's R, G, B sensitivities).
struct Observer {
  std::string name;  ///< e.g. "CIE 1931 2°"
  TabulatedSpectrum x_bar, y_bar, z_bar;

  /// The three curves at four wavelengths (per-sample path; no allocation).
  Response4 sample(const SampledWavelengths& lambda) const {
    return {x_bar.sample(lambda), y_bar.sample(lambda), z_bar.sample(lambda)};
  }
};

}  // namespace rimu
