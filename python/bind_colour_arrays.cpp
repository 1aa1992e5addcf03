// The colour arithmetic over arrays: xy, CIELAB, ΔE and RGB <-> XYZ of a single colour, a (24, 3) stack or an
// (H, W, 3) image alike, through the checks the tools use (colour_value_check.h) and the loop in C++ without the GIL.
#include "bindings.h"
#include "broadcast.h"
#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/colour_spaces/rgb_colour_space.h"

namespace rimu::python {
namespace {

Xyz xyz_at(const Colours& c, std::size_t i) { return {c.at(i)[0], c.at(i)[1], c.at(i)[2]}; }
Lab lab_at(const Colours& c, std::size_t i) { return {c.at(i)[0], c.at(i)[1], c.at(i)[2]}; }

// Every colour of `c` through `check` (a refusal names the colour's indices), in order, without the GIL.
template <typename Check>
void check_each(const Colours& c, const std::string& name, Check check) {
  py::gil_scoped_release release;
  for_each_colour_checked(c, name, [&](const double* v, const SourceLocation& at) { check(Xyz{v[0], v[1], v[2]}, at); });
}

// out[i·n ...] = f(i) for every colour: n numbers per colour.
template <std::size_t N, typename F>
py::array_t<double> map_colours(const std::vector<py::ssize_t>& leading, std::size_t count, F f) {
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

// One number per pair of colours: a float for a single pair, an array of the leading shape otherwise.
template <typename F>
py::object map_pairs(const std::vector<py::ssize_t>& leading, std::size_t count, F f) {
  py::array_t<double> out = result_array(leading, 0);
  double* o = out.mutable_data();
  for_each_range(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) o[i] = f(i);
  });
  return scalar_if_single(std::move(out), leading);
}

// The 3x3 `matrix` applied to every colour of argument `name` (RgbColourSpace::to_xyz/from_xyz are this product).
py::array_t<double> transform_colours(const py::object& value, const std::string& name, const Matrix3& matrix) {
  const Colours c = colours_of(value, name);
  return map_colours<3>(c.leading, c.count(), [&](std::size_t i) {
    const Xyz v = matrix.apply(xyz_at(c, i));
    return std::array<double, 3>{v.x, v.y, v.z};
  });
}

py::object lab_of_arrays(const py::object& xyz, const py::object& white) {
  Colours x = colours_of(xyz, "xyz"), w = colours_of(white, "white");
  check_each(w, "white", [](const Xyz& v, const SourceLocation& at) { check_white_xyz(v, at); });
  broadcast_colours(x, "xyz", w, "white");
  return map_colours<3>(x.leading, x.count(), [&](std::size_t i) {
    const Lab l = lab_of(xyz_at(x, i), xyz_at(w, i));
    return std::array<double, 3>{l.l, l.a, l.b};
  });
}

template <typename Difference>
py::object delta_e_of_arrays(const py::object& lab1, const py::object& lab2, Difference difference) {
  Colours a = colours_of(lab1, "lab1"), b = colours_of(lab2, "lab2");
  broadcast_colours(a, "lab1", b, "lab2");
  return map_pairs(a.leading, a.count(), [&](std::size_t i) { return difference(lab_at(a, i), lab_at(b, i)); });
}

}  // namespace

void bind_colour_arrays(py::module_& m) {
  m.def(
      "xy",
      [](const py::object& xyz) {
        const Colours c = colours_of(xyz, "xyz");
        check_each(c, "xyz", [](const Xyz& v, const SourceLocation& at) { check_has_chromaticity(v, at); });
        return map_colours<2>(c.leading, c.count(), [&](std::size_t i) {
          const Chromaticity xy = chromaticity_of(xyz_at(c, i));
          return std::array<double, 2>{xy.x, xy.y};
        });
      },
      py::arg("xyz"),
      "CIE 1931 (x, y) of XYZ: shape (..., 3) -> (..., 2). Black (X + Y + Z <= 0) has none: ValueError naming it.");
  m.def("lab", &lab_of_arrays, py::arg("xyz"), py::arg("white"),
        "CIELAB of XYZ relative to a white on the same scale: xyz (..., 3) and white (3,) or broadcastable "
        "(..., 3) -> (..., 3).");
  m.def("xyz_to_lab", &lab_of_arrays, py::arg("xyz"), py::arg("white"), "The same as lab().");
  m.def(
      "delta_e_2000",
      [](const py::object& lab1, const py::object& lab2) {
        return delta_e_of_arrays(lab1, lab2, [](const Lab& a, const Lab& b) { return delta_e_2000(a, b); });
      },
      py::arg("lab1"), py::arg("lab2"),
        "CIEDE2000 (kL = kC = kH = 1) between two CIELAB arrays (..., 3) that broadcast: a float for one pair, an "
        "array of the leading shape otherwise.");
  m.def(
      "delta_e_1976",
      [](const py::object& lab1, const py::object& lab2) {
        return delta_e_of_arrays(lab1, lab2, [](const Lab& a, const Lab& b) { return delta_e_1976(a, b); });
      },
      py::arg("lab1"), py::arg("lab2"),
      "CIE 1976 ΔE*ab, broadcast as delta_e_2000.");
  m.def(
      "rgb_to_xyz",
      [](const py::object& rgb, const std::string& space) {
        return transform_colours(rgb, "rgb", space_named(space, "space").rgb_to_xyz());
      },
      py::arg("rgb"), py::arg("space") = "srgb-linear", "Linear RGB (..., 3) to XYZ (white at Y = 1).");
  m.def(
      "xyz_to_rgb",
      [](const py::object& xyz, const std::string& space) {
        return transform_colours(xyz, "xyz", space_named(space, "space").xyz_to_rgb());
      },
      py::arg("xyz"), py::arg("space") = "srgb-linear", "XYZ (..., 3) to linear RGB (no adaptation).");
}

}  // namespace rimu::python
