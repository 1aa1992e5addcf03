// Broadcasting for the colour functions: (..., 3) arrays of colours and (..., N) stacks of spectra in, arrays of the
// same leading shape out, with the loop in C++ and the GIL released (parallel chunks for large inputs).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "bindings.h"

namespace rimu::python {

/// A numeric argument as a C-contiguous float64 array: float and integer arrays of any strides (and lists, numbers)
/// are converted; bool, complex, object and string data are refused with a ValueError naming `name` (converting
/// them would drop an imaginary part or read True as 1 without a word).
Array numeric_array(const py::handle& value, const std::string& name);

/// A (..., 3) array of colours, converted by numeric_array, every component checked (check_colour_components,
/// named by its indices: "xyz[4, 7]").
struct Colours {
  Array values;
  std::vector<py::ssize_t> leading;  ///< the shape before the last axis; empty for a single colour
  std::size_t count() const { return std::size_t(values.size() / 3); }
  const double* at(std::size_t i) const { return values.data() + 3 * i; }
};
Colours colours_of(const py::handle& value, const std::string& name);

/// `a` and `b` brought to one leading shape by numpy's broadcasting rules (a single colour pairs with every colour
/// of the other). ValueError naming `b_name` if the shapes do not broadcast.
void broadcast_colours(Colours& a, const std::string& a_name, Colours& b, const std::string& b_name);

/// A new float64 array of shape leading + (n,), or leading alone when n == 0.
py::array_t<double> result_array(const std::vector<py::ssize_t>& leading, py::ssize_t n);
/// `result` itself, or a Python float when it holds a single number with no leading shape.
py::object scalar_if_single(py::array_t<double> result, const std::vector<py::ssize_t>& leading);

/// Calls body(begin, end) over [0, count) with the GIL released: in one piece for small counts, in parallel
/// chunks (oneTBB) from kParallelCount on. `body` must not touch Python objects.
inline constexpr std::size_t kParallelCount = 16384;
void for_each_range(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body);

}  // namespace rimu::python
