// π in double precision, defined once: the sources that need it include this rather than each defining its own
// (the libraries build as unity batches, where two file-local definitions of one name collide).
#pragma once

#include <numbers>

namespace rimu {

inline constexpr double kPi = std::numbers::pi;

}  // namespace rimu
