// The whites Rimu has upsampling tables for, and the illuminant spectrum behind each.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {

/// One white: the colour spaces whose white chromaticity is `white` share its table.
struct UpsamplingWhite {
  std::string name;         ///< "e", "d65", "aces"
  Chromaticity white;       ///< as the colour spaces state it (rgb_colour_space.cpp)
  std::string illuminant;   ///< which spectrum stands for it, in words
};

/// E (CIE RGB), D65 (sRGB, Rec.2020, Display P3) and the ACES white (ACEScg, ACES2065-1).
const std::vector<UpsamplingWhite>& upsampling_whites();

/// The white whose chromaticity is within 1e-5 of `white`; throws InputError naming the known whites if none is.
const UpsamplingWhite& upsampling_white_for(Chromaticity white);

/// The illuminant spectrum of `white` (relative power): CIE E; CIE D65 (1 nm table); for the ACES white, CIE
/// daylight at 6000 K × 1.4388/1.4380 (the second radiation constant revised since D60 was defined), which is how
/// the Academy derived (0.32168, 0.33767) (Academy TB-2018-001).
TabulatedSpectrum upsampling_illuminant(SpectralLibrary& library, const UpsamplingWhite& white);

/// Path of the table of `white`, relative to the data root: "upsampling/smooth_<name>.bin".
std::filesystem::path upsampling_table_file(const UpsamplingWhite& white);

}  // namespace rimu
