#include "render/film/camera_colour_matrix.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/error.h"

namespace rimu {
namespace {

// The film's three channels for the radiance E(λ)·ρ(λ) (ρ = 1 without a reflectance): 1 nm trapezoid over 360-830 nm.
std::array<double, 3> channels_under(const Spectrum& illuminant, const Spectrum* reflectance,
                                     const SpectralResponse& response) {
  std::array<double, 3> sum{};
  for (int nm = 360; nm <= 830; ++nm) {
    const double w = (nm == 360 || nm == 830) ? 0.5 : 1.0;
    const double radiance = illuminant.value(nm) * (reflectance ? reflectance->value(nm) : 1.0);
    for (int c = 0; c < 3; ++c) sum[size_t(c)] += w * radiance * response.value(c, nm);
  }
  return sum;
}

Xyz as_xyz(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

// M = argmin Σ‖M cᵢ − xᵢ‖² from the normal equations M (Σ c cᵀ) = Σ x cᵀ.
Matrix3 least_squares(const std::vector<std::array<double, 3>>& c, const std::vector<std::array<double, 3>>& x,
                      const SpectralResponse& camera) {
  Matrix3 cc, xc;
  for (size_t i = 0; i < c.size(); ++i)
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) {
        cc(r, k) += c[i][size_t(r)] * c[i][size_t(k)];
        xc(r, k) += x[i][size_t(r)] * c[i][size_t(k)];
      }
  // Relative to the largest entry: a Gram matrix this close to singular means the sensor sees < 3 dimensions.
  double largest = 0.0;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) largest = std::max(largest, std::abs(cc(r, k)));
  if (!(largest > 0.0) || !(std::abs(cc.determinant()) > 1e-12 * largest * largest * largest))
    throw InputError({}, "cannot fit a camera-to-XYZ matrix for '" + camera.description() +
                             "': its responses to the ColorChecker patches do not span three dimensions");
  return xc * cc.inverse();
}

// The fit's training set: the camera's channels cᵢ of each ColorChecker patch lit by `white`, and the targets xᵢ, the
// XYZ of the same patch lit by D65 times Y(white)/Y(D65) (exactly 1 when `white` is D65).
struct TrainingSet {
  std::vector<std::string> names;
  std::vector<std::array<double, 3>> c, x;
};
TrainingSet training_set(const SpectralResponse& camera, const Spectrum& white, const SpectralResponse& xyz,
                         const Spectrum& d65, SpectralLibrary& library) {
  TrainingSet set;
  set.names = library.colorchecker_patch_names();
  const double scale = channels_under(white, nullptr, xyz)[1] / channels_under(d65, nullptr, xyz)[1];
  for (const std::string& name : set.names) {
    const SpectrumPtr patch = library.colorchecker_patch(name);
    set.c.push_back(channels_under(white, patch.get(), camera));
    std::array<double, 3> target = channels_under(d65, patch.get(), xyz);
    for (double& v : target) v *= scale;
    set.x.push_back(target);
  }
  return set;
}

}  // namespace

Matrix3 fit_camera_to_xyz_under(const SpectralResponse& camera, const Spectrum& white, SpectralLibrary& library) {
  const TrainingSet set =
      training_set(camera, white, SpectralResponse::cie_xyz(library), *library.illuminant("D65"), library);
  return least_squares(set.c, set.x, camera);
}

CameraColourFit fit_camera_to_xyz(const SpectralResponse& camera, SpectralLibrary& library) {
  const SpectralResponse xyz = SpectralResponse::cie_xyz(library);
  const SpectrumPtr d65 = library.illuminant("D65");
  const TrainingSet set = training_set(camera, *d65, xyz, *d65, library);
  CameraColourFit fit;
  fit.camera_to_xyz = least_squares(set.c, set.x, camera);
  fit.patch_count = int(set.c.size());
  fit.d65_white_rgb = channels_under(*d65, nullptr, camera);
  const Xyz white = as_xyz(channels_under(*d65, nullptr, xyz));
  for (size_t i = 0; i < set.c.size(); ++i) {
    const double de =
        delta_e_2000(lab_of(fit.camera_to_xyz.apply(as_xyz(set.c[i])), white), lab_of(as_xyz(set.x[i]), white));
    fit.mean_delta_e2000 += de / double(set.c.size());
    if (de > fit.max_delta_e2000) {
      fit.max_delta_e2000 = de;
      fit.worst_patch = set.names[i];
    }
  }
  return fit;
}

Matrix3 display_camera_to_xyz(const CameraColourFit& fit, bool white_balanced) {
  if (!white_balanced) return fit.camera_to_xyz;
  const auto& w = fit.d65_white_rgb;
  return fit.camera_to_xyz * Matrix3::diagonal(w[0] / w[1], 1.0, w[2] / w[1]);
}

}  // namespace rimu
