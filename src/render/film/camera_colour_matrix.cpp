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

}  // namespace

Matrix3 fit_camera_to_xyz_under(const SpectralResponse& camera, const Spectrum& white, SpectralLibrary& library) {
  const SpectralResponse xyz = SpectralResponse::cie_xyz(library);
  const SpectrumPtr d65 = library.illuminant("D65");
  const double scale = channels_under(white, nullptr, xyz)[1] / channels_under(*d65, nullptr, xyz)[1];
  std::vector<std::array<double, 3>> c, x;
  for (const std::string& name : library.colorchecker_patch_names()) {
    const SpectrumPtr patch = library.colorchecker_patch(name);
    c.push_back(channels_under(white, patch.get(), camera));
    std::array<double, 3> target = channels_under(*d65, patch.get(), xyz);
    for (double& v : target) v *= scale;
    x.push_back(target);
  }
  return least_squares(c, x, camera);
}

CameraColourFit fit_camera_to_xyz(const SpectralResponse& camera, SpectralLibrary& library) {
  const SpectralResponse xyz = SpectralResponse::cie_xyz(library);
  const SpectrumPtr d65 = library.illuminant("D65");
  const std::vector<std::string> names = library.colorchecker_patch_names();
  std::vector<std::array<double, 3>> c, x;
  for (const std::string& name : names) {
    const SpectrumPtr patch = library.colorchecker_patch(name);
    c.push_back(channels_under(*d65, patch.get(), camera));
    x.push_back(channels_under(*d65, patch.get(), xyz));
  }
  CameraColourFit fit;
  fit.camera_to_xyz = least_squares(c, x, camera);
  fit.patch_count = int(c.size());
  fit.d65_white_rgb = channels_under(*d65, nullptr, camera);
  const Xyz white = as_xyz(channels_under(*d65, nullptr, xyz));
  for (size_t i = 0; i < c.size(); ++i) {
    const double de = delta_e_2000(lab_of(fit.camera_to_xyz.apply(as_xyz(c[i])), white), lab_of(as_xyz(x[i]), white));
    fit.mean_delta_e2000 += de / double(c.size());
    if (de > fit.max_delta_e2000) {
      fit.max_delta_e2000 = de;
      fit.worst_patch = names[i];
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
