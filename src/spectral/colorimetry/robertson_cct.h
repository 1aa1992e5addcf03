// Correlated colour temperature by Robertson's (1968) isotemperature lines, beside Ohno's (2013) method.
#pragma once

#include <vector>

#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colorimetry/planckian_locus.h"

namespace rimu {

class CsvTable;

/// One of Robertson's isotemperature lines: the CIE 1960 (u, v) of the Planckian locus at a reciprocal temperature
/// and the slope dv/du of the line through it, perpendicular to the locus there.
struct IsotemperatureLine {
  double reciprocal_temperature_per_mk = 0.0;  ///< 10^6 / T
  Uv1960 uv;
  double slope = 0.0;
};

/// Robertson, "Computation of correlated color temperature and distribution temperature", JOSA 58(11):1528 (1968),
/// with the table of Wyszecki & Stiles (1982) Table 1(3.11): 31 isotemperature lines from 0 to 600 MK⁻¹
/// (infinity to 1667 K) for the CIE 1931 2° observer. A point's CCT interpolates, in reciprocal temperature, between
/// the two lines it falls between, by its signed perpendicular distances to them.
///
/// Why offer it beside Ohno (2013): it is the method of older standards, software and camera raw converters (DNG's
/// white balance), and a colour scientist comparing numbers with them needs the same method. Its table lies on
/// today's Planckian locus (c2 = 1.438777e-2 m·K) within the rounding of its 5 decimals, so its temperatures are on
/// today's scale (the table's c2 was IPTS-68's 1.4388e-2, 0.0016 % away). What it gives up is the interpolation
/// between lines 10-25 MK⁻¹ apart: within 0.08 MK⁻¹ of the exact CCT for |Duv| <= 0.02 over 1700-25000 K
/// (0.5 K at 6500 K), where Ohno's cascade reaches 0.011 K (measured in tests/spectral/robertson_cct_test.cpp).
/// Duv is the signed distance along the interpolated isotemperature line from the interpolated locus point
/// (positive above the locus, Ohno's sign convention); the chord between two lines' locus points cuts inside the
/// curved locus, which bounds its error by the chord's sagitta, 1.03e-4 at worst (near 6100 K).
///
/// Cheap (31 lines, no locus evaluation): usable on image-sized arrays.
class RobertsonCct {
 public:
  /// The lines in increasing reciprocal temperature; throws InputError (naming the table and line) unless there are
  /// at least two, the reciprocal temperatures strictly increase from 0, and every value is finite.
  explicit RobertsonCct(std::vector<IsotemperatureLine> lines, const std::string& source = "isotemperature lines");
  /// The table as data/cmf/robertson_1968_isotemperature_lines.csv stores it (columns
  /// reciprocal_temperature_per_mk, u, v, slope); errors name the file and line.
  static RobertsonCct from_csv(const CsvTable& table);

  /// CCT (K) and Duv of a chromaticity. Below the last line (warmer than 1667 K for the published
  /// table) the answer is the last line's temperature, flagged `below_range`; a point beyond the first line (a
  /// "colder than infinity" blue) gets the first line's, flagged `above_range`; |Duv| > 0.05 is `far_from_locus`.
  /// Non-finite input: far_from_locus with zeros, as PlanckianLocus::cct_duv.
  CctDuv cct_duv(Uv1960 uv) const;

  const std::vector<IsotemperatureLine>& lines() const { return lines_; }

 private:
  std::vector<IsotemperatureLine> lines_;
};

}  // namespace rimu
