// Composite Simpson's rule: the smooth one-dimensional integrals tabulated at load time (a coat's diffuse
// Fresnel reflectance and its internal reflectance) are evaluated with it.
#pragma once

namespace rimu {

/// ∫ g(x) dx over [a, b] by composite Simpson with `intervals` panels (an even number).
template <typename G>
double simpson_integral(const G& g, double a, double b, int intervals) {
  const double h = (b - a) / intervals;
  double sum = 0.0;
  for (int i = 0; i <= intervals; ++i) {
    const double weight = (i == 0 || i == intervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * g(a + i * h);
  }
  return sum * h / 3.0;
}

}  // namespace rimu
