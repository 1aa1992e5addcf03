#include "spectral/upsampling/rgb_upsampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/colorimetry/photometry_constants.h"
#include "spectral/upsampling/upsampling_whites.h"

namespace rimu {
namespace {

void check_finite(const Rgb& rgb, const std::string& space, const SourceLocation& where) {
  if (std::isfinite(rgb.r) && std::isfinite(rgb.g) && std::isfinite(rgb.b)) return;
  throw InputError(where, "RGB (" + std::to_string(rgb.r) + ", " + std::to_string(rgb.g) + ", " +
                              std::to_string(rgb.b) + ") in " + space +
                              " is not finite: every component must be a finite number to be upsampled");
}

/// RGB (0, 0, 0): every upsample_* and *_coefficients call gives exactly zero for it, not "mapped".
bool is_black(const Rgb& rgb) { return rgb.r == 0.0 && rgb.g == 0.0 && rgb.b == 0.0; }

/// A colour no non-negative spectrum has (possible with negative components): Y ≤ 0 or X + Y + Z ≤ 0 (NaN-safe).
bool has_no_spectrum(const Xyz& xyz) { return !(xyz.y > 0.0) || !(xyz.x + xyz.y + xyz.z > 0.0); }

/// Re-imposes XYZ = target on a non-negative knot spectrum by the smallest change in the metric Σ ΔS_i²/S_i:
/// ΔS = diag(S)·Aᵀλ with (A·diag(S)·Aᵀ)·λ = target − A·S. Knots at zero stay at zero, so the result stays ≥ 0
/// if the relative change 1 + (Aᵀλ)_i stays ≥ 0; where it does not, the knot is clamped to 0 and the step
/// repeated (the table is close enough that one step is normally exact to 1e-15).
void correct_to(KnotValues& s, const KnotColorimetry& c, const Xyz& target) {
  const double t[3] = {target.x, target.y, target.z};
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Xyz got = c.xyz_of(s);
    const double r[3] = {t[0] - got.x, t[1] - got.y, t[2] - got.z};
    if (std::abs(r[0]) + std::abs(r[1]) + std::abs(r[2]) <= 1e-14 * (std::abs(t[0]) + t[1] + std::abs(t[2]))) return;
    Matrix3 m;
    for (int i = 0; i < kUpsampleKnotCount; ++i)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) m(k, l) += c.row(k)[i] * s[i] * c.row(l)[i];
    const double scale = m(0, 0) + m(1, 1) + m(2, 2);
    if (!(std::abs(m.determinant()) > 1e-12 * scale * scale * scale)) return;  // fewer than 3 live knots
    const auto lambda = m.inverse().apply(std::array<double, 3>{r[0], r[1], r[2]});
    for (int i = 0; i < kUpsampleKnotCount; ++i) {
      const double g = lambda[0] * c.row(0)[i] + lambda[1] * c.row(1)[i] + lambda[2] * c.row(2)[i];
      s[i] = std::fmax(0.0, s[i] * (1.0 + g));
    }
  }
}

// How far above 1 the fast path's unclamped peak may reach before the brightness limit moves the colour: the
// basis truncation's overshoot at narrow peaks (≤ 1.5 % on the 33³ grids of sRGB, ACEScg, Rec.2020 away from
// the locus; docs/upsampling.md).
constexpr double kRingingAllowance = 1.02;
// The fast path reports a colour as moved (gamut_mapped) when fitting its clamped spectrum leaves more than this
// relative XYZ residual (ΔE00 ≲ 0.01): the basis cannot hold that spectrum at zero or under 1.
constexpr double kFitTolerance = 1e-4;

double delta_e(const Xyz& a, const Xyz& b, const Xyz& white) { return delta_e_2000(lab_of(a, white), lab_of(b, white)); }

Xyz scaled(const Xyz& v, double k) { return {v.x * k, v.y * k, v.z * k}; }

}  // namespace

RgbUpsampler::RgbUpsampler(SpectralLibrary& library, const RgbColourSpace& space)
    : space_(space),
      illuminant_(std::make_shared<const TabulatedSpectrum>(
          upsampling_illuminant(library, upsampling_white_for(space.white())))),
      colorimetry_(library.observer(StandardObserver::cie1931_2deg), *illuminant_, upsampling_white_for(space.white()).white),
      table_(UpsamplingTable::read(library.root() / upsampling_table_file(upsampling_white_for(space.white())))),
      gamut_(table_.gamut()) {
  const double white_y = integrate_on_grid(IntegrationGrid::cie_1nm(), [&](double l) {
    return illuminant_->value(l) * library.observer(StandardObserver::cie1931_2deg).y_bar.value(l);
  });
  emission_scale_ = 1.0 / (kMaxLuminousEfficacy_lm_W * white_y);
}

KnotValues RgbUpsampler::smooth_shape(Chromaticity xy, bool* moved) const {
  const Chromaticity w = gamut_.white();
  const double dx = xy.x - w.x, dy = xy.y - w.y;
  const double angle = std::atan2(dy, dx);
  double rho = std::hypot(dx, dy) == 0.0 ? 0.0 : std::hypot(dx, dy) / (gamut_.boundary_radius(angle) * table_.usable_fraction);
  const bool outside = rho > 1.0;
  if (outside) {
    rho = 1.0;
    xy = gamut_.at(angle, table_.usable_fraction);
  }
  if (moved) *moved = outside;
  KnotValues s = table_.interpolate(angle, rho);
  correct_to(s, colorimetry_, xyz_from_xyY(xy, 1.0));
  return s;
}

KnotValues RgbUpsampler::reflectance_knots(const Xyz& xyz, bool* moved) const {
  KnotValues s = smooth_shape(chromaticity_of(xyz), moved);
  // Brightness limit (Manuka notes Eq. 12: every value ≤ 1): Y_max = 1 / max s for the Y = 1 shape.
  const double peak = *std::max_element(s.begin(), s.end());
  double luminance = xyz.y;
  // The tolerance keeps white and greys (peak 1 ± 1e-15 after the correction) from counting as clipped; the
  // min(·, 1) below removes that rounding from the stored values.
  if (luminance * peak > 1.0 + 1e-12) {
    luminance = 1.0 / peak;
    *moved = true;
  }
  for (double& v : s) v = std::fmin(v * luminance, 1.0);
  return s;
}

UpsampledReflectance RgbUpsampler::upsample_reflectance(const Rgb& rgb, const SourceLocation& where) const {
  check_finite(rgb, space_.name(), where);
  UpsampledReflectance out;
  if (is_black(rgb)) return out;
  const Xyz xyz = space_.to_xyz(rgb);
  const Xyz white = colorimetry_.white_xyz();
  if (has_no_spectrum(xyz)) {
    out.gamut_mapped = true;
    out.delta_e2000 = delta_e(xyz, Xyz{}, white);
    return out;
  }
  bool moved = false;
  out.spectrum = ReflectanceSpectrum(reflectance_knots(xyz, &moved));
  out.gamut_mapped = moved;
  out.delta_e2000 = delta_e(xyz, xyz_of(out.spectrum.samples()), white);
  return out;
}

ReflectanceSpectrum RgbUpsampler::reflectance_spectrum(const Rgb& rgb, const SourceLocation& where) const {
  check_finite(rgb, space_.name(), where);
  if (is_black(rgb)) return {};
  const Xyz xyz = space_.to_xyz(rgb);
  if (has_no_spectrum(xyz)) return {};
  bool moved = false;
  return ReflectanceSpectrum(reflectance_knots(xyz, &moved));
}

UpsampledEmission RgbUpsampler::upsample_emission(const Rgb& rgb, const SourceLocation& where) const {
  check_finite(rgb, space_.name(), where);
  UpsampledEmission out;
  if (is_black(rgb)) return out;
  const Xyz xyz = space_.to_xyz(rgb);
  if (has_no_spectrum(xyz)) {
    out.gamut_mapped = true;
    out.delta_e2000 = delta_e(scaled(xyz, 1.0 / std::fmax(std::abs(xyz.y), 1e-300)), Xyz{}, colorimetry_.white_xyz());
    return out;
  }
  bool moved = false;
  const KnotValues s = smooth_shape(chromaticity_of(xyz), &moved);
  out.spectrum = EmissionSpectrum(s, emission_scale_ * xyz.y, illuminant_);
  out.gamut_mapped = moved;
  // Both at Y = 1 (L* = 100): the difference is the chromaticity shift alone.
  out.delta_e2000 = delta_e(scaled(xyz, 1.0 / xyz.y), xyz_of(out.spectrum.shape()), colorimetry_.white_xyz());
  return out;
}

const UpsamplingBasis& RgbUpsampler::build_basis() const {
  const std::lock_guard<std::mutex> lock(lazy_basis_->mutex);
  if (!lazy_basis_->basis) {
    lazy_basis_->basis = std::make_unique<const UpsamplingBasis>(table_, colorimetry_);
    lazy_basis_->built.store(lazy_basis_->basis.get(), std::memory_order_release);
  }
  return *lazy_basis_->basis;
}

BasisCoefficients RgbUpsampler::smooth_coefficients(const Xyz& xyz, bool* moved, SmoothShapeBounds* bounds) const {
  // The offset from the white, (dx, dy) = (X − x_w·Σ, Y − y_w·Σ)/Σ with Σ = X + Y + Z, is located unnormalised:
  // locate() only needs its direction, and ρ = |offset|·(1/Σ)·(1/R(θ)) with 1/R tabulated, so the division by Σ
  // runs beside locate()'s instead of before it (the setup is a chain of dependent divisions, roots and loads).
  const double total = xyz.x + xyz.y + xyz.z;
  const Chromaticity w = gamut_.white();
  const double ox = xyz.x - w.x * total, oy = xyz.y - w.y * total;
  const UpsamplingBasis::PolarCell cell = basis().locate(ox, oy);
  const double offset = std::sqrt(ox * ox + oy * oy);
  const double inv_total = 1.0 / total;
  Chromaticity xy{xyz.x * inv_total, xyz.y * inv_total};
  double rho = offset * inv_total * cell.inverse_usable_radius;
  if (rho > 1.0) {  // radial move onto the usable gamut's edge, as smooth_shape
    const double k = inv_total / rho;
    xy = {w.x + ox * k, w.y + oy * k};
    rho = 1.0;
    *moved = true;
  }
  return basis().smooth_coefficients_in_cell(xy, cell.angle_cell, rho, bounds);
}

BasisCoefficients RgbUpsampler::reflectance_coefficients(const Rgb& rgb, bool* mapped, const SourceLocation& where) const {
  check_finite(rgb, space_.name(), where);
  bool moved = false;
  BasisCoefficients c;
  const Xyz xyz = space_.to_xyz(rgb);
  if (is_black(rgb)) {
  } else if (has_no_spectrum(xyz)) {
    moved = true;
  } else {
    SmoothShapeBounds bounds;
    c = smooth_coefficients(xyz, &moved, &bounds);
    double luminance = xyz.y;
    // Brightness limit as reflectance_knots, on this representation's own (unclamped) peak; the 95-knot pass
    // that finds it is skipped where the bound shows the limit is far. The basis rings by up to ~2 % of the
    // peak around narrow peaks, so its peak overstates the exact path's: the limit allows that much above 1,
    // and fit_clamped below flattens it at 1 and restores the colour. Continuous in Y, like the exact limit.
    bool have_knots = false;
    alignas(16) float knots[kUpsampleKnotCount + 1];
    double peak = bounds.peak_bound;  // ≥ the peak; the peak itself once have_knots
    if (luminance * bounds.peak_bound > 1.0) {
      peak = basis().knots_float(c, knots);
      have_knots = true;
      if (luminance * peak > kRingingAllowance) {
        luminance = kRingingAllowance / peak;
        moved = true;
      }
    }
    c *= float(luminance);
    // Clamped at 0 (ringing) or at 1 (the allowance): fit the clamped spectrum to the colour asked for (at the
    // luminance kept). Below the brightness limit the cheaper fit (clamping at zero in the low blocks; it verifies
    // its result and hands over to the full fit if a knot ends above 1).
    const bool clamps_at_1 = luminance * peak > 1.0;
    if (bounds.rings || clamps_at_1) {
      const Xyz target = scaled(bounds.colour, luminance);
      const double left =
          clamps_at_1 ? basis().fit_clamped(c, basis().correction_directions(bounds, float(luminance)), target, 1.0f,
                                            have_knots ? knots : nullptr, float(luminance))
                      : basis().fit_zero_clamped(c, bounds, float(luminance), target, 1.0f);
      if (left > kFitTolerance) moved = true;
    }
  }
  if (mapped) *mapped = moved;
  return c;
}

ReflectanceSpectrum RgbUpsampler::fast_reflectance_spectrum(const Rgb& rgb, const SourceLocation& where) const {
  const BasisCoefficients c = reflectance_coefficients(rgb, nullptr, where);
  alignas(16) float knots[kUpsampleKnotCount + 1];
  basis().knots_float(c, knots);
  KnotValues clamped;
  for (int i = 0; i < kUpsampleKnotCount; ++i) clamped[i] = std::clamp(double(knots[i]), 0.0, 1.0);
  return ReflectanceSpectrum(clamped);
}

BasisCoefficients RgbUpsampler::emission_coefficients(const Rgb& rgb, bool* mapped, const SourceLocation& where) const {
  check_finite(rgb, space_.name(), where);
  bool moved = false;
  BasisCoefficients c;
  const Xyz xyz = space_.to_xyz(rgb);
  if (is_black(rgb)) {
  } else if (has_no_spectrum(xyz)) {
    moved = true;
  } else {
    SmoothShapeBounds bounds;
    c = smooth_coefficients(xyz, &moved, &bounds);
    c *= float(xyz.y);
    if (bounds.rings) {
      const double left = basis().fit_zero_clamped(
          c, bounds, float(xyz.y), scaled(bounds.colour, xyz.y), INFINITY);
      if (left > kFitTolerance) moved = true;
    }
  }
  if (mapped) *mapped = moved;
  return c;
}

EmissionSpectrum RgbUpsampler::fast_emission_spectrum(const Rgb& rgb, const SourceLocation& where) const {
  // The shape at Y = 1 and the luminance in the scale, as upsample_emission stores them.
  const BasisCoefficients c = emission_coefficients(rgb, nullptr, where);
  const double luminance = space_.to_xyz(rgb).y;
  if (c.c[0] == 0.0f || !(luminance > 0.0)) return {};
  alignas(16) float knots[kUpsampleKnotCount + 1];
  basis().knots_float(c, knots);
  KnotValues shape;
  for (int i = 0; i < kUpsampleKnotCount; ++i) shape[i] = std::fmax(double(knots[i]), 0.0) / luminance;
  return EmissionSpectrum(shape, emission_scale_ * luminance, illuminant_);
}

}  // namespace rimu
