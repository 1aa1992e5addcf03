// Broadcasting for the colour functions: (..., 3) arrays of colours and (..., N) stacks of spectra in, arrays of the
// same leading shape out, with the loop in C++ and the GIL released (parallel chunks for large inputs).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "bindings.h"
#include "spectral/colour_spaces/matrix3.h"

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

inline Xyz xyz_at(const Colours& c, std::size_t i) { return {c.at(i)[0], c.at(i)[1], c.at(i)[2]}; }

/// Every colour of `c` through check(Xyz, where) (a refusal names the colour's indices), in order, without the GIL.
template <typename Check>
void check_each(const Colours& c, const std::string& name, Check check) {
  py::gil_scoped_release release;
  for_each_colour_checked(c, name, [&](const double* v, const SourceLocation& at) { check(Xyz{v[0], v[1], v[2]}, at); });
}

/// Argument `name` as (..., 3) whites: every one through check_white_xyz.
Colours whites_of(const py::handle& value, const std::string& name);

/// The 3x3 `matrix` applied to every colour of argument `name`: (..., 3) -> (..., 3).
py::array_t<double> transform_colours(const py::object& value, const std::string& name, const Matrix3& matrix);

/// An argument that takes any array-like (a number, a list, a numpy array of any dtype; converted and checked by
/// numeric_array): "numpy.typing.ArrayLike" in signatures.
inline bool accepts_anything(PyObject*) { return true; }
class ArrayLike : public py::object {
 public:
  PYBIND11_OBJECT_DEFAULT(ArrayLike, py::object, accepts_anything)
};

/// An optional rimu.Library argument (None: the module's shared one): "Library | None" in signatures.
class OptionalLibrary : public py::object {
 public:
  PYBIND11_OBJECT_DEFAULT(OptionalLibrary, py::object, accepts_anything)
};

/// A float for a single value, an array of the leading shape otherwise; "float | numpy.ndarray" in signatures.
class FloatOrArray : public py::object {
 public:
  FloatOrArray() = default;
  explicit FloatOrArray(py::object o) : py::object(std::move(o)) {}
};

/// out[i·N ...] = f(i) for every item of the leading shape: N numbers each, in an array of shape leading + (N,).
template <std::size_t N, typename F>
py::array_t<double> map_items(const std::vector<py::ssize_t>& leading, std::size_t count, F f) {
  py::array_t<double> out = result_array(leading, py::ssize_t(N));
  double* o = out.mutable_data();
  for_each_range(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::array<double, N> v = f(i);
      for (std::size_t k = 0; k < N; ++k) o[N * i + k] = v[k];
    }
  });
  return out;
}

/// One number per item: a float for a single one (no leading shape), an array of the leading shape otherwise.
template <typename F>
FloatOrArray map_scalars(const std::vector<py::ssize_t>& leading, std::size_t count, F f) {
  py::array_t<double> out = result_array(leading, 0);
  double* o = out.mutable_data();
  for_each_range(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) o[i] = f(i);
  });
  return FloatOrArray(scalar_if_single(std::move(out), leading));
}

}  // namespace rimu::python

namespace pybind11::detail {
template <>
struct handle_type_name<rimu::python::FloatOrArray> {
  static constexpr auto name = const_name("float | numpy.ndarray");
};
template <>
struct handle_type_name<rimu::python::ArrayLike> {
  static constexpr auto name = const_name("numpy.typing.ArrayLike");
};
template <>
struct handle_type_name<rimu::python::OptionalLibrary> {
  static constexpr auto name = const_name("Library | None");
};
}  // namespace pybind11::detail
