// IES LM-63 photometric files (the 1986, 1991, 1995 and 2002 editions): a luminaire's candela table as measured
// on a goniophotometer. Layout (ANSI/IES LM-63-2002, section 5):
//   IESNA:LM-63-2002                      (version line; absent in 1986 files)
//   [KEYWORD] text                        (any number: [TEST], [MANUFAC], [LUMCAT], ...)
//   TILT=NONE | TILT=INCLUDE | TILT=<file>
//   [if INCLUDE: lamp-to-luminaire geometry, pair count N, N tilt angles, N multipliers]
//   #lamps  lumens/lamp (−1: absolute photometry)  candela multiplier  #vertical  #horizontal
//   photometric type (1 = C, 2 = B, 3 = A)  units (1 = feet, 2 = metres)  width  length  height
//   ballast factor  future use (1995: ballast-lamp photometric factor)  input watts
//   vertical angles, horizontal angles, then the candela values: #vertical per horizontal angle
// After TILT the numbers are free-form (whitespace and line breaks anywhere). Rimu reads type C; the candela
// values it keeps are table × multiplier × ballast factor (× the 1995 ballast-lamp factor), and with
// TILT=INCLUDE × the tilt multiplier at 0° (the lamp as it was measured; Rimu does not tilt lamps).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "transport/lights/candela_distribution.h"

namespace rimu {

struct IesPhotometry {
  std::string name;     ///< the file, for messages
  std::string version;  ///< the first line ("IESNA:LM-63-2002"), or "LM-63-1986" when absent
  std::vector<std::pair<std::string, std::string>> keywords;  ///< in file order, e.g. {"MANUFAC", "Acme"}
  std::string tilt = "NONE";                                  ///< NONE or INCLUDE
  double tilt_factor = 1.0;                                   ///< the TILT=INCLUDE multiplier at 0°
  int lamp_count = 1;
  double lumens_per_lamp = -1.0;  ///< −1: absolute photometry (no rated lamp lumens)
  double candela_multiplier = 1.0;
  int photometric_type = 1;  ///< 1 = C, 2 = B, 3 = A
  int units_type = 2;        ///< 1 = feet, 2 = metres (of the luminous opening below)
  double width = 0, length = 0, height = 0;
  double ballast_factor = 1.0, ballast_lamp_factor = 1.0, input_watts = 0.0;
  std::vector<double> vertical_deg, horizontal_deg;  ///< as in the file
  std::vector<double> candela;  ///< [horizontal][vertical], all factors above applied

  /// The rated lumens of all lamps, or 0 for absolute photometry.
  double rated_lamp_lumens() const { return lumens_per_lamp > 0 ? lamp_count * lumens_per_lamp : 0.0; }
};

/// Parses LM-63 text. Throws InputError "name:line: ..." for a malformed file: missing TILT line, wrong or
/// non-numeric values, counts that do not match, non-monotonic angles, negative candela, a truncated table or
/// trailing values. Photometric types B and A, and TILT=<file>, are reported as unsupported.
IesPhotometry parse_ies(const std::string& text, const std::string& name);
/// Reads and parses a file (InputError if it cannot be opened).
IesPhotometry read_ies_file(const std::filesystem::path& path);

/// The candela table over the whole sphere: horizontal angles expanded by the file's symmetry (one angle: axial;
/// 0-90: quadrant; 0-180: bilateral about the 0-180° plane; 90-270: bilateral about the 90-270° plane; 0-360 or
/// less: full, closed at 360° with the 0° column), scaled by `scale`.
std::shared_ptr<const CandelaDistribution> candela_distribution(const IesPhotometry& ies, double scale = 1.0);

/// The full angle between the two directions in the C = 0° plane where the intensity falls to `fraction` of the
/// peak in that plane (beam angle for 0.5, field angle for 0.1, as IES defines them); 0 if it never does.
double ies_spread_angle_deg(const CandelaDistribution& table, double fraction);

}  // namespace rimu
