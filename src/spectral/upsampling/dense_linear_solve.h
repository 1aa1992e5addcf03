// A small dense linear solve for the upsamplers' fits (the smoothest spectrum's KKT system, the sigmoid fit's
// damped Gauss–Newton step): sizes of 3 to a few dozen, solved once per colour, so no library is worth it.
#pragma once

#include <vector>

namespace rimu {

/// Solves the dense system M·x = b in place (M row-major, size × size; x replaces b) by Gaussian elimination with
/// partial pivoting; false if M is singular.
bool solve_dense(std::vector<double>& m, std::vector<double>& b, int size);

}  // namespace rimu
