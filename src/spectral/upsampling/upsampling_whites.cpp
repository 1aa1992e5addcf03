#include "spectral/upsampling/upsampling_whites.h"

#include <cmath>

#include "spectral/error.h"

namespace rimu {

const std::vector<UpsamplingWhite>& upsampling_whites() {
  // The chromaticities repeat those in rgb_colour_space.cpp (ITU-R BT.709-6; SMPTE ST 2065-1; CIE E), which the
  // run time matches against RgbColourSpace::white().
  static const std::vector<UpsamplingWhite> whites = {
      {"e", {1.0 / 3.0, 1.0 / 3.0}, "CIE illuminant E"},
      {"d65", {0.3127, 0.3290}, "CIE D65 (1 nm table)"},
      {"aces", {0.32168, 0.33767}, "CIE daylight at 6000 K x 1.4388/1.4380 (ACES white, Academy TB-2018-001)"},
  };
  return whites;
}

const UpsamplingWhite& upsampling_white_for(Chromaticity white) {
  for (const UpsamplingWhite& w : upsampling_whites())
    if (std::abs(w.white.x - white.x) <= 1e-5 && std::abs(w.white.y - white.y) <= 1e-5) return w;
  throw InputError({}, "no RGB upsampling table for a colour space with white (" + std::to_string(white.x) + ", " +
                           std::to_string(white.y) +
                           "); tables exist for E (1/3, 1/3), D65 (0.3127, 0.3290) and ACES (0.32168, 0.33767)");
}

TabulatedSpectrum upsampling_illuminant(SpectralLibrary& library, const UpsamplingWhite& white) {
  if (white.name == "aces") return daylight_spectrum(library.daylight_basis(), 6000.0 * 1.4388 / 1.4380);
  const SpectrumPtr s = library.illuminant(white.name == "e" ? "E" : "D65");
  return *std::dynamic_pointer_cast<const TabulatedSpectrum>(s);
}

std::filesystem::path upsampling_table_file(const UpsamplingWhite& white) {
  return std::filesystem::path("upsampling") / ("smooth_" + white.name + ".bin");
}

}  // namespace rimu
