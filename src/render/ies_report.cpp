#include "render/ies_report.h"

#include <cmath>
#include <numbers>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "render/render_error.h"
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

}  // namespace

namespace {

// The numbers both report forms print.
struct IesSummary {
  double peak_cd = 0, peak_gamma_deg = 0, peak_c_deg = 0;
  double lumens = 0, watts = 0, beam_deg = 0, field_deg = 0, intensity_at_point_cd = 0;
};

IesSummary summarise(const IesPhotometry& ies, const InspectPoint& point) {
  validate_inspect_point(point);
  const auto table = candela_distribution(ies);
  IesSummary r;
  for (size_t i = 0; i < ies.horizontal_deg.size(); ++i)
    for (size_t j = 0; j < ies.vertical_deg.size(); ++j)
      if (ies.candela[i * ies.vertical_deg.size() + j] > r.peak_cd)
        r.peak_cd = ies.candela[i * ies.vertical_deg.size() + j], r.peak_gamma_deg = ies.vertical_deg[j],
        r.peak_c_deg = ies.horizontal_deg[i];
  r.lumens = table->integral_sr();
  r.watts = point.electrical_w.value_or(ies.input_watts);
  r.beam_deg = ies_spread_angle_deg(*table, 0.5);
  r.field_deg = ies_spread_angle_deg(*table, 0.1);
  const double angle = point.off_axis_deg;
  r.intensity_at_point_cd = table->intensity_deg(std::abs(angle), angle >= 0 ? 0.0 : 180.0);
  const double illuminance_lx = r.intensity_at_point_cd / (point.distance_m * point.distance_m);
  for (double v : {r.peak_cd, r.lumens, r.lumens / (4.0 * std::numbers::pi), illuminance_lx,
                   r.watts > 0 ? r.lumens / r.watts : 0.0, ies.rated_lamp_lumens() > 0 ? r.lumens / ies.rated_lamp_lumens() : 0.0})
    if (!std::isfinite(v))
      throw InputError({ies.name, 0, ""}, "the candela values overflow: the total flux or a derived quantity is not a "
                                          "finite number");
  return r;
}

}  // namespace

std::string inspect_ies_text(const IesPhotometry& ies, const InspectPoint& point) {
  const IesSummary r = summarise(ies, point);
  std::ostringstream o;
  o << std::setprecision(6);
  o << "file: " << ies.name << " (" << ies.version << ")\n";
  for (const auto& [key, value] : ies.keywords) o << "  [" << key << "] " << value << "\n";
  o << "photometry: type C, " << symmetry_name(ies) << ", " << ies.vertical_deg.size() << " vertical × "
    << ies.horizontal_deg.size() << " horizontal angles, TILT=" << ies.tilt << "\n";
  o << "peak intensity: " << r.peak_cd << " cd (γ " << r.peak_gamma_deg << "°, C " << r.peak_c_deg << "°)\n";
  o << "total luminous flux: " << r.lumens << " lm (∫ I dω over the interpolated table)\n";
  if (ies.rated_lamp_lumens() > 0)
    o << "lamp lumens: " << ies.rated_lamp_lumens() << " lm (" << ies.lamp_count << " × " << ies.lumens_per_lamp
      << "); luminaire efficiency " << 100.0 * r.lumens / ies.rated_lamp_lumens() << " %\n";
  else
    o << "lamp lumens: absolute photometry (-1)\n";
  if (r.watts > 0) o << "input power: " << r.watts << " W; luminaire efficacy " << r.lumens / r.watts << " lm/W\n";
  o << "beam angle (50 % of peak, C 0-180° plane): " << r.beam_deg << "°\n";
  o << "field angle (10 % of peak, C 0-180° plane): " << r.field_deg << "°\n";
  o << "at " << point.distance_m << " m, " << point.off_axis_deg << "° from the axis (C 0°): " << r.intensity_at_point_cd
    << " cd, " << r.intensity_at_point_cd / (point.distance_m * point.distance_m) << " lx on a surface facing the lamp\n";
  o << "average intensity: " << r.lumens / (4.0 * std::numbers::pi)
    << " cd (the isotropic point light of the same lumens)\n";
  return o.str();
}

nlohmann::json inspect_ies_json(const IesPhotometry& ies, const InspectPoint& point) {
  const IesSummary r = summarise(ies, point);
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
  if (ies.rated_lamp_lumens() > 0) {
    j["rated_lamp_lumens_lm"] = ies.rated_lamp_lumens();
    j["luminaire_efficiency"] = r.lumens / ies.rated_lamp_lumens();
  }
  if (r.watts > 0) j["input_power_w"] = r.watts, j["luminaire_efficacy_lm_w"] = r.lumens / r.watts;
  j["beam_angle_deg"] = r.beam_deg;
  j["field_angle_deg"] = r.field_deg;
  j["distance_m"] = point.distance_m;
  j["off_axis_deg"] = point.off_axis_deg;
  j["intensity_at_angle_cd"] = r.intensity_at_point_cd;
  j["illuminance_at_distance_lx"] = r.intensity_at_point_cd / (point.distance_m * point.distance_m);
  j["average_intensity_cd"] = r.lumens / (4.0 * std::numbers::pi);
  return j;
}

void plot_ies_polar_png(const IesPhotometry& ies, const std::filesystem::path& png) {
  const char* env = std::getenv("RIMU_GNUPLOT");
  const std::string gnuplot = env ? env : "/usr/bin/gnuplot";
  if (!std::filesystem::exists(gnuplot)) throw RenderError("cannot plot: gnuplot not found at " + gnuplot);
  const auto table = candela_distribution(ies);
  const std::filesystem::path data = png.string() + ".dat", script = png.string() + ".gp";
  {
    std::ofstream d(data);
    // Two blocks: the C 0/180° plane and the C 90/270° plane. Plot angle: nadir (γ = 0) at −90°, the C 0° (90°)
    // half to the right, the C 180° (270°) half to the left.
    for (double c : {0.0, 90.0}) {
      for (double g = -180.0; g <= 180.0; g += 0.5) {
        const double value = g >= 0 ? table->intensity_deg(g, c) : table->intensity_deg(-g, c + 180.0);
        d << g - 90.0 << ' ' << value << '\n';
      }
      d << "\n\n";
    }
    std::ofstream s(script);
    s << "set terminal pngcairo size 700,700\nset output '" << png.string() << "'\n"
      << "set polar\nset angles degrees\nset size square\nset grid polar 30\nunset xtics\nunset ytics\n"
      << "set border 0\nset title \"" << ies.name << " (cd)\"\nset rtics\n"
      << "plot '" << data.string() << "' index 0 using 1:2 with lines lw 2 title 'C 0-180°', "
      << "'' index 1 using 1:2 with lines lw 2 dt 2 title 'C 90-270°'\n";
  }
  const int status = std::system(("'" + gnuplot + "' '" + script.string() + "' 2>&1").c_str());
  std::filesystem::remove(data);
  std::filesystem::remove(script);
  if (status != 0) throw RenderError("gnuplot failed writing " + png.string());
}

}  // namespace rimu
