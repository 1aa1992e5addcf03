#include "spectral/colorimetry/chromaticity.h"

namespace rimu {

Chromaticity chromaticity_of(const Xyz& c) {
  const double sum = c.x + c.y + c.z;
  if (sum == 0.0) return {0.0, 0.0};
  return {c.x / sum, c.y / sum};
}

Xyz xyz_from_xyY(Chromaticity xy, double luminance_y) {
  if (xy.y == 0.0) return {};
  return {xy.x * luminance_y / xy.y, luminance_y, (1.0 - xy.x - xy.y) * luminance_y / xy.y};
}

Uv1960 uv1960_of(const Xyz& c) {
  const double d = c.x + 15.0 * c.y + 3.0 * c.z;
  if (d == 0.0) return {};
  return {4.0 * c.x / d, 6.0 * c.y / d};
}

Uv1976 uv1976_of(const Xyz& c) {
  const double d = c.x + 15.0 * c.y + 3.0 * c.z;
  if (d == 0.0) return {};
  return {4.0 * c.x / d, 9.0 * c.y / d};
}

Uv1960 uv1960_of(Chromaticity xy) {
  const double d = -2.0 * xy.x + 12.0 * xy.y + 3.0;
  return {4.0 * xy.x / d, 6.0 * xy.y / d};
}

Uv1976 uv1976_of(Chromaticity xy) {
  const double d = -2.0 * xy.x + 12.0 * xy.y + 3.0;
  return {4.0 * xy.x / d, 9.0 * xy.y / d};
}

Chromaticity chromaticity_of(Uv1960 uv) {
  const double d = 2.0 * uv.u - 8.0 * uv.v + 4.0;
  return {3.0 * uv.u / d, 2.0 * uv.v / d};
}

}  // namespace rimu
