// The precomputed table of smoothest spectra over the knot gamut, for one white.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "spectral/upsampling/knot_gamut.h"
#include "spectral/upsampling/upsampling_knots.h"

namespace rimu {

/// Smoothest spectra (smoothest_spectrum.h) on a polar grid over the knot gamut of one white.
///
/// Grid: `angle_count` angles θ_a = 2π a / angle_count around the white, times `radius_count` relative radii
/// ρ_r = 1 − (1 − r/(radius_count − 1))², dense towards the boundary where spectra change fastest. ρ is relative
/// to `usable_fraction` of the hull radius (KnotGamut), so ρ = 1 keeps a margin from the hull, where the smoothest
/// spectrum degenerates into two hats. The polar grid has no entry outside the gamut (nothing is "invalid"); the
/// row ρ = 0 is the white itself, stored exactly flat.
///
/// Per entry: the spectrum scaled to a maximum of 1, quantised to 16 bits (the run time re-imposes the exact
/// colour, so quantisation only perturbs the shape by ≤ 8e-6 of the maximum), and the luminance Y of that
/// max-1 spectrum: the brightness limit of a reflectance with this chromaticity (Meng et al. 2015, section 4.2).
///
/// File format (little-endian): "RIMUUPS1"; uint32 angle_count, radius_count, knot_count (95), hull_count;
/// float64 white x, y, usable_fraction; char[16] white name; float64 hull (x, y) × hull_count; float32 limits ×
/// entries; uint16 shapes × entries × 95. Entries run over angle (outer), then radius.
struct UpsamplingTable {
  std::string white_name;  ///< e.g. "d65"
  Chromaticity white;
  double usable_fraction = 0.995;
  int angle_count = 0, radius_count = 0;
  std::vector<Chromaticity> hull;       ///< the KnotGamut vertices the table was made on
  std::vector<float> luminance_limits;  ///< Y of the max-1 spectrum, per entry
  std::vector<uint16_t> shapes;         ///< 65535 = 1, per entry × knot

  /// ρ of radius row `r`.
  double radius_of_row(int r) const;
  /// Entry index of grid point (angle a, radius r).
  size_t entry(int a, int r) const { return size_t(a) * radius_count + r; }
  /// The knot spectrum with luminance Y ≈ 1 at (θ, ρ ∈ [0,1]): bilinear interpolation of the four surrounding
  /// entries, each first scaled to Y = 1. Its colour is close to, not exactly, the grid point's (the caller
  /// corrects it).
  KnotValues interpolate(double angle_rad, double relative_radius) const;
  /// The gamut the table's polar coordinates refer to.
  KnotGamut gamut() const { return KnotGamut(white, hull); }

  /// Reads a table; throws InputError naming the file on a bad magic number, size or value.
  static UpsamplingTable read(const std::filesystem::path& path);
  /// Writes the table (the generator's output).
  void write(const std::filesystem::path& path) const;
};

}  // namespace rimu
