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
  std::size_t step = 3;              ///< numbers from one colour to the next: 0 once one colour serves them all
  /// How many colours the leading shape holds (after broadcasting, more than `values` may store).
  std::size_t count() const {
    std::size_t n = 1;
    for (py::ssize_t d : leading) n *= std::size_t(d);
    return n;
  }
  const double* at(std::size_t i) const { return values.data() + step * i; }
};
Colours colours_of(const py::handle& value, const std::string& name);

/// check(colour, where) for every colour of `c` in order; a refusal is re-raised naming the colour's indices
/// ("xyz[4, 7]"; a single colour by `name` alone). The place is built only then: the loop costs the checks alone.
template <typename Check>
void for_each_colour_checked(const Colours& c, const std::string& name, Check check) {
  const SourceLocation nowhere;
  for (std::size_t i = 0; i < c.count(); ++i) {
    try {
      check(c.at(i), nowhere);
    } catch (const InputError& e) {
      throw InputError(argument(c.leading.empty() ? name : element_name(name, c.leading, py::ssize_t(i))),
                       e.explanation());
    }
  }
}

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
