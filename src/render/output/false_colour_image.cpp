#include "render/output/false_colour_image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <ostream>
#include <sstream>

#include "render/output/output_file.h"
#include "render/output/plot_output.h"
#include "spectral/error.h"

namespace rimu {
namespace {

// The range a legend may span: beyond, a float pixel cannot hold the value (the EXR is 32-bit).
constexpr double kMinLegendValue = 1e-30, kMaxLegendValue = 1e30;

// Four significant digits, without an exponent between 1 and 1e9 (a legend reads "20000 nt", not "2e+04").
std::string number_text(double x) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.4g", x);
  if (std::strchr(buffer, 'e') && x >= 1 && x < 1e9) std::snprintf(buffer, sizeof buffer, "%.0f", x);
  return buffer;
}

const char* unit_label(FalseColourQuantity quantity) {
  switch (quantity) {
    case FalseColourQuantity::luminance: return "luminance (nt = cd/m²)";
    case FalseColourQuantity::illuminance: return "illuminance (lx), π × luminance: white Lambertian reference";
    case FalseColourQuantity::relative_error: return "relative standard error of luminance (%)";
  }
  return "";
}

// Tics of a log legend: every decade inside the range, with 2 and 5 between when it spans less than two decades,
// and the range's ends unless a tic already sits next to them.
std::vector<double> legend_tics(const FalseColourRange& range) {
  std::vector<double> tics;
  const int first = int(std::ceil(std::log10(range.low) - 1e-9)), last = int(std::floor(std::log10(range.high) + 1e-9));
  const bool sparse = last - first < 2;
  for (int d = first - 1; d <= last; ++d)
    for (double m : sparse ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
      const double v = m * std::pow(10.0, d);
      if (v >= range.low * (1 - 1e-9) && v <= range.high * (1 + 1e-9)) tics.push_back(v);
    }
  for (double end : {range.low, range.high}) {
    const double p = false_colour_position(end, range);
    const bool near = std::any_of(tics.begin(), tics.end(),
                                  [&](double t) { return std::abs(false_colour_position(t, range) - p) < 0.05; });
    if (!near) tics.push_back(end);
  }
  std::sort(tics.begin(), tics.end());
  return tics;
}

}  // namespace

FalseColourQuantity parse_false_colour_quantity(const std::string& text, const std::string& option) {
  if (text == "luminance") return FalseColourQuantity::luminance;
  if (text == "illuminance") return FalseColourQuantity::illuminance;
  throw InputError({"", 0, option}, "'" + text + "' is not a false-colour quantity: give luminance (nt) or "
                                    "illuminance (lx, π × luminance)");
}

FalseColourRange parse_false_colour_range(const std::string& text, const std::string& option) {
  const auto fail = [&](const std::string& why) -> FalseColourRange {
    throw InputError({"", 0, option}, "'" + text + "': " + why);
  };
  const size_t colon = text.find(':');
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos)
    return fail("give the legend's range as LOW:HIGH, e.g. 1:10000");
  double bounds[2];
  const std::string parts[2] = {text.substr(0, colon), text.substr(colon + 1)};
  for (int k = 0; k < 2; ++k) {
    char* end = nullptr;
    bounds[k] = std::strtod(parts[k].c_str(), &end);
    if (parts[k].empty() || end != parts[k].c_str() + parts[k].size() || !std::isfinite(bounds[k]))
      return fail("'" + parts[k] + "' is not a finite number");
  }
  if (!(bounds[0] >= kMinLegendValue) || !(bounds[1] <= kMaxLegendValue))
    return fail("a log scale needs 1e-30 <= LOW and HIGH <= 1e30");
  if (!(bounds[1] > bounds[0])) return fail("HIGH must be greater than LOW");
  return {bounds[0], bounds[1]};
}

FalseColourValues false_colour_values(const ExrDisplaySource& source, FalseColourQuantity quantity) {
  const Film& film = *source.film;
  const PixelBounds bounds = film.pixel_bounds();
  FalseColourValues image;
  image.width = bounds.width();
  image.height = bounds.height();
  image.quantity = quantity;
  image.values.reserve(size_t(bounds.area()));
  const double per_nt = quantity == FalseColourQuantity::luminance ? 1.0 : std::numbers::pi;
  // A camera film's Y as its display image (and the metering) takes it: through the fitted matrix, white-balanced
  // when the file is.
  const std::optional<Matrix3> camera_to_xyz =
      source.camera_fit ? std::optional<Matrix3>(display_camera_to_xyz(*source.camera_fit, source.white_balanced))
                        : std::nullopt;
  for (int y = bounds.y0; y < bounds.y1; ++y)
    for (int x = bounds.x0; x < bounds.x1; ++x) {
      const std::array<double, 3> value = film.output_value(x, y);
      const double y_value = camera_to_xyz ? camera_to_xyz->apply(value)[1] : value[1];
      const double v = y_value * source.nits_per_unit_y * per_nt;
      image.values.push_back(std::isfinite(v) ? v : std::nan(""));
    }
  return image;
}

FalseColourRange default_false_colour_range(const std::vector<double>& values, const std::string& option) {
  std::vector<double> positive;
  for (double v : values)
    if (v > 0 && std::isfinite(v)) positive.push_back(std::clamp(v, kMinLegendValue, kMaxLegendValue));
  if (positive.empty())
    throw InputError({"", 0, option}, "no pixel of the image is brighter than 0, so it has no log scale to show; "
                                      "give one with --range LOW:HIGH");
  const auto percentile = [&](double p) {
    const size_t k = std::min(positive.size() - 1, size_t(p * double(positive.size() - 1) + 0.5));
    std::nth_element(positive.begin(), positive.begin() + ptrdiff_t(k), positive.end());
    return positive[k];
  };
  FalseColourRange range{percentile(0.01), percentile(0.99)};
  if (!(range.high > range.low * (1 + 1e-6))) {
    const double centre = std::sqrt(range.low * range.high);
    range = {std::max(centre / 10, kMinLegendValue), std::min(centre * 10, kMaxLegendValue)};
  }
  return range;
}

double false_colour_position(double value, const FalseColourRange& range) {
  if (!(value > 0)) return 0.0;
  return std::clamp(std::log(value / range.low) / std::log(range.high / range.low), 0.0, 1.0);
}

GnuplotJob false_colour_job(const FalseColourValues& image, const FalseColourRange& range, const std::string& title) {
  // The legend is drawn over [0, 1] in legend positions with tics labelled in the unit: the colour of a pixel is
  // then exactly false_colour_rgb(false_colour_position(value)), whatever gnuplot's own log scaling would round.
  // Rows bottom first: gnuplot's array puts the first row at y = 0.
  std::string data(sizeof(float) * image.values.size(), '\0');
  char* out = data.data();
  for (int row = image.height - 1; row >= 0; --row)
    for (int x = 0; x < image.width; ++x) {
      const float position = float(false_colour_position(image.values[size_t(row) * size_t(image.width) + size_t(x)], range));
      std::memcpy(out, &position, sizeof position);
      out += sizeof position;
    }
  const int plot_width = 900;
  const int plot_height = int(std::lround(plot_width * double(image.height) / std::max(image.width, 1)));
  GnuplotJob job;
  job.terminal = "pngcairo size " + std::to_string(plot_width + 260) + "," +
                 std::to_string(std::clamp(plot_height + 120, 300, 1600));
  job.data_files = {{"values.bin", std::move(data)}};
  std::ostringstream c;
  c << "set title " << gnuplot_text(title) << " noenhanced\n"
    << "set size ratio -1\nunset xtics\nunset ytics\nunset key\nset border 0\n"
    << "set xrange [-0.5:" << image.width - 0.5 << "]\nset yrange [-0.5:" << image.height - 0.5 << "]\n"
    << false_colour_palette_command() << "set cbrange [0:1]\nset cblabel " << gnuplot_text(unit_label(image.quantity))
    << " noenhanced\nset cbtics (";
  const std::vector<double> tics = legend_tics(range);
  for (size_t k = 0; k < tics.size(); ++k)
    c << (k ? ", " : "") << "'" << number_text(tics[k]) << "' " << false_colour_position(tics[k], range);
  c << ")\nset mcbtics 1\n"
    << "plot 'values.bin' binary array=(" << image.width << "," << image.height << ") format='%float32' with image\n";
  job.commands = c.str();
  return job;
}

void write_exr_false_colour(const std::filesystem::path& exr, const std::filesystem::path& png,
                            FalseColourQuantity quantity, const std::optional<FalseColourRange>& range,
                            std::ostream& log) {
  check_plot_png(png, {"", 0, "--png"});
  check_output_not_input(png, "--png", {{exr, "the image to display"}});
  SpectralLibrary library = SpectralLibrary::at_default_location();
  const ExrDisplaySource source = read_exr_for_display(exr, library);
  const FalseColourValues image = false_colour_values(source, quantity);
  const FalseColourRange used = range ? *range : default_false_colour_range(image.values, "--range");
  size_t below = 0, above = 0;
  for (double v : image.values) below += !(v >= used.low), above += v > used.high;
  const double count = double(std::max<size_t>(image.values.size(), 1));
  const char* unit = quantity == FalseColourQuantity::luminance ? "nt" : "lx";
  const std::string range_text = number_text(used.low) + " to " + number_text(used.high) + " " + unit;
  const std::string origin = range ? "--range" : "1st-99th percentile";
  draw_plot_png(false_colour_job(image, used,
                                 plot_file_name(exr) + ": " +
                                     (quantity == FalseColourQuantity::luminance ? "luminance" : "illuminance") +
                                     ", log scale " + range_text + " (" + origin + "; beyond it clamped)"),
                png);
  log << "rimu display: false colour of the " << (quantity == FalseColourQuantity::luminance ? "luminance" : "illuminance")
      << ", log scale " << range_text << " (" << origin << "), " << number_text(100.0 * double(below) / count)
      << " % of the pixels below it, " << number_text(100.0 * double(above) / count) << " % above\n";
}

}  // namespace rimu
