#include "broadcast.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "spectral/colorimetry/colour_value_check.h"

namespace rimu::python {
namespace {

std::vector<py::ssize_t> shape_of(const py::array& a) { return std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()); }

std::string shape_text(const std::vector<py::ssize_t>& shape) {
  std::string out = "(";
  for (size_t d = 0; d < shape.size(); ++d) out += (d ? ", " : "") + std::to_string(shape[d]);
  return out + (shape.size() == 1 ? ",)" : ")");
}

}  // namespace

Array numeric_array(const py::handle& value, const std::string& name) {
  const py::array any = py::array::ensure(value);
  if (!any) throw InputError(argument(name), "expected numbers (a number, a list or a numpy array)");
  const char kind = any.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw InputError(argument(name), "expected real numbers (a float or integer array), got an array of dtype " +
                                         std::string(py::str(any.dtype())));
  return Array::ensure(any);
}

Colours colours_of(const py::handle& value, const std::string& name) {
  Colours c{numeric_array(value, name), {}};
  const std::vector<py::ssize_t> shape = shape_of(c.values);
  if (shape.empty() || shape.back() != 3)
    throw InputError(argument(name), "expected 3 values, or an array of shape (..., 3); got shape " + shape_text(shape));
  c.leading.assign(shape.begin(), shape.end() - 1);
  py::gil_scoped_release release;
  for_each_colour_checked(c, name, [](const double* v, const SourceLocation& at) {
    check_colour_components(v[0], v[1], v[2], at);
  });
  return c;
}

Colours whites_of(const py::handle& value, const std::string& name) {
  Colours w = colours_of(value, name);
  check_each(w, name, [](const Xyz& v, const SourceLocation& at) { check_white_xyz(v, at); });
  return w;
}

py::array_t<double> transform_colours(const py::object& value, const std::string& name, const Matrix3& matrix) {
  const Colours c = colours_of(value, name);
  return map_items<3>(c.leading, c.count(), [&](std::size_t i) {
    const Xyz v = matrix.apply(xyz_at(c, i));
    return std::array<double, 3>{v.x, v.y, v.z};
  });
}

void broadcast_colours(Colours& a, const std::string& a_name, Colours& b, const std::string& b_name) {
  if (a.leading == b.leading) return;
  // numpy's rule: shapes aligned at the right; each pair of dimensions equal, or one of them 1 or missing.
  const size_t rank = std::max(a.leading.size(), b.leading.size());
  std::vector<py::ssize_t> leading(rank);
  for (size_t d = 0; d < rank; ++d) {
    const auto dim = [&](const Colours& c) {
      const size_t missing = rank - c.leading.size();
      return d < missing ? py::ssize_t(1) : c.leading[d - missing];
    };
    const py::ssize_t da = dim(a), db = dim(b);
    if (da != db && da != 1 && db != 1)
      throw InputError(argument(b_name), "shape " + shape_text(b.leading) + " does not broadcast with " + a_name +
                                             "'s " + shape_text(a.leading) + " (the colour axis of 3 left out)");
    leading[d] = da == 1 ? db : da;
  }
  for (Colours* c : {&a, &b}) {
    if (c->leading == leading) continue;
    if (c->count() == 1) {  // one colour for all (a white for an image): read in place, no copy
      c->leading = leading;
      c->step = 0;
      continue;
    }
    // Colour i of the result reads the colour of c whose indices are i's, with 0 along c's dimensions of 1.
    std::vector<py::ssize_t> full = leading;
    full.push_back(3);
    Array copy(full);
    double* out = copy.mutable_data();
    const size_t missing = rank - c->leading.size();
    const py::ssize_t count = copy.size() / 3;
    for (py::ssize_t i = 0; i < count; ++i) {
      py::ssize_t rest = i, source = 0, stride = 1;
      for (size_t d = rank; d-- > 0;) {
        const py::ssize_t index = rest % leading[d];
        rest /= leading[d];
        if (d < missing) continue;
        const py::ssize_t extent = c->leading[d - missing];
        source += (extent == 1 ? 0 : index) * stride;
        stride *= extent;
      }
      std::copy_n(c->at(size_t(source)), 3, out + 3 * i);
    }
    c->values = std::move(copy);
    c->leading = leading;
  }
}

py::array_t<double> result_array(const std::vector<py::ssize_t>& leading, py::ssize_t n) {
  std::vector<py::ssize_t> shape = leading;
  if (n > 0) shape.push_back(n);
  return py::array_t<double>(shape);
}

py::object scalar_if_single(py::array_t<double> result, const std::vector<py::ssize_t>& leading) {
  if (leading.empty() && result.ndim() == 0) return py::float_(result.data()[0]);
  return result;
}

void for_each_range(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body) {
  py::gil_scoped_release release;
  if (count < kParallelCount) {
    body(0, count);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

}  // namespace rimu::python
