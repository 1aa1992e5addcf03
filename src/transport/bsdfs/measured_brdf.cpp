#include "transport/bsdfs/measured_brdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "spectral/error.h"
#include "transport/bsdfs/microfacet.h"

namespace rimu {

namespace {

[[noreturn]] void fail(const TensorFile& file, const std::string& what) {
  throw InputError({file.name(), 0, ""}, "measured BRDF: " + what);
}

std::string shape_text(const std::vector<uint64_t>& shape) {
  std::string s = "[";
  for (size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + "]";
}

// A parameter axis (incident angles, wavelengths): finite, strictly increasing.
std::vector<float> axis(const TensorFile& file, const std::string& field) {
  std::vector<float> values = file.floats(field, 1);
  if (values.empty()) fail(file, "field \"" + field + "\" is empty");
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) fail(file, "field \"" + field + "\" holds a value that is not finite");
    if (i > 0 && !(values[i] > values[i - 1]))
      fail(file, "field \"" + field + "\" must increase strictly (entry " + std::to_string(i) + ")");
  }
  return values;
}

// A table's values: finite; for a density also ≥ 0 with positive mass in each grid of `per_grid` values.
std::vector<float> table(const TensorFile& file, const std::string& field, size_t rank, bool density, size_t per_grid) {
  std::vector<float> values = file.floats(field, rank);
  const auto& shape = file.field(field).shape;
  if (shape[rank - 1] < 2 || shape[rank - 2] < 2)
    fail(file, "field \"" + field + "\" has shape " + shape_text(shape) + "; its last two extents must be at least 2");
  for (const float v : values) {
    if (!std::isfinite(v)) fail(file, "field \"" + field + "\" holds a value that is not finite");
    if (density && v < 0.0f) fail(file, "field \"" + field + "\" holds a negative density");
  }
  if (density)
    for (size_t g = 0; g < values.size() / per_grid; ++g) {
      double sum = 0.0;
      for (size_t i = 0; i < per_grid; ++i) sum += values[g * per_grid + i];
      if (!(sum > 0.0)) fail(file, "field \"" + field + "\" has an incident direction whose density is 0 everywhere");
    }
  return values;
}

}  // namespace

MeasuredBrdf MeasuredBrdf::from_tensor_file(const TensorFile& file) {
  MeasuredBrdf brdf;
  brdf.name_ = file.name();
  const std::vector<float> theta_i = axis(file, "theta_i"), phi_i = axis(file, "phi_i");
  brdf.wavelengths_nm_ = axis(file, "wavelengths");

  const auto& ndf_shape = file.field("ndf").shape;
  const auto& sigma_shape = file.field("sigma").shape;
  const auto& vndf_shape = file.field("vndf").shape;
  const auto& luminance_shape = file.field("luminance").shape;
  const auto& spectra_shape = file.field("spectra").shape;
  const uint64_t n_phi = phi_i.size(), n_theta = theta_i.size(), n_lambda = brdf.wavelengths_nm_.size();
  if (ndf_shape.size() != 2) fail(file, "field \"ndf\" must have rank 2, not " + std::to_string(ndf_shape.size()));
  if (sigma_shape.size() != 2) fail(file, "field \"sigma\" must have rank 2, not " + std::to_string(sigma_shape.size()));
  if (vndf_shape.size() != 4 || vndf_shape[0] != n_phi || vndf_shape[1] != n_theta)
    fail(file, "field \"vndf\" has shape " + shape_text(vndf_shape) + "; expected [phi_i, theta_i, ., .] = [" +
                   std::to_string(n_phi) + ", " + std::to_string(n_theta) + ", ., .]");
  if (luminance_shape.size() != 4 || luminance_shape[0] != n_phi || luminance_shape[1] != n_theta ||
      luminance_shape[2] != luminance_shape[3])
    fail(file, "field \"luminance\" has shape " + shape_text(luminance_shape) + "; expected [" + std::to_string(n_phi) +
                   ", " + std::to_string(n_theta) + ", n, n]");
  if (spectra_shape.size() != 5 || spectra_shape[0] != n_phi || spectra_shape[1] != n_theta ||
      spectra_shape[2] != n_lambda || spectra_shape[3] != luminance_shape[2] || spectra_shape[4] != luminance_shape[3])
    fail(file, "field \"spectra\" has shape " + shape_text(spectra_shape) + "; expected [" + std::to_string(n_phi) + ", " +
                   std::to_string(n_theta) + ", " + std::to_string(n_lambda) + ", " + std::to_string(luminance_shape[2]) +
                   ", " + std::to_string(luminance_shape[3]) + "] (phi_i, theta_i, wavelengths, luminance's grid)");

  // Two φ entries or fewer: isotropic, ωm's φ relative to ωo's (pbrt-v4's and the paper's rule). An anisotropic
  // table must cover the whole circle: files reduced by a symmetry (a half or a quarter turn) are not read, as in pbrt-v4.
  brdf.isotropic_ = n_phi <= 2;
  if (!brdf.isotropic_) {
    const double span = double(phi_i.back()) - double(phi_i.front());
    if (std::lround(2.0 * std::numbers::pi / span) != 1)
      fail(file, "an anisotropic table must span 2π in phi_i (this one spans " + std::to_string(span) +
                     " rad: a file reduced by symmetry, which Rimu and pbrt-v4 do not read)");
  }

  const auto extent = [](const std::vector<uint64_t>& shape, size_t i) { return int(shape[i]); };
  using Use = BilinearWarp2D::Use;
  const std::vector<float> ndf = table(file, "ndf", 2, false, 0);
  // A GGX lobe of width α peaks at D = 1/(π α²): a measured D that high is as narrow as a glossy GGX lobe.
  const float glossy_peak = 1.0f / (std::numbers::pi_v<float> * TrowbridgeReitz::kGlossyAlpha * TrowbridgeReitz::kGlossyAlpha);
  brdf.glossy_ = *std::max_element(ndf.begin(), ndf.end()) > glossy_peak;
  brdf.ndf_ = BilinearWarp2D(ndf, extent(ndf_shape, 1), extent(ndf_shape, 0), {}, Use::interpolate);
  brdf.sigma_ = BilinearWarp2D(table(file, "sigma", 2, false, 0), extent(sigma_shape, 1), extent(sigma_shape, 0), {},
                               Use::interpolate);
  const size_t vndf_grid = size_t(vndf_shape[2] * vndf_shape[3]), luminance_grid = size_t(luminance_shape[2] * luminance_shape[3]);
  brdf.vndf_ = BilinearWarp2D(table(file, "vndf", 4, true, vndf_grid), extent(vndf_shape, 3), extent(vndf_shape, 2),
                              {phi_i, theta_i}, Use::warp);
  brdf.luminance_ = BilinearWarp2D(table(file, "luminance", 4, true, luminance_grid), extent(luminance_shape, 3),
                                   extent(luminance_shape, 2), {phi_i, theta_i}, Use::warp);
  brdf.spectra_ = BilinearWarp2D(table(file, "spectra", 5, false, 0), extent(spectra_shape, 4), extent(spectra_shape, 3),
                                 {phi_i, theta_i, brdf.wavelengths_nm_}, Use::interpolate);
  return brdf;
}

MeasuredBrdf MeasuredBrdf::read(const std::filesystem::path& path) { return from_tensor_file(TensorFile::read(path)); }

size_t MeasuredBrdf::memory_bytes() const {
  return sizeof(float) * wavelengths_nm_.size() + ndf_.memory_bytes() + sigma_.memory_bytes() + vndf_.memory_bytes() +
         luminance_.memory_bytes() + spectra_.memory_bytes();
}

}  // namespace rimu
