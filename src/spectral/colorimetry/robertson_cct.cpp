#include "spectral/colorimetry/robertson_cct.h"

#include <cmath>
#include <limits>

#include "spectral/io/csv_table.h"
#include "spectral/error.h"

namespace rimu {
namespace {

/// Unit vector along an isotemperature line of slope dv/du, oriented to increasing v (+Duv): every line of the
/// table has a negative slope, so that is the direction of decreasing u.
Uv1960 line_direction(double slope) {
  const double length = std::sqrt(1.0 + slope * slope);
  return {-1.0 / length, -slope / length};
}

/// Robertson's d_i: the signed perpendicular distance of `p` from the line, (v - v_i) - t_i (u - u_i) over
/// sqrt(1 + t_i²). With the table's negative slopes it is positive on the warm side of the line (larger u), so
/// walking the lines from infinity (0 MK⁻¹) towards 1667 K it changes sign once, where the point is passed.
double distance_to_line(const IsotemperatureLine& line, Uv1960 p) {
  return ((p.v - line.uv.v) - line.slope * (p.u - line.uv.u)) / std::sqrt(1.0 + line.slope * line.slope);
}

}  // namespace

RobertsonCct::RobertsonCct(std::vector<IsotemperatureLine> lines, const std::string& source) : lines_(std::move(lines)) {
  if (lines_.size() < 2) throw InputError(SourceLocation{source, 0, ""}, "expected at least two isotemperature lines");
  for (size_t i = 0; i < lines_.size(); ++i) {
    const IsotemperatureLine& l = lines_[i];
    if (!std::isfinite(l.reciprocal_temperature_per_mk) || !std::isfinite(l.uv.u) || !std::isfinite(l.uv.v) ||
        !std::isfinite(l.slope))
      throw InputError(SourceLocation{source, 0, ""}, "isotemperature line " + std::to_string(i + 1) + " is not finite");
    if (i == 0 ? l.reciprocal_temperature_per_mk < 0.0
               : !(l.reciprocal_temperature_per_mk > lines_[i - 1].reciprocal_temperature_per_mk))
      throw InputError(SourceLocation{source, 0, ""}, "isotemperature line " + std::to_string(i + 1) +
                                                   ": reciprocal temperatures must start at 0 or more and increase");
  }
}

RobertsonCct RobertsonCct::from_csv(const CsvTable& table) {
  const std::vector<double> mired = table.numbers(table.column_index("reciprocal_temperature_per_mk"));
  const std::vector<double> u = table.numbers(table.column_index("u"));
  const std::vector<double> v = table.numbers(table.column_index("v"));
  const std::vector<double> slope = table.numbers(table.column_index("slope"));
  std::vector<IsotemperatureLine> lines;
  for (size_t i = 0; i < mired.size(); ++i) {
    if (i > 0 && !(mired[i] > mired[i - 1]))
      throw InputError(SourceLocation{table.name(), table.line_of_row(i), ""},
                       "reciprocal temperatures must increase from row to row");
    lines.push_back({mired[i], {u[i], v[i]}, slope[i]});
  }
  return RobertsonCct(std::move(lines), table.name());
}

CctDuv RobertsonCct::cct_duv(Uv1960 uv) const {
  if (!std::isfinite(uv.u) || !std::isfinite(uv.v)) return {0.0, 0.0, CctValidity::far_from_locus};

  // The first pair of neighbouring lines whose distances change sign holds the point between them.
  double previous = distance_to_line(lines_[0], uv);
  size_t i = 1;
  double current = 0.0;
  for (; i < lines_.size(); ++i) {
    current = distance_to_line(lines_[i], uv);
    if ((previous < 0.0) != (current < 0.0) || current == 0.0) break;
    previous = current;
  }
  auto temperature_of = [](double reciprocal_per_mk) {
    return reciprocal_per_mk > 0.0 ? 1e6 / reciprocal_per_mk : std::numeric_limits<double>::max();
  };
  if (i == lines_.size()) {
    // No sign change: the point lies beyond one end. Still on the warm side of the last line (d > 0): warmer than
    // the table reaches; on the cold side of every line: bluer than the infinite-temperature line.
    const IsotemperatureLine& end = previous > 0.0 ? lines_.back() : lines_.front();
    const Uv1960 along = line_direction(end.slope);
    const double duv = (uv.u - end.uv.u) * along.u + (uv.v - end.uv.v) * along.v;
    return {temperature_of(end.reciprocal_temperature_per_mk), duv,
            previous > 0.0 ? CctValidity::below_range : CctValidity::above_range};
  }

  // Robertson's interpolation: the fraction of the way from line i-1 to line i at which the distance vanishes,
  // applied to the reciprocal temperature, the locus point and the line's direction.
  const IsotemperatureLine& a = lines_[i - 1];
  const IsotemperatureLine& b = lines_[i];
  const double f = previous / (previous - current);
  const double reciprocal = a.reciprocal_temperature_per_mk + f * (b.reciprocal_temperature_per_mk - a.reciprocal_temperature_per_mk);
  const Uv1960 on_locus{a.uv.u + f * (b.uv.u - a.uv.u), a.uv.v + f * (b.uv.v - a.uv.v)};
  const Uv1960 da = line_direction(a.slope), db = line_direction(b.slope);
  Uv1960 along{da.u + f * (db.u - da.u), da.v + f * (db.v - da.v)};
  const double length = std::hypot(along.u, along.v);
  along = {along.u / length, along.v / length};
  const double duv = (uv.u - on_locus.u) * along.u + (uv.v - on_locus.v) * along.v;
  return {temperature_of(reciprocal), duv,
          std::abs(duv) > PlanckianLocus::kMaxAbsDuv ? CctValidity::far_from_locus : CctValidity::ok};
}

}  // namespace rimu
