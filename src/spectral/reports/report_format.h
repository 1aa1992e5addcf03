// printf-style formatting of up to three numbers for the reports' text lines.
#pragma once

#include <cstdio>
#include <string>

namespace rimu {

/// `pattern` (a printf format taking up to three doubles) applied to a, b, c; lines longer than 199 characters are
/// cut (the reports' lines are far shorter).
inline std::string format_numbers(const char* pattern, double a, double b = 0, double c = 0) {
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, pattern, a, b, c);
  return buffer;
}

}  // namespace rimu
