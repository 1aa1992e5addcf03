// The check a light-meter test makes (render/reports/light_meter.h): the reading's standard error is small enough to
// tell a `max_relative_error` mistake apart, and the reading lies within five standard errors of the exact value (a
// false alarm below 1e-6 under the normal approximation).
#pragma once

#include <doctest/doctest.h>

#include <cmath>

#include "render/reports/light_meter.h"

namespace rimu::test {

inline void check_reading(const MeterReading& r, double expected, double max_relative_error = 0.01) {
  CAPTURE(r.value);
  CAPTURE(r.standard_error);
  CAPTURE(expected);
  CHECK(r.standard_error < max_relative_error * expected);
  CHECK(std::abs(r.value - expected) <= 5.0 * r.standard_error + 1e-9 * expected);
}

}  // namespace rimu::test
