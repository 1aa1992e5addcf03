#include "render/film/spectral_response.h"

#include <algorithm>
#include <cmath>
#include <regex>

#include "render/film/camera_colour_matrix.h"
#include "spectral/error.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/wavelengths/wavelength_range.h"

namespace rimu {
namespace {

constexpr std::string_view kCameraFolder = "spectra/cameras";

// The source prefixes of data/spectra/cameras (see data/spectra/README.md, "cameras/").
constexpr std::string_view kCameraSourcePrefixes[] = {"rawtoaces_", "npl_darrodi2015_", "pbrt_physlight_"};

// The curve divided by `divisor`, keeping its knots (so its 1 nm lookup copy is the scaled one).
TabulatedSpectrum scaled(const TabulatedSpectrum& curve, double divisor) {
  std::vector<double> values = curve.values();
  for (double& v : values) v /= divisor;
  return TabulatedSpectrum(curve.wavelengths_nm(), std::move(values), curve.extrapolation(), curve.describe());
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

double integral_as_sampled_nm(const TabulatedSpectrum& curve) {
  // value() (and sample(), which agrees with it at every wavelength in 360-830 nm) is linear between consecutive
  // knots and constant (clamp) or zero outside them, with a step at the end knots under zero extrapolation. On
  // each interval between consecutive breakpoints (360, the knots inside, 830) it is therefore linear, and the
  // midpoint rule, (b − a)·value((a + b)/2), is exact there and never looks at the steps.
  std::vector<double> breakpoints = {kLambdaMinNm};
  for (double knot : curve.wavelengths_nm())
    if (knot > kLambdaMinNm && knot < kLambdaMaxNm) breakpoints.push_back(knot);
  breakpoints.push_back(kLambdaMaxNm);
  double sum = 0.0;
  for (size_t i = 1; i < breakpoints.size(); ++i) {
    const double a = breakpoints[i - 1], b = breakpoints[i];
    sum += (b - a) * curve.value(0.5 * (a + b));
  }
  return sum;
}

SpectralResponse::SpectralResponse(ResponseKind kind, Observer curves, double normalisation_nm, std::string description,
                                   std::string camera_name)
    : kind_(kind),
      curves_(std::move(curves)),
      normalisation_nm_(normalisation_nm),
      description_(std::move(description)),
      camera_name_(std::move(camera_name)) {
  channel_names_ = kind_ == ResponseKind::cie_xyz ? std::array<std::string, 3>{"X", "Y", "Z"}
                                                  : std::array<std::string, 3>{"R", "G", "B"};
}

SpectralResponse SpectralResponse::cie_xyz(SpectralLibrary& library, StandardObserver observer) {
  const Observer& o = library.observer(observer);
  const double y_integral_nm = integral_as_sampled_nm(o.y_bar);
  Observer normalised{o.name, scaled(o.x_bar, y_integral_nm), scaled(o.y_bar, y_integral_nm),
                      scaled(o.z_bar, y_integral_nm)};
  return SpectralResponse(ResponseKind::cie_xyz, std::move(normalised), y_integral_nm, o.name, "");
}

SpectralResponse SpectralResponse::rgb_transport(SpectralLibrary& library) {
  SpectralResponse response = cie_xyz(library);
  const Matrix3& m = RgbColourSpace::named("srgb-linear").rgb_to_xyz();
  // Row k of M gives channel k from (R, G, B): lane j's weight is M[k][j]; the dead lane 3 weighs 0.
  auto row = [&](int k) { return Float4(float(m(k, 0)), float(m(k, 1)), float(m(k, 2)), 0.0f); };
  response.rgb_lane_matrix_ = {row(0), row(1), row(2)};
  response.lanes_are_rgb_ = true;
  response.description_ = "linear sRGB lanes to CIE 1931 XYZ (rgb transport baseline)";
  return response;
}

std::string SpectralResponse::camera_short_name(std::string_view file_stem) {
  std::string name(file_stem);
  for (std::string_view prefix : kCameraSourcePrefixes) {
    if (name.rfind(prefix, 0) == 0) {
      name.erase(0, prefix.size());
      break;
    }
  }
  static const std::regex step_suffix("_[0-9]+nm$");
  return std::regex_replace(name, step_suffix, "");
}

std::vector<std::string> SpectralResponse::camera_file_stems(const SpectralLibrary& library) {
  std::vector<std::string> stems;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(library.root() / kCameraFolder, error))
    if (entry.path().extension() == ".csv") stems.push_back(entry.path().stem().string());
  std::sort(stems.begin(), stems.end());
  return stems;
}

SpectralResponse SpectralResponse::camera_rgb(SpectralLibrary& library, std::string_view name) {
  const std::vector<std::string> stems = camera_file_stems(library);
  std::vector<std::string> matches;
  for (const auto& stem : stems)
    if (stem == name) matches = {stem};
  if (matches.empty())
    for (const auto& stem : stems)
      if (camera_short_name(stem) == name) matches.push_back(stem);

  if (matches.size() != 1) {
    std::vector<std::string> short_names;
    for (const auto& stem : stems) short_names.push_back(camera_short_name(stem));
    std::sort(short_names.begin(), short_names.end());
    short_names.erase(std::unique(short_names.begin(), short_names.end()), short_names.end());
    const std::string what =
        matches.empty() ? "unknown camera '" + std::string(name) + "'; known cameras: " + joined(short_names) +
                              " (or a full file stem: " + joined(stems) + ")"
                        : "camera name '" + std::string(name) + "' is ambiguous; use one of: " + joined(matches);
    throw InputError({"", 0, "--film"}, what);
  }

  const std::string& stem = matches.front();
  const CsvTable& table = library.table(std::filesystem::path(kCameraFolder) / (stem + ".csv"));
  Observer raw{stem, TabulatedSpectrum::from_csv(table, "R", Extrapolation::zero),
               TabulatedSpectrum::from_csv(table, "G", Extrapolation::zero),
               TabulatedSpectrum::from_csv(table, "B", Extrapolation::zero)};
  const double g_integral_nm = integral_as_sampled_nm(raw.y_bar);
  if (!(g_integral_nm > 0.0))
    throw InputError({table.name(), 0, "G"}, "the green sensitivity integrates to zero; cannot normalise");
  Observer normalised{stem, scaled(raw.x_bar, g_integral_nm), scaled(raw.y_bar, g_integral_nm),
                      scaled(raw.z_bar, g_integral_nm)};
  return SpectralResponse(ResponseKind::camera_rgb, std::move(normalised), g_integral_nm,
                          "camera " + camera_short_name(stem) + " (" + stem + ")", stem);
}

SpectralResponse SpectralResponse::colour_corrected(const SpectralResponse& camera, const Matrix3& camera_to_xyz,
                                                   SpectralLibrary& library, const std::string& white_description) {
  // The camera's curves are piecewise linear between their knots, so their combination is, between the union of the
  // knots: tabulated there, it is exact.
  const std::array<const TabulatedSpectrum*, 3> curves = {&camera.curves_.x_bar, &camera.curves_.y_bar,
                                                          &camera.curves_.z_bar};
  std::vector<double> knots;
  for (const TabulatedSpectrum* c : curves) knots.insert(knots.end(), c->wavelengths_nm().begin(), c->wavelengths_nm().end());
  std::sort(knots.begin(), knots.end());
  knots.erase(std::unique(knots.begin(), knots.end()), knots.end());
  std::array<std::vector<double>, 3> values;
  for (const double nm : knots)
    for (int k = 0; k < 3; ++k) {
      double v = 0.0;
      for (int j = 0; j < 3; ++j) v += camera_to_xyz(k, j) * curves[size_t(j)]->value(nm);
      values[size_t(k)].push_back(v);
    }
  const Extrapolation outside = camera.curves_.y_bar.extrapolation();
  const std::string name = camera.camera_name_ + " to XYZ";
  Observer combined{name, TabulatedSpectrum(knots, values[0], outside, name + " X"),
                    TabulatedSpectrum(knots, values[1], outside, name + " Y"),
                    TabulatedSpectrum(knots, values[2], outside, name + " Z")};
  // In the XYZ film's units (the fit's targets are), so its photometric scale is the 1931 observer's.
  SpectralResponse response(ResponseKind::cie_xyz, std::move(combined), cie_xyz(library).normalisation_nm(),
                            camera.description_ + " through its ColorChecker fit to XYZ, white balanced to " +
                                white_description,
                            camera.camera_name_);
  response.white_balance_in_curves_ = true;
  return response;
}

SpectralResponse SpectralResponse::from_spec(SpectralLibrary& library, std::string_view spec, const Spectrum* white,
                                            const std::string& white_description) {
  if (spec == "xyz") return cie_xyz(library, StandardObserver::cie1931_2deg);
  if (spec == "xyz10") return cie_xyz(library, StandardObserver::cie1964_10deg);
  constexpr std::string_view camera_prefix = "camera:", corrected_prefix = "camera-xyz:";
  if (spec.rfind(camera_prefix, 0) == 0) return camera_rgb(library, spec.substr(camera_prefix.size()));
  if (spec.rfind(corrected_prefix, 0) == 0) {
    const SpectralResponse camera = camera_rgb(library, spec.substr(corrected_prefix.size()));
    // Balanced to the given white, else to D65 (looked up only then).
    const Matrix3 m = white ? fit_camera_to_xyz_under(camera, *white, library)
                            : fit_camera_to_xyz_under(camera, *library.illuminant("D65"), library);
    return colour_corrected(camera, m, library, white_description);
  }
  throw InputError({"", 0, "--film"}, "unknown film response '" + std::string(spec) +
                                          "'; expected xyz, xyz10, camera:<name> or camera-xyz:<name>");
}

double SpectralResponse::value(int channel, double lambda_nm) const {
  const TabulatedSpectrum& c = channel == 0 ? curves_.x_bar : (channel == 1 ? curves_.y_bar : curves_.z_bar);
  return c.value(lambda_nm);
}

double SpectralResponse::luminance_nits_per_unit_y() const {
  return kind_ == ResponseKind::cie_xyz ? kMaxLuminousEfficacy_lm_W * normalisation_nm_ : 0.0;
}

}  // namespace rimu
