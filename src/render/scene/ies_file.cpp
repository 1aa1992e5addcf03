#include "render/scene/ies_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "spectral/error.h"
#include "spectral/io/input_file.h"

namespace rimu {
namespace {

// The numbers after the TILT line, each with the line it came from, read one at a time.
class NumberReader {
 public:
  NumberReader(const std::vector<std::string>& lines, size_t first_line, std::string name)
      : name_(std::move(name)) {
    for (size_t l = first_line; l < lines.size(); ++l) {
      std::istringstream words(lines[l]);
      std::string w;
      while (words >> w) tokens_.push_back({w, int(l + 1)});
    }
    last_line_ = int(lines.size());
  }

  [[noreturn]] void fail(int line, const std::string& what) const { throw InputError({name_, line, ""}, what); }
  int line() const { return next_ < tokens_.size() ? tokens_[next_].line : last_line_; }

  /// The next value, named `what` in messages.
  double number(const std::string& what) {
    if (next_ >= tokens_.size()) fail(last_line_, "the file ends before " + what);
    const Token& t = tokens_[next_++];
    double v = 0.0;
    // from_chars takes no leading '+', which some writers put on exponents' mantissas ("+1.5").
    const char* begin = t.text.data() + (t.text.size() > 1 && t.text[0] == '+' ? 1 : 0);
    const auto [end, error] = std::from_chars(begin, t.text.data() + t.text.size(), v);
    if (error != std::errc() || end != t.text.data() + t.text.size() || !std::isfinite(v))
      fail(t.line, "expected a number for " + what + ", got '" + t.text + "'");
    last_read_line_ = t.line;
    return v;
  }
  double number_in(const std::string& what, double min, double max) {
    const double v = number(what);
    if (!(v >= min && v <= max))
      fail(last_read_line_, what + " must be in [" + format(min) + ", " + format(max) + "], got " + format(v));
    return v;
  }
  int integer(const std::string& what, int min, int max) {
    const double v = number_in(what, min, max);
    if (v != std::floor(v)) fail(last_read_line_, what + " must be a whole number, got " + format(v));
    return int(v);
  }
  int last_read_line() const { return last_read_line_; }
  bool at_end() const { return next_ >= tokens_.size(); }

  static std::string format(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

 private:
  struct Token {
    std::string text;
    int line;
  };
  std::vector<Token> tokens_;
  size_t next_ = 0;
  int last_line_ = 0, last_read_line_ = 0;
  std::string name_;
};

// `count` strictly increasing angles within [min, max].
std::vector<double> read_angles(NumberReader& in, int count, const std::string& what, double min, double max) {
  std::vector<double> a;
  for (int i = 0; i < count; ++i) {
    a.push_back(in.number_in(what + " " + std::to_string(i + 1), min, max));
    if (i > 0 && !(a[size_t(i)] > a[size_t(i) - 1]))
      in.fail(in.last_read_line(), what + "s must increase: " + NumberReader::format(a[size_t(i)]) + " after " +
                                       NumberReader::format(a[size_t(i) - 1]));
  }
  return a;
}

// Linear interpolation of (x, y) pairs at x0, clamped at the ends.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double x0) {
  if (x0 <= x.front()) return y.front();
  if (x0 >= x.back()) return y.back();
  const size_t i = size_t(std::upper_bound(x.begin(), x.end(), x0) - x.begin()) - 1;
  const double t = (x0 - x[i]) / (x[i + 1] - x[i]);
  return (1.0 - t) * y[i] + t * y[i + 1];
}

}  // namespace

IesPhotometry parse_ies(const std::string& text, const std::string& name) {
  reject_nul_bytes(text, name);
  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    std::string l;
    while (std::getline(in, l)) {
      if (!l.empty() && l.back() == '\r') l.pop_back();
      lines.push_back(l);
    }
  }
  IesPhotometry ies;
  ies.name = name;
  size_t l = 0;
  if (!lines.empty() && (lines[0].rfind("IESNA", 0) == 0)) {
    ies.version = lines[0];
    l = 1;
  } else {
    ies.version = "LM-63-1986";
  }
  for (; l < lines.size() && lines[l].rfind("TILT", 0) != 0; ++l) {
    const std::string& k = lines[l];
    const size_t close = k.find(']');
    if (!k.empty() && k[0] == '[' && close != std::string::npos) {
      const size_t start = k.find_first_not_of(" \t", close + 1);
      ies.keywords.push_back({k.substr(1, close - 1), start == std::string::npos ? "" : k.substr(start)});
    }
    // 1986 files have free text before TILT; it is kept only when it has the [KEYWORD] form.
  }
  if (l >= lines.size())
    throw InputError({name, int(lines.size()), ""}, "no TILT= line: this is not an IES LM-63 photometric file");
  const std::string tilt = lines[l].substr(lines[l].find('=') == std::string::npos ? 4 : lines[l].find('=') + 1);
  const int tilt_line = int(l + 1);
  const std::string tilt_value = tilt.substr(0, tilt.find_last_not_of(" \t") + 1);
  NumberReader in(lines, l + 1, name);
  if (tilt_value == "INCLUDE") {
    ies.tilt = "INCLUDE";
    in.integer("the lamp-to-luminaire geometry", 1, 3);
    const int pairs = in.integer("the number of tilt angles", 1, 1000);
    const std::vector<double> angles = read_angles(in, pairs, "tilt angle", -90.0, 180.0);
    std::vector<double> factors;
    for (int i = 0; i < pairs; ++i) factors.push_back(in.number_in("tilt multiplier " + std::to_string(i + 1), 0.0, 1e6));
    ies.tilt_factor = interpolate(angles, factors, 0.0);
  } else if (tilt_value != "NONE") {
    throw InputError({name, tilt_line, ""}, "TILT=" + tilt_value + ": a separate tilt file is not supported; use "
                                            "TILT=NONE or TILT=INCLUDE");
  }

  ies.lamp_count = in.integer("the number of lamps", 1, 100000);
  const int lumens_line = in.line();
  ies.lumens_per_lamp = in.number("the lumens per lamp");
  if (!(ies.lumens_per_lamp > 0.0 || ies.lumens_per_lamp == -1.0))
    in.fail(lumens_line, "the lumens per lamp must be positive, or -1 for absolute photometry; got " +
                             NumberReader::format(ies.lumens_per_lamp));
  ies.candela_multiplier = in.number_in("the candela multiplier", 1e-12, 1e12);
  const int vertical_count = in.integer("the number of vertical angles", 2, 100000);
  const int horizontal_count = in.integer("the number of horizontal angles", 1, 100000);
  const int type_line = in.line();
  ies.photometric_type = in.integer("the photometric type (1 = C, 2 = B, 3 = A)", 1, 3);
  if (ies.photometric_type != 1)
    in.fail(type_line, std::string("photometric type ") + (ies.photometric_type == 2 ? "B" : "A") +
                           " is not supported; Rimu reads type C (1)");
  ies.units_type = in.integer("the units type (1 = feet, 2 = metres)", 1, 2);
  ies.width = in.number("the luminous opening's width");
  ies.length = in.number("the luminous opening's length");
  ies.height = in.number("the luminous opening's height");
  ies.ballast_factor = in.number_in("the ballast factor", 1e-6, 1e6);
  const double future = in.number("the future-use (ballast-lamp photometric factor) field");
  const bool lm63_1995 = ies.version.find("1995") != std::string::npos || ies.version == "IESNA91";
  if (lm63_1995) {
    if (!(future > 0.0)) in.fail(in.last_read_line(), "the ballast-lamp photometric factor must be positive");
    ies.ballast_lamp_factor = future;
  }
  ies.input_watts = in.number_in("the input watts", 0.0, 1e9);

  // Type C: vertical angles from nadir (0-90 or 90-180 half spaces, or 0-180), horizontal from 0.
  ies.vertical_deg = read_angles(in, vertical_count, "vertical angle", 0.0, 180.0);
  ies.horizontal_deg = read_angles(in, horizontal_count, "horizontal angle", 0.0, 360.0);
  const double h0 = ies.horizontal_deg.front(), h1 = ies.horizontal_deg.back();
  const bool known_range = (h0 == 0.0 && (horizontal_count == 1 || h1 == 90.0 || h1 == 180.0 || h1 > 180.0)) ||
                           (h0 == 90.0 && h1 == 270.0);
  if (!known_range)
    in.fail(in.last_read_line(), "horizontal angles must run 0 (axial), 0-90, 0-180, 90-270 or 0-360 for type C; "
                                 "got " + NumberReader::format(h0) + "-" + NumberReader::format(h1));

  const double factor = ies.candela_multiplier * ies.ballast_factor * ies.ballast_lamp_factor * ies.tilt_factor;
  const size_t expected = size_t(vertical_count) * size_t(horizontal_count);
  const int table_line = in.line();
  for (size_t i = 0; i < expected; ++i) {
    if (in.at_end())
      in.fail(in.line(), "the candela table ends after " + std::to_string(i) + " of " + std::to_string(expected) +
                             " values (" + std::to_string(horizontal_count) + " horizontal × " +
                             std::to_string(vertical_count) + " vertical angles)");
    const double cd = in.number("candela value " + std::to_string(i + 1));
    if (cd < 0.0) in.fail(in.last_read_line(), "candela value " + std::to_string(i + 1) + " is negative (" +
                                                   NumberReader::format(cd) + ")");
    if (!std::isfinite(cd * factor))
      in.fail(in.last_read_line(), "candela value " + std::to_string(i + 1) + " (" + NumberReader::format(cd) +
                                       ") times the multipliers (" + NumberReader::format(factor) +
                                       ") overflows a double");
    ies.candela.push_back(cd * factor);
  }
  if (!in.at_end())
    in.fail(in.line(), "more values than the " + std::to_string(expected) + " the counts announce (" +
                           std::to_string(horizontal_count) + " horizontal × " + std::to_string(vertical_count) +
                           " vertical angles)");
  // Values that are each finite can still sum to infinity; a lamp of infinite flux is not a measurement. The flux
  // of the bilinear table is at most 4π·peak, and building its sampling distribution averages four corners (≤ 4·peak)
  // before weighting by solid angle, so 16π·peak finite keeps every sum finite. The check comes before the table
  // is built: the distribution asserts finite weights.
  const double peak_cd = ies.candela.empty() ? 0.0 : *std::max_element(ies.candela.begin(), ies.candela.end());
  if (!std::isfinite(16.0 * std::numbers::pi * peak_cd))
    in.fail(table_line, "the candela values are too large: the total luminous flux they give overflows a double "
                        "(check the candela multiplier and the values' units)");
  return ies;
}

IesPhotometry read_ies_file(const std::filesystem::path& path) {
  return parse_ies(read_input_file(path, kMaxTableFileBytes), path.string());
}

std::shared_ptr<const CandelaDistribution> candela_distribution(const IesPhotometry& ies, double scale) {
  const std::vector<double>& h = ies.horizontal_deg;
  const double first = h.front(), last = h.back();
  // fold(C): the tabulated angle whose column holds the intensity at C, by the file's symmetry (LM-63-2002 §5.19).
  auto fold = [&](double c) {
    if (h.size() == 1) return first;
    if (first == 90.0) return c < 90.0 ? 180.0 - c : c > 270.0 ? 540.0 - c : c;  // about the 90-270° plane
    if (last == 90.0) {
      const double m = std::fmod(c, 180.0);
      return m > 90.0 ? 180.0 - m : m;
    }
    if (last == 180.0) return c > 180.0 ? 360.0 - c : c;
    return c > last ? 0.0 : c;  // full turn, closed at 360° by the 0° column
  };
  // Whether fold(c) is a tabulated angle.
  auto folds_onto_table = [&](double c) {
    const double f = fold(c);
    return std::any_of(h.begin(), h.end(), [&](double a) { return std::abs(a - f) < 1e-9; });
  };
  // Grid: the images of the tabulated angles under the symmetry's mirrors, kept only where they fold back onto a
  // tabulated angle (so the expanded table is still interpolated between measured values only).
  std::vector<double> grid{0.0, 360.0};
  for (double a : h)
    for (double c : {a, 180.0 - a, 180.0 + a, 360.0 - a, 540.0 - a})
      if (c >= 0.0 && c <= 360.0 && folds_onto_table(c)) grid.push_back(c);
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }),
             grid.end());
  const size_t nv = ies.vertical_deg.size();
  std::vector<double> values;
  values.reserve(grid.size() * nv);
  for (double c : grid) {
    // Mirror images fold exactly onto a column; 0° and 360° may fall between two (a 90-270° file without 180°),
    // where the fold is linear, so interpolating the two columns there keeps the expansion exact.
    const double f = fold(c);
    size_t i = 0;
    while (i + 2 < h.size() && f > h[i + 1]) ++i;
    const double t = h.size() == 1 ? 0.0 : std::clamp((f - h[i]) / (h[i + 1] - h[i]), 0.0, 1.0);
    const size_t i1 = h.size() == 1 ? 0 : i + 1;
    for (size_t v = 0; v < nv; ++v)
      values.push_back(scale * ((1.0 - t) * ies.candela[i * nv + v] + t * ies.candela[i1 * nv + v]));
  }
  // A table starting above nadir (90-180) or stopping at the horizon is 0 outside; CandelaDistribution handles that.
  return std::make_shared<const CandelaDistribution>(ies.vertical_deg, std::move(grid), std::move(values));
}

double ies_spread_angle_deg(const CandelaDistribution& table, double fraction) {
  // Walk the C = 0° / 180° plane in 0.01° steps from the peak outwards on both sides.
  constexpr double step = 0.01;
  double peak = 0.0, peak_gamma = 0.0;  // signed γ: negative on the C = 180° side
  auto at = [&](double g) { return g >= 0 ? table.intensity_deg(g, 0.0) : table.intensity_deg(-g, 180.0); };
  for (double g = -180.0; g <= 180.0; g += step)
    if (at(g) > peak) peak = at(g), peak_gamma = g;
  if (!(peak > 0.0)) return 0.0;
  auto edge = [&](double direction) {
    for (double g = peak_gamma; std::abs(g) <= 180.0; g += direction * step) {
      const double v = at(g), next = at(g + direction * step);
      if (next <= fraction * peak) return g + direction * step * (v - fraction * peak) / (v - next);
    }
    return std::nan("");
  };
  const double a = edge(1.0), b = edge(-1.0);
  return std::isfinite(a) && std::isfinite(b) ? a - b : 0.0;
}

}  // namespace rimu
