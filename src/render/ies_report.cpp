#include "render/ies_report.h"

#include <cmath>
#include <numbers>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "render/render_error.h"

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

std::string inspect_ies_text(const IesPhotometry& ies, double distance_m, double angle_deg,
                             std::optional<double> electrical_w) {
  const auto table = candela_distribution(ies);
  std::ostringstream o;
  o << std::setprecision(6);
  o << "file: " << ies.name << " (" << ies.version << ")\n";
  for (const auto& [key, value] : ies.keywords) o << "  [" << key << "] " << value << "\n";
  o << "photometry: type C, " << symmetry_name(ies) << ", " << ies.vertical_deg.size() << " vertical × "
    << ies.horizontal_deg.size() << " horizontal angles, TILT=" << ies.tilt << "\n";
  // The peak over the grid, with where it is.
  double peak = 0, peak_gamma = 0, peak_c = 0;
  for (size_t i = 0; i < ies.horizontal_deg.size(); ++i)
    for (size_t j = 0; j < ies.vertical_deg.size(); ++j)
      if (ies.candela[i * ies.vertical_deg.size() + j] > peak)
        peak = ies.candela[i * ies.vertical_deg.size() + j], peak_gamma = ies.vertical_deg[j], peak_c = ies.horizontal_deg[i];
  const double lumens = table->integral_sr();
  o << "peak intensity: " << peak << " cd (γ " << peak_gamma << "°, C " << peak_c << "°)\n";
  o << "total luminous flux: " << lumens << " lm (∫ I dω over the interpolated table)\n";
  if (ies.rated_lamp_lumens() > 0)
    o << "lamp lumens: " << ies.rated_lamp_lumens() << " lm (" << ies.lamp_count << " × " << ies.lumens_per_lamp
      << "); luminaire efficiency " << 100.0 * lumens / ies.rated_lamp_lumens() << " %\n";
  else
    o << "lamp lumens: absolute photometry (-1)\n";
  const double watts = electrical_w.value_or(ies.input_watts);
  if (watts > 0) o << "input power: " << watts << " W; luminaire efficacy " << lumens / watts << " lm/W\n";
  const double beam = ies_spread_angle_deg(*table, 0.5), field = ies_spread_angle_deg(*table, 0.1);
  o << "beam angle (50 % of peak, C 0-180° plane): " << beam << "°\n";
  o << "field angle (10 % of peak, C 0-180° plane): " << field << "°\n";
  const double intensity = table->intensity_deg(std::abs(angle_deg), angle_deg >= 0 ? 0.0 : 180.0);
  o << "at " << distance_m << " m, " << angle_deg << "° from the axis (C 0°): " << intensity << " cd, "
    << intensity / (distance_m * distance_m) << " lx on a surface facing the lamp\n";
  o << "average intensity: " << lumens / (4.0 * std::numbers::pi) << " cd (the isotropic point light of the same lumens)\n";
  return o.str();
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
