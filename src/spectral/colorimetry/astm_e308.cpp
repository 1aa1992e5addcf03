#include "spectral/colorimetry/astm_e308.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "spectral/error.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu {
namespace {

/// The Lagrange basis polynomial k of the nodes 0, 1, …, points−1, at x.
double lagrange_basis(int points, int k, double x) {
  double value = 1.0;
  for (int m = 0; m < points; ++m)
    if (m != k) value *= (x - m) / double(k - m);
  return value;
}

bool near(double a, double b) { return std::abs(a - b) < 1e-6; }

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

}  // namespace

std::vector<double> e308_lagrange_coefficients(int points, double position) {
  std::vector<double> c(static_cast<size_t>(points), 0.0);
  for (int k = 0; k < points; ++k) c[size_t(k)] = lagrange_basis(points, k, position);
  return c;
}

TabulatedSpectrum e308_interpolate_to_1nm(const TabulatedSpectrum& data) {
  const auto& l = data.wavelengths_nm();
  const auto& v = data.values();
  const int n = int(l.size());
  const int step = n >= 2 ? int(std::lround(l[1] - l[0])) : 0;
  bool even = n >= 3 && step >= 1 && near(l[0], std::round(l[0]));
  for (int i = 1; even && i < n; ++i) even = near(l[size_t(i)] - l[size_t(i - 1)], step);
  if (!even)
    throw InputError({}, "'" + data.describe() + "': interpolating to 1 nm needs at least 3 samples evenly spaced "
                                                 "on whole nanometres");
  std::vector<double> nm_out, value_out;
  const int first = int(std::lround(l.front())), last = first + (n - 1) * step;
  for (int nm = first; nm <= last; ++nm) {
    const int interval = std::min((nm - first) / step, n - 2);
    const double r = double(nm - first - interval * step) / step;
    double value = 0.0;
    if (r == 0.0) {
      value = v[size_t(interval)];
    } else if (interval == 0) {
      const auto c = e308_lagrange_coefficients(3, r);
      for (int k = 0; k < 3; ++k) value += c[size_t(k)] * v[size_t(k)];
    } else if (interval == n - 2) {
      const auto c = e308_lagrange_coefficients(3, 1.0 + r);
      for (int k = 0; k < 3; ++k) value += c[size_t(k)] * v[size_t(n - 3 + k)];
    } else {
      const auto c = e308_lagrange_coefficients(4, 1.0 + r);
      for (int k = 0; k < 4; ++k) value += c[size_t(k)] * v[size_t(interval - 1 + k)];
    }
    nm_out.push_back(nm);
    value_out.push_back(value);
  }
  return TabulatedSpectrum(std::move(nm_out), std::move(value_out), Extrapolation::zero, data.describe() + ", 1 nm");
}

E308WeightTable compute_e308_weights(const Spectrum& illuminant, const Observer& observer, double interval_nm,
                                     const std::string& illuminant_name, double first_nm, double last_nm) {
  const int step = int(std::lround(interval_nm));
  assert(step >= 2 && near(step, interval_nm));
  const int count = int((last_nm - first_nm) / step) + 1;  // 20 nm over 360-830: 360 … 820
  assert(count >= 4);
  E308WeightTable table{illuminant_name, observer.name, first_nm, interval_nm, std::vector<Xyz>(size_t(count))};

  double white_y = 0.0;  // Σ S ȳ over the same 1 nm points: k = 100 / white_y
  const int last_point = int(first_nm) + (count - 1) * step;
  for (int nm = int(first_nm); nm <= last_point; ++nm) {
    const double s = illuminant.value(nm);
    const Xyz product{s * observer.x_bar.value(nm), s * observer.y_bar.value(nm), s * observer.z_bar.value(nm)};
    white_y += product.y;
    const int interval = (nm - int(first_nm)) / step;  // the interval [interval, interval+1] holding nm
    const int offset = (nm - int(first_nm)) % step;
    auto add = [&](int j, double c) {
      table.weights[size_t(j)].x += c * product.x;
      table.weights[size_t(j)].y += c * product.y;
      table.weights[size_t(j)].z += c * product.z;
    };
    if (offset == 0) {  // on a sample: the interpolant is the sample itself
      add(interval, 1.0);
      continue;
    }
    const double r = double(offset) / step;
    if (interval == 0) {  // first interval: quadratic through samples 0, 1, 2
      const auto c = e308_lagrange_coefficients(3, r);
      for (int k = 0; k < 3; ++k) add(k, c[size_t(k)]);
    } else if (interval == count - 2) {  // last interval: quadratic through the last three samples
      const auto c = e308_lagrange_coefficients(3, 1.0 + r);
      for (int k = 0; k < 3; ++k) add(count - 3 + k, c[size_t(k)]);
    } else {  // inside: cubic through the two samples either side
      const auto c = e308_lagrange_coefficients(4, 1.0 + r);
      for (int k = 0; k < 4; ++k) add(interval - 1 + k, c[size_t(k)]);
    }
  }
  const double k = 100.0 / white_y;
  for (Xyz& w : table.weights) w = {k * w.x, k * w.y, k * w.z};
  return table;
}

int e308_table_number(E308Table table) { return table == E308Table::table5_uncorrected ? 5 : 6; }

std::string e308_table_description(E308Table table) {
  return table == E308Table::table5_uncorrected
             ? "ASTM E308 Table 5 (weights for spectral data not corrected for bandpass)"
             : "ASTM E308 Table 6 (weights for spectral data corrected for bandpass)";
}

namespace {

/// T·v for the Stearns correction matrix T (symmetric, tridiagonal): the same formula serves for data (R' = T R)
/// and weights (W5 = Tᵀ W6 = T W6).
template <typename T>
std::vector<T> stearns_apply(const std::vector<T>& v) {
  const size_t n = v.size();
  const double a = kStearnsAlpha;
  std::vector<T> out(n);
  for (size_t i = 0; i < n; ++i) {
    if (i == 0) out[i] = (1 + a) * v[0] - a * v[1];
    else if (i == n - 1) out[i] = (1 + a) * v[n - 1] - a * v[n - 2];
    else out[i] = (1 + 2 * a) * v[i] - a * (v[i - 1] + v[i + 1]);
  }
  return out;
}

}  // namespace

E308WeightTable e308_table5_from_table6(const E308WeightTable& table6) {
  assert(table6.weights.size() >= 2);
  std::vector<double> x, y, z;
  for (const Xyz& w : table6.weights) {
    x.push_back(w.x);
    y.push_back(w.y);
    z.push_back(w.z);
  }
  x = stearns_apply(x);
  y = stearns_apply(y);
  z = stearns_apply(z);
  E308WeightTable table5 = table6;
  for (size_t j = 0; j < table5.weights.size(); ++j) table5.weights[j] = {x[j], y[j], z[j]};
  return table5;
}

TabulatedSpectrum stearns_bandpass_correction(const TabulatedSpectrum& data) {
  if (data.values().size() < 2)
    throw InputError({}, "'" + data.describe() + "': the bandpass correction needs at least 2 samples");
  return TabulatedSpectrum(data.wavelengths_nm(), stearns_apply(data.values()), data.extrapolation(),
                           data.describe() + ", bandpass-corrected (Stearns & Stearns)");
}

E308WeightTable fold_e308_weights(const E308WeightTable& table, double first_nm, double last_nm) {
  E308WeightTable folded = table;
  folded.first_nm = first_nm;
  folded.weights.clear();
  for (size_t j = 0; j < table.weights.size(); ++j) {
    const double nm = table.wavelength_nm(j);
    const Xyz& w = table.weights[j];
    if (nm <= first_nm + 1e-6 && !folded.weights.empty()) {
      folded.weights.front() = {folded.weights.front().x + w.x, folded.weights.front().y + w.y,
                                folded.weights.front().z + w.z};
    } else if (nm > last_nm + 1e-6) {
      folded.weights.back() = {folded.weights.back().x + w.x, folded.weights.back().y + w.y,
                               folded.weights.back().z + w.z};
    } else {
      folded.weights.push_back(w);
    }
  }
  return folded;
}

Xyz apply_e308_weights(const TabulatedSpectrum& data, const E308WeightTable& table) {
  const auto& lambda = data.wavelengths_nm();
  const auto& values = data.values();
  const std::string what = "'" + data.describe() + "'";
  const double step = lambda[1] - lambda[0];
  for (size_t i = 1; i < lambda.size(); ++i)
    if (!near(lambda[i] - lambda[i - 1], table.interval_nm))
      throw InputError({}, "ASTM E308 weights are for data every " + number(table.interval_nm) + " nm; " + what +
                               " has a step of " + number(lambda[i] - lambda[i - 1]) + " nm at " +
                               number(lambda[i - 1]) + " nm (use --method 1nm or native)");
  (void)step;
  if (lambda.front() > kE308LatestStart_nm + 1e-6 || lambda.back() < kE308EarliestEnd_nm - 1e-6)
    throw InputError({}, "ASTM E308 needs data from " + number(kE308LatestStart_nm) + " nm or below to " +
                             number(kE308EarliestEnd_nm) + " nm or above (it would extend the end values over the "
                             "unmeasured tails); " + what + " covers " + number(lambda.front()) + "-" +
                             number(lambda.back()) + " nm");
  const double offset = (lambda.front() - table.first_nm) / table.interval_nm;
  if (!near(offset, std::round(offset)))
    throw InputError({}, what + " starts at " + number(lambda.front()) + " nm, between the " +
                             number(table.interval_nm) + " nm grid points of the E308 weights (which start at " +
                             number(table.first_nm) + " nm)");
  // Only the data inside the weights' range count; the weights of missing wavelengths go to the end samples.
  const double first = std::max(lambda.front(), table.first_nm);
  const double last = std::min(lambda.back(), table.last_nm());
  const E308WeightTable folded = fold_e308_weights(table, first, last);
  Xyz xyz;
  for (size_t i = 0; i < lambda.size(); ++i) {
    if (lambda[i] < first - 1e-6 || lambda[i] > last + 1e-6) continue;
    const size_t j = size_t(std::lround((lambda[i] - first) / table.interval_nm));
    const Xyz& w = folded.weights[j];
    xyz.x += values[i] * w.x;
    xyz.y += values[i] * w.y;
    xyz.z += values[i] * w.z;
  }
  return xyz;
}

std::string e308_weights_csv(const E308WeightTable& table, const std::string& comment) {
  std::ostringstream out;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  out << "wavelength_nm,Wx,Wy,Wz\n";
  char buffer[128];
  for (size_t j = 0; j < table.weights.size(); ++j) {
    const Xyz& w = table.weights[j];
    std::snprintf(buffer, sizeof buffer, "%g,%.9f,%.9f,%.9f\n", table.wavelength_nm(j), w.x, w.y, w.z);
    out << buffer;
  }
  return out.str();
}

E308WeightTable e308_weights_from_csv(const CsvTable& csv, const std::string& illuminant, const std::string& observer) {
  const std::vector<double> lambda = csv.numbers(0);
  const std::vector<double> wx = csv.numbers(csv.column_index("Wx"));
  const std::vector<double> wy = csv.numbers(csv.column_index("Wy"));
  const std::vector<double> wz = csv.numbers(csv.column_index("Wz"));
  if (lambda.size() < 4) throw InputError({csv.name(), 0, ""}, "an E308 weight table needs at least 4 rows");
  E308WeightTable table{illuminant, observer, lambda[0], lambda[1] - lambda[0], {}};
  for (size_t j = 0; j < lambda.size(); ++j) {
    if (!near(lambda[j], table.wavelength_nm(j)))
      throw InputError({csv.name(), csv.line_of_row(j), ""}, "E308 weights must be evenly spaced");
    table.weights.push_back({wx[j], wy[j], wz[j]});
  }
  return table;
}

}  // namespace rimu
