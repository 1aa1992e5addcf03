#include "spectral/upsampling/sigmoid_polynomial.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/upsampling/dense_linear_solve.h"
#include "spectral/upsampling/upsampling_whites.h"

namespace rimu {

namespace {

constexpr double kFirstNm = 360.0, kLastNm = 830.0;
constexpr double kSpanNm = kLastNm - kFirstNm;

// S(x) = ½ + x / (2√(1 + x²)); the infinite limits are the constants 0 and 1.
double sigmoid(double x) {
  if (std::isinf(x)) return x > 0 ? 1.0 : 0.0;
  return 0.5 + x / (2.0 * std::sqrt(1.0 + x * x));
}

// Coefficients of a polynomial in t = (λ − 360)/470, the variable the fit works in (so the three unknowns have
// comparable scales), as coefficients of the same polynomial in λ itself.
SigmoidPolynomial in_nanometres(const std::array<double, 3>& a) {
  const double s = 1.0 / kSpanNm, o = kFirstNm;
  // a0 t² + a1 t + a2 with t = s(λ − o)
  return {a[0] * s * s, a[1] * s - 2.0 * a[0] * s * s * o, a[0] * s * s * o * o - a[1] * s * o + a[2]};
}

std::string describe(const Rgb& rgb) {
  std::ostringstream s;
  s << "(" << rgb.r << ", " << rgb.g << ", " << rgb.b << ")";
  return s.str();
}

void require_finite_non_negative(const Rgb& rgb, const char* what, const SourceLocation& where) {
  for (double v : {rgb.r, rgb.g, rgb.b})
    if (!std::isfinite(v) || v < 0)
      throw InputError(where, std::string(what) + " " + describe(rgb) + ": every component must be finite and >= 0");
}

}  // namespace

SigmoidPolynomial SigmoidPolynomial::constant(double v) {
  if (v <= 0) return {0, 0, -std::numeric_limits<double>::infinity()};
  if (v >= 1) return {0, 0, std::numeric_limits<double>::infinity()};
  return {0, 0, (v - 0.5) / std::sqrt(v * (1.0 - v))};
}

double SigmoidPolynomial::value(double lambda_nm) const {
  if (std::isinf(c2)) return c2 > 0 ? 1.0 : 0.0;
  return sigmoid((c0 * lambda_nm + c1) * lambda_nm + c2);
}

SigmoidFitter::SigmoidFitter(SpectralLibrary& library, const RgbColourSpace& space) : space_(space) {
  const TabulatedSpectrum illuminant = upsampling_illuminant(library, upsampling_white_for(space.white()));
  const Observer& observer = library.observer(StandardObserver::cie1931_2deg);
  double y_sum = 0;
  for (double nm = kFirstNm; nm <= kLastNm; nm += 1.0) {
    const double e = illuminant.value(nm);
    lambda_nm_.push_back(nm);
    wx_.push_back(observer.x_bar.value(nm) * e);
    wy_.push_back(observer.y_bar.value(nm) * e);
    wz_.push_back(observer.z_bar.value(nm) * e);
    y_sum += wy_.back();
  }
  for (size_t i = 0; i < lambda_nm_.size(); ++i) {
    wx_[i] /= y_sum;
    wy_[i] /= y_sum;
    wz_[i] /= y_sum;
    illuminant_white_.x += wx_[i];
    illuminant_white_.y += wy_[i];
    illuminant_white_.z += wz_[i];
  }
  space_white_ = space_.to_xyz({1, 1, 1});
}

Xyz SigmoidFitter::xyz_of(const SigmoidPolynomial& p) const {
  Xyz xyz;
  for (size_t i = 0; i < lambda_nm_.size(); ++i) {
    const double s = p.value(lambda_nm_[i]);
    xyz.x += s * wx_[i];
    xyz.y += s * wy_[i];
    xyz.z += s * wz_[i];
  }
  return xyz;
}

Rgb SigmoidFitter::rgb_of(const SigmoidSpectrum& s) const {
  Xyz xyz = xyz_of(s.polynomial);
  // The spectrum's colour relative to the illuminant's white, read in the space (white to white).
  xyz = {xyz.x * s.scale * space_white_.x / illuminant_white_.x, xyz.y * s.scale * space_white_.y / illuminant_white_.y,
         xyz.z * s.scale * space_white_.z / illuminant_white_.z};
  return space_.from_xyz(xyz);
}

double SigmoidFitter::delta_e_ab(const Rgb& rgb, const SigmoidSpectrum& s) const {
  const double k = s.scale > 0 ? 1.0 / s.scale : 0.0;
  const Lab target = lab_of(space_.to_xyz({rgb.r * k, rgb.g * k, rgb.b * k}), space_white_);
  return delta_e_1976(target, lab_of(xyz_of(s.polynomial), illuminant_white_));
}

SigmoidSpectrum SigmoidFitter::fit(const Rgb& rgb) const {
  // Polynomial in t = (λ − 360)/470, evaluated on the grid.
  std::vector<double> t(lambda_nm_.size());
  for (size_t i = 0; i < t.size(); ++i) t[i] = (lambda_nm_[i] - kFirstNm) / kSpanNm;
  const auto lab_at = [&](const std::array<double, 3>& a) {
    Xyz xyz;
    for (size_t i = 0; i < t.size(); ++i) {
      const double s = sigmoid((a[0] * t[i] + a[1]) * t[i] + a[2]);
      xyz.x += s * wx_[i];
      xyz.y += s * wy_[i];
      xyz.z += s * wz_[i];
    }
    return lab_of(xyz, illuminant_white_);
  };
  const auto residual = [&](const std::array<double, 3>& a, const Lab& target) {
    const Lab lab = lab_at(a);
    return std::array<double, 3>{lab.l - target.l, lab.a - target.a, lab.b - target.b};
  };
  const auto norm = [](const std::array<double, 3>& r) { return std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]); };

  // Continuation from the constant ½ (a = 0, RGB (½, ½, ½)) to the colour in kSteps targets on the straight line,
  // each solved from the previous solution.
  constexpr int kSteps = 16;
  std::array<double, 3> a{0, 0, 0};
  for (int step = 1; step <= kSteps; ++step) {
    const double u = double(step) / kSteps;
    const Rgb along{0.5 + u * (rgb.r - 0.5), 0.5 + u * (rgb.g - 0.5), 0.5 + u * (rgb.b - 0.5)};
    const Lab target = lab_of(space_.to_xyz(along), space_white_);
    std::array<double, 3> r = residual(a, target);
    double r_norm = norm(r);
    const int iterations = step == kSteps ? 300 : 50;
    double mu = 1e-3;
    for (int it = 0; it < iterations && r_norm > 1e-9; ++it) {
      // Jacobian ∂Lab/∂a by central differences (the residual is smooth in a).
      std::array<std::array<double, 3>, 3> jacobian{};
      for (int k = 0; k < 3; ++k) {
        const double h = 1e-5 * std::max(1.0, std::abs(a[k]));
        std::array<double, 3> plus = a, minus = a;
        plus[k] += h;
        minus[k] -= h;
        const std::array<double, 3> rp = residual(plus, target), rm = residual(minus, target);
        for (int row = 0; row < 3; ++row) jacobian[row][k] = (rp[row] - rm[row]) / (2 * h);
      }
      // Levenberg–Marquardt: (JᵀJ + μ·diag(JᵀJ))·δ = −Jᵀr, μ shrinking after a step that lowers |r| and growing
      // after one that does not; near the solution it is the Gauss–Newton step, where the sigmoid saturates and J
      // is nearly singular it turns towards the gradient.
      std::array<std::array<double, 3>, 3> jtj{};
      std::array<double, 3> jtr{};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
          for (int row = 0; row < 3; ++row) jtj[i][j] += jacobian[row][i] * jacobian[row][j];
        for (int row = 0; row < 3; ++row) jtr[i] -= jacobian[row][i] * r[row];
      }
      bool improved = false;
      for (int attempt = 0; attempt < 40 && !improved; ++attempt) {
        std::array<std::array<double, 3>, 3> damped = jtj;
        for (int i = 0; i < 3; ++i) damped[i][i] += mu * std::max(jtj[i][i], 1e-12);
        std::vector<double> m{damped[0][0], damped[0][1], damped[0][2], damped[1][0], damped[1][1], damped[1][2],
                              damped[2][0], damped[2][1], damped[2][2]};
        std::vector<double> delta(jtr.begin(), jtr.end());
        if (solve_dense(m, delta, 3) &&
            std::isfinite(delta[0]) && std::isfinite(delta[1]) && std::isfinite(delta[2])) {
          const std::array<double, 3> trial{a[0] + delta[0], a[1] + delta[1], a[2] + delta[2]};
          const std::array<double, 3> rt = residual(trial, target);
          const double rt_norm = norm(rt);
          if (rt_norm < r_norm) {
            a = trial;
            r = rt;
            r_norm = rt_norm;
            improved = true;
            mu = std::max(mu / 3.0, 1e-12);
            break;
          }
        }
        mu *= 4.0;
      }
      if (!improved) break;  // a minimum the line cannot leave: the colour lies beyond the reachable gamut
    }
  }
  SigmoidSpectrum result{in_nanometres(a), 1.0, 0.0};
  result.delta_e_ab = delta_e_ab(rgb, result);
  return result;
}

SigmoidSpectrum SigmoidFitter::fit_albedo(const Rgb& rgb, const SourceLocation& where) const {
  require_finite_non_negative(rgb, "RGB reflectance", where);
  if (rgb.r > 1 || rgb.g > 1 || rgb.b > 1)
    throw InputError(where, "RGB reflectance " + describe(rgb) + ": every component must be <= 1");
  if (rgb.r == rgb.g && rgb.g == rgb.b) return {SigmoidPolynomial::constant(rgb.r), 1.0, 0.0};
  return fit(rgb);
}

SigmoidSpectrum SigmoidFitter::fit_unbounded(const Rgb& rgb, const SourceLocation& where) const {
  require_finite_non_negative(rgb, "unbounded RGB", where);
  const double m = 2.0 * std::max({rgb.r, rgb.g, rgb.b});
  if (m == 0) return {SigmoidPolynomial::constant(0), 0.0, 0.0};
  SigmoidSpectrum s = fit_albedo({rgb.r / m, rgb.g / m, rgb.b / m}, where);
  s.scale = m;
  return s;
}

}  // namespace rimu
