// ASTM E308-15 tristimulus weighting factors for 10 nm and 20 nm data, computed as ASTM E2022-11 prescribes.
//
// Summing 10 nm data at 10 nm misses the shape of the CMFs between the samples. E308 instead assumes the data
// between two samples follow the Lagrange polynomial through their neighbours (cubic through four samples inside
// the range, quadratic through three in the first and last interval), so the 1 nm sum
//   X = k Σ_λ R(λ) S(λ) x̄(λ),   R(λ) = Σ_j L_j(λ) R_j
// becomes X = Σ_j R_j W_x,j with W_x,j = k Σ_λ L_j(λ) S(λ) x̄(λ) over the 1 nm CIE tables. These are the weights of
// E308's Table 6 ("for use with spectral data corrected for bandpass"). E308's Table 5 is for data that were NOT
// corrected: an instrument whose triangular bandpass equals the interval reports R_i ≈ R(λ_i) + (Δ²/12) R''(λ_i),
// and Table 5 folds the correction of that into the weights (e308_table5_from_table6()).
#pragma once

#include <string>
#include <vector>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/io/csv_table.h"
#include "spectral/colorimetry/observer.h"
#include "spectral/spectra/spectrum.h"

namespace rimu {

class TabulatedSpectrum;

/// The shortest coverage E308 data must have here: ISO 13655:2017 (spectral measurement for graphic arts) asks
/// for 380-730 nm at 10 nm, the range of common 10 nm instruments and of the BabelColor ColorChecker data.
/// E308 folds the weights of unmeasured wavelengths into the end samples (§7.3.2), i.e. assumes the end value
/// continues. The weights below 400 nm are small (0.09 % of Z under D50, 2°, data/e308/), but that tail is where
/// optical brighteners and blue samples change fastest, so data starting later than 380 nm are refused rather
/// than silently extended.
inline constexpr double kE308LatestStart_nm = 380.0;
inline constexpr double kE308EarliestEnd_nm = 730.0;

/// Which of E308's two weight tables: Table 6 for spectral data corrected for the instrument's bandpass (or
/// measured with a bandpass much narrower than the interval), Table 5 for uncorrected data from an instrument
/// whose (triangular) bandpass equals the measurement interval, the common 10 nm spectrophotometer.
enum class E308Table { table6_bandpass_corrected, table5_uncorrected };

/// 6 or 5.
int e308_table_number(E308Table table);
/// e.g. "ASTM E308 Table 6 (weights for spectral data corrected for bandpass)": what every report prints.
std::string e308_table_description(E308Table table);

/// The Stearns & Stearns (1988) bandpass correction coefficient E308 uses: R'_i = (1 + 2α) R_i − α (R_i−1 + R_i+1),
/// R'_1 = (1 + α) R_1 − α R_2 at the ends. α = 0.083 ≈ 1/12, the second-moment ratio of a triangle as wide as
/// the interval (a triangle of half-width Δ blurs a parabola by Δ²/12 · R'').
inline constexpr double kStearnsAlpha = 0.083;

/// Weighting factors W_x, W_y, W_z at first_nm + j·interval_nm, normalised so that Σ W_y = 100 (the perfect
/// reflecting diffuser has Y = 100).
struct E308WeightTable {
  std::string illuminant;  ///< e.g. "D50"
  std::string observer;    ///< e.g. "CIE 1931 2°"
  double first_nm = 360.0;
  double interval_nm = 10.0;
  std::vector<Xyz> weights;

  double wavelength_nm(size_t j) const { return first_nm + double(j) * interval_nm; }
  double last_nm() const { return wavelength_nm(weights.size() - 1); }
};

/// The E2022 Lagrange coefficients of the samples around a 1 nm point at fraction r ∈ (0, 1) of an interval:
/// `points` (3 or 4) returned for samples j0 … j0+points−1 (see astm_e308.cpp for which).
std::vector<double> e308_lagrange_coefficients(int points, double position);

/// Evenly spaced data (e.g. a 5 nm illuminant) at every whole nanometre of its range, by the same Lagrange
/// polynomials: cubic through the two samples either side, quadratic in the first and last interval. This is how
/// E308's 1 nm illuminants that the CIE tabulates only at 5 nm (D55, D75, the F series) must have been made: their
/// published white points come out within 6.1e-4 of the printed 3 decimals this way (Y = 100), while linear
/// interpolation misses them by up to 0.12 (F7 Z).
/// Throws InputError if the data are not evenly spaced on whole nanometres or have fewer than 3 samples.
TabulatedSpectrum e308_interpolate_to_1nm(const TabulatedSpectrum& data);

/// Computes the weights from an illuminant and observer at 1 nm over [first_nm, last_nm] (E308 uses 360-830 nm;
/// for 20 nm the grid ends at 820 nm). `illuminant` is evaluated at whole nanometres: pass the CIE 1 nm tables.
E308WeightTable compute_e308_weights(const Spectrum& illuminant, const Observer& observer, double interval_nm,
                                     const std::string& illuminant_name, double first_nm = 360.0,
                                     double last_nm = 830.0);

/// E308-15 §7.3.2: for data measured over a shorter range [first_nm, last_nm] (on the table's grid), the weights
/// at wavelengths without data are added to the weights of the first and last measured wavelength.
E308WeightTable fold_e308_weights(const E308WeightTable& table, double first_nm, double last_nm);

/// Σ_j R_j W_j for data on the table's grid. Throws InputError (naming the data) if the spacing differs from the
/// table's, the data start after 380 nm or end before 730 nm (the tails E308 needs), or do not sit on the grid.
Xyz apply_e308_weights(const TabulatedSpectrum& data, const E308WeightTable& table);

/// Table 5 from Table 6 on the same grid: X = Σ W6_i R'_i with R' the Stearns-corrected data is Σ W5_i R_i with
/// W5 = Tᵀ W6, T the correction matrix above. T is symmetric, so W5_i = (1 + 2α) W6_i − α (W6_i−1 + W6_i+1) and
/// (1 + α) W6_1 − α W6_2 at the ends; every column of T sums to 1, so the white point (Σ W) is unchanged.
E308WeightTable e308_table5_from_table6(const E308WeightTable& table6);

/// The Stearns & Stearns correction of evenly spaced data (the formula above), for data measured with a
/// triangular bandpass as wide as their interval. Throws InputError for fewer than 2 samples.
TabulatedSpectrum stearns_bandpass_correction(const TabulatedSpectrum& data);

/// The table as CSV (wavelength_nm,Wx,Wy,Wz), preceded by '#' lines of `comment` (the generating command).
std::string e308_weights_csv(const E308WeightTable& table, const std::string& comment);
/// Reads a table written by e308_weights_csv(); throws InputError on a malformed or unevenly spaced file.
E308WeightTable e308_weights_from_csv(const CsvTable& csv, const std::string& illuminant, const std::string& observer);

}  // namespace rimu
