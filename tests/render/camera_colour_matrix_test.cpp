// The camera-to-XYZ fit: exact where an exact answer exists (the XYZ film's own curves), and for a real sensor a
// matrix that reproduces the ColorChecker far better than showing raw R, G, B as Rec.709 did.
#include <doctest/doctest.h>

#include "render/film/camera_colour_matrix.h"
#include "spectral/colorimetry/chromaticity.h"
#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/error.h"
#include "spectral/spectra/tabulated_spectrum.h"
#include "test_support.h"

using namespace rimu;

namespace {

/// The three channels of `response` for `patch` (a perfect white when null) under `light`: trapezoidal sums over
/// 360-830 nm at 1 nm, the integral the fit itself evaluates.
std::array<double, 3> channels_under(const Spectrum& light, const SpectralResponse& response, const Spectrum* patch) {
  std::array<double, 3> s{};
  for (int nm = 360; nm <= 830; ++nm) {
    const double w = (nm == 360 || nm == 830) ? 0.5 : 1.0;
    const double e = light.value(nm) * (patch ? patch->value(nm) : 1.0);
    for (int c = 0; c < 3; ++c) s[size_t(c)] += w * e * response.value(c, nm);
  }
  return s;
}

}  // namespace

TEST_CASE("fitting the XYZ film's own curves gives the identity with no residual") {
  const CameraColourFit fit = fit_camera_to_xyz(SpectralResponse::cie_xyz(test::library()), test::library());
  CHECK(fit.patch_count == 24);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(fit.camera_to_xyz(r, c) == doctest::Approx(r == c ? 1.0 : 0.0).epsilon(1e-9));
  CHECK(fit.mean_delta_e2000 < 1e-6);
}

TEST_CASE("a measured sensor's fit beats raw R, G, B shown as Rec.709 on the ColorChecker") {
  // Raw R, G, B taken as linear Rec.709 (the old display path: IEC 61966-2-1 matrix after scaling the sensor's
  // D65 white to D65 with Y kept) against the fit, both as mean CIEDE2000 over the 24 patches under D65. A 3×3
  // fit of a modern sensor reaches a few ΔE00 (Hong, Luo & Rhodes 2001 report means of 2-4 ΔE for 3×3 linear
  // fits of digital cameras); the raw view is an uncorrected colour space and far off.
  SpectralLibrary& library = test::library();
  const SpectralResponse camera = SpectralResponse::camera_rgb(library, "nikon_d850");
  const CameraColourFit fit = fit_camera_to_xyz(camera, library);
  CAPTURE(fit.mean_delta_e2000);
  CAPTURE(fit.max_delta_e2000);
  CAPTURE(fit.worst_patch);
  CHECK(fit.mean_delta_e2000 < 4.0);

  // The fit on its own training data reports the same residual a direct evaluation gives.
  const Matrix3 srgb_to_xyz{{{{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}}}};
  const SpectralResponse xyz = SpectralResponse::cie_xyz(library);
  const SpectrumPtr d65 = library.illuminant("D65");
  const auto channels = [&](const SpectralResponse& r, const Spectrum* patch) { return channels_under(*d65, r, patch); };
  const auto white_xyz = channels(xyz, nullptr);
  const auto white_raw = channels(camera, nullptr);
  const Xyz white{white_xyz[0], white_xyz[1], white_xyz[2]};
  // Raw view, fairly scaled: raw white → (1,1,1)·Y_w so that the sensor's D65 white shows as D65.
  const Matrix3 raw_view = srgb_to_xyz * Matrix3::diagonal(white_xyz[1] / white_raw[0], white_xyz[1] / white_raw[1],
                                                           white_xyz[1] / white_raw[2]);
  double raw_mean = 0.0, fit_mean = 0.0;
  const auto names = library.colorchecker_patch_names();
  for (const auto& name : names) {
    const SpectrumPtr patch = library.colorchecker_patch(name);
    const auto raw = channels(camera, patch.get());
    const auto x = channels(xyz, patch.get());
    const Lab reference = lab_of(Xyz{x[0], x[1], x[2]}, white);
    raw_mean += delta_e_2000(lab_of(raw_view.apply(Xyz{raw[0], raw[1], raw[2]}), white), reference) / 24.0;
    fit_mean += delta_e_2000(lab_of(fit.camera_to_xyz.apply(Xyz{raw[0], raw[1], raw[2]}), white), reference) / 24.0;
  }
  CAPTURE(raw_mean);
  CHECK(fit_mean == doctest::Approx(fit.mean_delta_e2000).epsilon(1e-9));
  CHECK(raw_mean > 2.0 * fit_mean);
}

TEST_CASE("through a white balance, the balanced neutral is displayed with D65's chromaticity") {
  SpectralLibrary& library = test::library();
  const CameraColourFit fit = fit_camera_to_xyz(SpectralResponse::camera_rgb(library, "nikon_d850"), library);
  const Matrix3 m = display_camera_to_xyz(fit, true);
  const auto w = m.apply(std::array<double, 3>{1.0, 1.0, 1.0});
  const Chromaticity xy = chromaticity_of(Xyz{w[0], w[1], w[2]});
  // D65 (CIE 15:2004 Table T.3): x 0.31272, y 0.32903; the fit maps the sensor's D65 white to within its residual
  // on the neutral patches, a few thousandths in xy.
  CHECK(xy.x == doctest::Approx(0.31272).epsilon(0.01 / 0.31272));
  CHECK(xy.y == doctest::Approx(0.32903).epsilon(0.01 / 0.32903));
  const Matrix3 unbalanced = display_camera_to_xyz(fit, false);
  CHECK(unbalanced(1, 1) == fit.camera_to_xyz(1, 1));
}

TEST_CASE("the fit holds on surfaces it was not trained on: the 14 CIE test colour samples") {
  // Validation on CIE 13.3's TCS01-14 (data/spectra/reflectances), a set independent of the ColorChecker, under
  // the same D65. A least-squares matrix generalises to similar smooth reflectances with errors of the training
  // set's order, so the held-out mean must stay within twice the training mean and below 3 ΔE00.
  SpectralLibrary& library = test::library();
  const SpectralResponse camera = SpectralResponse::camera_rgb(library, "nikon_d850");
  const SpectralResponse xyz = SpectralResponse::cie_xyz(library);
  const CameraColourFit fit = fit_camera_to_xyz(camera, library);
  const SpectrumPtr d65 = library.illuminant("D65");
  const auto channels = [&](const SpectralResponse& r, const Spectrum* patch) { return channels_under(*d65, r, patch); };
  const auto w = channels(xyz, nullptr);
  const Xyz white{w[0], w[1], w[2]};
  const CsvTable& tcs = library.table("spectra/reflectances/cie_13_3_tcs_5nm.csv");
  double mean = 0.0, worst = 0.0;
  for (size_t column = 1; column < tcs.column_count(); ++column) {
    const TabulatedSpectrum sample = TabulatedSpectrum::from_csv(tcs, tcs.header()[column], Extrapolation::clamp);
    const auto raw = channels(camera, &sample);
    const auto x = channels(xyz, &sample);
    const double de = delta_e_2000(lab_of(fit.camera_to_xyz.apply(Xyz{raw[0], raw[1], raw[2]}), white),
                                   lab_of(Xyz{x[0], x[1], x[2]}, white));
    mean += de / double(tcs.column_count() - 1);
    worst = std::max(worst, de);
  }
  MESSAGE("nikon_d850 on CIE TCS01-14: mean ΔE00 " << mean << ", max " << worst << " (training mean "
                                                    << fit.mean_delta_e2000 << ")");
  CHECK(mean < 2.0 * fit.mean_delta_e2000);
  CHECK(mean < 3.0);
}

TEST_CASE("pbrt-v4's sensor pipeline: under D65 it is the D65 fit, under tungsten a white keeps its luminance and "
          "comes out with D65's chromaticity") {
  SpectralLibrary& library = test::library();
  const SpectralResponse camera = SpectralResponse::camera_rgb(library, "nikon_d850");
  const SpectrumPtr d65 = library.illuminant("D65"), a = library.illuminant("A");
  const Matrix3 under_d65 = fit_camera_to_xyz_under(camera, *d65, library);
  const CameraColourFit fit = fit_camera_to_xyz(camera, library);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(under_d65(r, c) == doctest::Approx(fit.camera_to_xyz(r, c)).epsilon(1e-9));

  // Under illuminant A the fit adapts: the perfect white lit by A maps to D65's chromaticity (within the fit's
  // residual on the neutral patches, a few thousandths in xy) at the luminance the XYZ film sees from A (the fit
  // keeps Y(A) by construction of its targets, to its residual: 1 %).
  const Matrix3 under_a = fit_camera_to_xyz_under(camera, *a, library);
  const auto white = under_a.apply(channels_under(*a, camera, nullptr));
  const Chromaticity xy = chromaticity_of(Xyz{white[0], white[1], white[2]});
  CHECK(xy.x == doctest::Approx(0.31272).epsilon(0.01 / 0.31272));
  CHECK(xy.y == doctest::Approx(0.32903).epsilon(0.01 / 0.32903));
  const double y_of_a = channels_under(*a, SpectralResponse::cie_xyz(library), nullptr)[1];
  CHECK(white[1] == doctest::Approx(y_of_a).epsilon(0.01));
  // The raw white under A, by contrast, is far from neutral through the D65 fit.
  const auto raw = fit.camera_to_xyz.apply(channels_under(*a, camera, nullptr));
  CHECK(chromaticity_of(Xyz{raw[0], raw[1], raw[2]}).x > 0.40);

  // The colour-corrected film's curves are the matrix times the sensor's, so its channels of any light are M times
  // the sensor's raw ones; it is an XYZ film in the XYZ film's photometric units, with its white balance built in.
  const SpectralResponse corrected = SpectralResponse::from_spec(library, "camera-xyz:nikon_d850", a.get(), "A");
  CHECK(corrected.kind() == ResponseKind::cie_xyz);
  CHECK(corrected.white_balance_in_curves());
  CHECK(corrected.luminance_nits_per_unit_y() == doctest::Approx(SpectralResponse::cie_xyz(library).luminance_nits_per_unit_y()));
  for (const char* patch : {"dark_skin", "blue", "yellow"}) {
    const SpectrumPtr p = library.colorchecker_patch(patch);
    const auto direct = channels_under(*a, corrected, p.get());
    const auto through = under_a.apply(channels_under(*a, camera, p.get()));
    for (int c = 0; c < 3; ++c) CHECK(direct[size_t(c)] == doctest::Approx(through[size_t(c)]).epsilon(1e-9));
  }
  CHECK_THROWS_AS(SpectralResponse::from_spec(library, "camera-xyz:leica_m3"), InputError);
}
