#include "render/reports/ies_report.h"

#include <array>
#include <cmath>
#include <vector>
#include <numbers>
#include <iomanip>
#include <sstream>

#include "render/output/plot_output.h"
#include "spectral/error.h"

namespace rimu {
namespace {

const char* symmetry_name(const IesPhotometry& ies) {
  const auto& h = ies.horizontal_deg;
  if (h.size() == 1) return "axially symmetric";
  if (h.front() == 90.0) return "bilateral about the 90-270° plane";
  if (h.back() == 90.0) return "quadrant symmetric (0-90°)";
  if (h.back() == 180.0) return "bilateral about the 0-180° plane (0-180°)";
  return "full (0-360°)";
}

std::string lumens_text(double lm) {
  std::ostringstream s;
  s << lm;
  return s.str();
}

}  // namespace

namespace {

// The numbers both report forms print.
struct IesSummary {
  double scale = 1, file_lumens = 0, efficacy_lumens = 0;  // efficacy_lumens: 0 = the total flux
  double peak_cd = 0, peak_gamma_deg = 0, peak_c_deg = 0;
  double lumens = 0, watts = 0, beam_deg = 0, field_deg = 0, intensity_at_point_cd = 0, on_axis_cd = 0;
  std::vector<double> plane_gamma_deg;
  std::array<std::vector<double>, 4> plane_cd;  // C 0°, 90°, 180°, 270°
};

constexpr std::array<double, 4> kPlaneCDeg{0.0, 90.0, 180.0, 270.0};

IesSummary summarise(const IesPhotometry& ies, const InspectPoint& point, std::optional<double> luminaire_lumens) {
  validate_inspect_point(point);
  IesSummary r;
  r.file_lumens = candela_distribution(ies)->integral_sr();
  if (luminaire_lumens) {
    if (!(*luminaire_lumens >= 1e-30 && *luminaire_lumens <= 1e30))
      throw InputError({"", 0, "--lumens"}, "expected a luminous flux in [1e-30, 1e30] lm");
    if (!(r.file_lumens > 0.0))
      throw InputError({ies.name, 0, ""}, "the candela table is all zero: it cannot be scaled to --lumens");
    r.scale = *luminaire_lumens / r.file_lumens;
  }
  const auto table = candela_distribution(ies, r.scale);
  for (size_t i = 0; i < ies.horizontal_deg.size(); ++i)
    for (size_t j = 0; j < ies.vertical_deg.size(); ++j)
      if (r.scale * ies.candela[i * ies.vertical_deg.size() + j] > r.peak_cd)
        r.peak_cd = r.scale * ies.candela[i * ies.vertical_deg.size() + j], r.peak_gamma_deg = ies.vertical_deg[j],
        r.peak_c_deg = ies.horizontal_deg[i];
  r.lumens = table->integral_sr();
  r.watts = point.electrical_w.value_or(ies.input_watts);
  // The file's input watts belong to the file's flux: scaled to other lumens, its efficacy is still the file's.
  r.efficacy_lumens = luminaire_lumens && !point.electrical_w ? r.file_lumens : 0.0;
  r.beam_deg = ies_spread_angle_deg(*table, 0.5);
  r.field_deg = ies_spread_angle_deg(*table, 0.1);
  const double angle = point.off_axis_deg;
  r.intensity_at_point_cd = table->intensity_deg(std::abs(angle), angle >= 0 ? 0.0 : 180.0);
  r.on_axis_cd = table->intensity_deg(0.0, 0.0);
  // The table's own γ range: beyond it the intensity is 0 by definition, not measured.
  for (double g = ies.vertical_deg.front(); g <= ies.vertical_deg.back() + 1e-9; g += kPlaneTableStepDeg) {
    r.plane_gamma_deg.push_back(g);
    for (size_t c = 0; c < kPlaneCDeg.size(); ++c) r.plane_cd[c].push_back(table->intensity_deg(g, kPlaneCDeg[c]));
  }
  const double illuminance_lx = r.intensity_at_point_cd / (point.distance_m * point.distance_m);
  for (double v : {r.peak_cd, r.lumens, r.lumens / (4.0 * std::numbers::pi), illuminance_lx, r.on_axis_cd,
                   r.watts > 0 ? r.lumens / r.watts : 0.0, ies.rated_lamp_lumens() > 0 ? r.lumens / ies.rated_lamp_lumens() : 0.0})
    if (!std::isfinite(v))
      throw InputError({ies.name, 0, ""}, "the candela values overflow: the total flux or a derived quantity is not a "
                                          "finite number");
  return r;
}

}  // namespace

std::string inspect_ies_text(const IesPhotometry& ies, const InspectPoint& point,
                             std::optional<double> luminaire_lumens) {
  const IesSummary r = summarise(ies, point, luminaire_lumens);
  std::ostringstream o;
  o << std::setprecision(6);
  o << "file: " << ies.name << " (" << ies.version << ")\n";
  for (const auto& [key, value] : ies.keywords) o << "  [" << key << "] " << value << "\n";
  o << "photometry: type C, " << symmetry_name(ies) << ", " << ies.vertical_deg.size() << " vertical × "
    << ies.horizontal_deg.size() << " horizontal angles, TILT=" << ies.tilt << "\n";
  o << "peak intensity: " << r.peak_cd << " cd (γ " << r.peak_gamma_deg << "°, C " << r.peak_c_deg << "°)\n";
  o << "total luminous flux: " << r.lumens << " lm (∫ I dω over the interpolated table)\n";
  if (luminaire_lumens)
    o << "scaled to " << *luminaire_lumens << " lm: the file's candela × " << r.scale << " (the file's table gives "
      << r.file_lumens << " lm)\n";
  if (ies.rated_lamp_lumens() > 0)
    o << "lamp lumens: " << ies.rated_lamp_lumens() << " lm (" << ies.lamp_count << " × " << ies.lumens_per_lamp
      << "); luminaire efficiency " << 100.0 * r.file_lumens / ies.rated_lamp_lumens() << " % (of the file)\n";
  else
    o << "lamp lumens: absolute photometry (-1)\n";
  if (r.watts > 0)
    o << "input power: " << r.watts << " W; luminaire efficacy " << (r.efficacy_lumens > 0 ? r.efficacy_lumens : r.lumens) / r.watts
      << " lm/W" << (r.efficacy_lumens > 0 ? " (of the file: its flux and input watts)" : "") << "\n";
  o << "beam angle (50 % of peak, C 0-180° plane): " << r.beam_deg << "°\n";
  o << "field angle (10 % of peak, C 0-180° plane): " << r.field_deg << "°\n";
  o << "at " << point.distance_m << " m, " << point.off_axis_deg << "° from the axis (C 0°): " << r.intensity_at_point_cd
    << " cd, " << r.intensity_at_point_cd / (point.distance_m * point.distance_m) << " lx on a surface facing the lamp\n";
  o << "on the axis (γ 0°, " << r.on_axis_cd << " cd), on a surface facing the lamp:";
  for (double d : kOnAxisDistancesM) o << (d > kOnAxisDistancesM[0] ? ", " : " ") << d << " m " << r.on_axis_cd / (d * d) << " lx";
  o << "\n";
  o << "average intensity: " << r.lumens / (4.0 * std::numbers::pi)
    << " cd (the isotropic point light of the same lumens)\n";
  // setw counts bytes: γ and ° are two bytes each in UTF-8, one column on screen.
  o << "intensity (cd) in the main planes:\n" << std::setw(9) << "γ";
  for (const char* c : {"C 0°", "C 90°", "C 180°", "C 270°"}) o << std::setw(13) << c;
  o << "\n";
  for (size_t k = 0; k < r.plane_gamma_deg.size(); ++k) {
    o << std::setw(7) << r.plane_gamma_deg[k] << "°";
    for (const auto& plane : r.plane_cd) o << std::setw(12) << plane[k];
    o << "\n";
  }
  return o.str();
}

nlohmann::json inspect_ies_json(const IesPhotometry& ies, const InspectPoint& point,
                                std::optional<double> luminaire_lumens) {
  const IesSummary r = summarise(ies, point, luminaire_lumens);
  nlohmann::json j;
  j["file"] = ies.name;
  j["format"] = ies.version;
  j["keywords"] = nlohmann::json::object();
  for (const auto& [key, value] : ies.keywords) j["keywords"][key] = value;
  j["symmetry"] = symmetry_name(ies);
  j["vertical_angle_count"] = ies.vertical_deg.size();
  j["horizontal_angle_count"] = ies.horizontal_deg.size();
  j["tilt"] = ies.tilt;
  j["peak_intensity_cd"] = r.peak_cd;
  j["peak_gamma_deg"] = r.peak_gamma_deg;
  j["peak_c_deg"] = r.peak_c_deg;
  j["total_luminous_flux_lm"] = r.lumens;
  j["file_luminous_flux_lm"] = r.file_lumens;
  j["candela_scale"] = r.scale;
  if (ies.rated_lamp_lumens() > 0) {
    j["rated_lamp_lumens_lm"] = ies.rated_lamp_lumens();
    j["luminaire_efficiency"] = r.file_lumens / ies.rated_lamp_lumens();
  }
  if (r.watts > 0)
    j["input_power_w"] = r.watts,
    j["luminaire_efficacy_lm_w"] = (r.efficacy_lumens > 0 ? r.efficacy_lumens : r.lumens) / r.watts;
  j["beam_angle_deg"] = r.beam_deg;
  j["field_angle_deg"] = r.field_deg;
  j["distance_m"] = point.distance_m;
  j["off_axis_deg"] = point.off_axis_deg;
  j["intensity_at_angle_cd"] = r.intensity_at_point_cd;
  j["illuminance_at_distance_lx"] = r.intensity_at_point_cd / (point.distance_m * point.distance_m);
  j["average_intensity_cd"] = r.lumens / (4.0 * std::numbers::pi);
  j["on_axis_intensity_cd"] = r.on_axis_cd;
  j["on_axis_illuminance"] = nlohmann::json::array();
  for (double d : kOnAxisDistancesM) j["on_axis_illuminance"].push_back({{"distance_m", d}, {"lx", r.on_axis_cd / (d * d)}});
  j["planes"] = {{"gamma_deg", r.plane_gamma_deg}, {"c0_cd", r.plane_cd[0]}, {"c90_cd", r.plane_cd[1]},
                 {"c180_cd", r.plane_cd[2]}, {"c270_cd", r.plane_cd[3]}};
  return j;
}

void plot_ies_polar_png(const IesPhotometry& ies, const std::filesystem::path& png,
                        std::optional<double> luminaire_lumens, const std::string& option) {
  check_plot_png(png, {"", 0, option});
  const auto table = candela_distribution(ies);
  // Relative photometry is drawn per 1000 lamp lumens (cd/klm), the usual way to compare luminaires; absolute
  // photometry (lumens per lamp −1), or a table scaled to a luminaire's lumens, in candela.
  const double lamp_lumens = luminaire_lumens ? 0.0 : ies.rated_lamp_lumens();
  const double scale = luminaire_lumens ? *luminaire_lumens / table->integral_sr()
                       : lamp_lumens > 0 ? 1000.0 / lamp_lumens
                                         : 1.0;
  if (!std::isfinite(scale) || !(scale > 0.0))
    throw InputError({ies.name, 0, ""}, "the candela table cannot be scaled to the luminaire's lumens");
  const std::string unit = lamp_lumens > 0 ? "cd/klm" : "cd";
  std::ostringstream data;
  double peak = 0;
  // Two blocks: the C 0/180° plane and the C 90/270° plane. The polar angle is γ with γ = 0 (nadir) at the
  // bottom, counterclockwise: the C 0° (90°) half to the right at +γ, the C 180° (270°) half to the left at −γ.
  for (double c : {0.0, 90.0}) {
    for (double g = -180.0; g <= 180.0; g += 0.5) {
      const double value = g >= 0 ? table->intensity_deg(g, c) : table->intensity_deg(-g, c + 180.0);
      data << g << ' ' << scale * value << '\n';
      peak = std::fmax(peak, scale * value);
    }
    data << "\n\n";
  }
  // γ labelled on both halves: 0° at the nadir, 90° at the horizon, 180° at the zenith.
  std::string ttics;
  for (int t = 0; t < 360; t += 30)
    ttics += (t ? ", " : "") + std::string("\"") + std::to_string(t <= 180 ? t : 360 - t) + "°\" " + std::to_string(t);
  // gnuplot labels the angles on the outer circle only when the radial range ends on a tic: end it on the next
  // round number above the peak, with 3-6 rings at a round step.
  const double decade = std::pow(10.0, std::floor(std::log10(peak > 0 ? peak : 1.0)));
  double r_max = 10.0 * decade, ring = 2.0 * decade;
  for (double m : {1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0})
    if (peak <= m * decade * (1.0 + 1e-9)) {
      r_max = m * decade;
      break;
    }
  for (double step : {0.1, 0.2, 0.25, 0.5, 1.0, 2.0}) {
    const double rings = r_max / (step * decade);
    if (rings <= 6.0 + 1e-9 && std::abs(rings - std::round(rings)) < 1e-6) {
      ring = step * decade;
      break;
    }
  }
  GnuplotJob job;
  job.terminal = "pngcairo size 700,760";
  job.data_files = {{"candela.dat", data.str()}};
  job.commands = "set polar\nset angles degrees\nset theta bottom counterclockwise\nset size square\n"
                 "set grid polar 30\nunset xtics\nunset ytics\nset border 0\nset rrange [0:" + std::to_string(r_max) +
                 "]\nset rtics " + std::to_string(ring) + "\nset ttics (" + ttics + ")\n"
                 "set rlabel '" + unit + "'\nset title " +
                 gnuplot_text(plot_file_name(ies.name) + ": luminous intensity (" + unit + ") against γ" +
                              (luminaire_lumens ? ", scaled to " + lumens_text(*luminaire_lumens) + " lm" : "")) +
                 " noenhanced\nset key below noenhanced\n"
                 "plot 'candela.dat' index 0 using 1:2 with lines lw 2 title 'C 0° (right) and 180° (left)', "
                 "'' index 1 using 1:2 with lines lw 2 dt 2 title 'C 90° (right) and 270° (left)'";
  draw_plot_png(job, png);
}

}  // namespace rimu
