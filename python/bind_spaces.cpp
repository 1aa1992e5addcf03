// RGB spaces' matrices, chromatic adaptation and the sRGB curve; and the RGB upsampler (which needs tables:
// rimu.Library.upsample_*). xy, CIELAB, ΔE and RGB <-> XYZ over arrays are in bind_colour_arrays.cpp.
#include <pybind11/stl.h>

#include "bindings.h"
#include "broadcast.h"
#include "spectral/colour_spaces/chromatic_adaptation.h"
#include "spectral/error.h"
#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/upsampling/rgb_upsampler.h"
#include "spectral/reports/upsample_report.h"

namespace rimu::python {
namespace {

Xyz xyz_of(const Array& a, const std::string& name) {
  const auto t = read_triple(a, name);
  return {t[0], t[1], t[2]};
}

Rgb rgb_of(const Array& a, const std::string& name) {
  const auto t = read_triple(a, name);
  return {t[0], t[1], t[2]};
}

Xyz white_of(const Array& a, const std::string& name) {
  const Xyz w = xyz_of(a, name);
  check_white_xyz(w, argument(name));
  return w;
}

// (wavelengths_nm, values at 1 nm, gamut_mapped) of upsample_colour, the checks and the upsampling
// `rimu-colour upsample` uses.
py::tuple upsampled_arrays(SpectralLibrary& library, const Array& rgb, const std::string& space, bool emission) {
  const Rgb c = rgb_of(rgb, "rgb");
  const RgbUpsampler upsampler(library, space_named(space, "space"));
  const UpsampledColour u = upsample_colour(upsampler, c, emission, argument("rgb"));
  const py::tuple arrays = arrays_at_1nm(*u.spectrum);
  return py::make_tuple(arrays[0], arrays[1], u.gamut_mapped);
}

// f of every element of argument `name` (check_colour_component first), in an array of its shape; a number for a
// number.
FloatOrArray per_element(const Array& a, const std::string& name, double (*f)(double)) {
  const std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
  py::array_t<double> out(shape);
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    check_colour_component(a.data()[i], argument(element_name(name, shape, i)));
    out.mutable_data()[i] = f(a.data()[i]);
  }
  if (a.ndim() == 0) return FloatOrArray(py::float_(out.data()[0]));
  return FloatOrArray(std::move(out));
}

py::array_t<double> matrix_array(const Matrix3& m) {
  py::array_t<double> out({3, 3});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.mutable_at(i, j) = m(i, j);
  return out;
}

}  // namespace

void bind_spaces(py::module_& m) {
  m.def("colour_spaces", &RgbColourSpace::names,
        "Names of the built-in RGB spaces (the `space` arguments).\n\nExample: 'acescg' in rimu.colour_spaces()");
  m.def(
      "rgb_conversion_matrix",
      [](const std::string& source, const std::string& destination, const std::string& cat) {
        return matrix_array(rgb_conversion_matrix(space_named(source, "source"), space_named(destination, "destination"),
                                                  cat_method_option(cat, argument("cat"))));
      },
      py::arg("source"), py::arg("destination"), py::arg("cat") = "bradford",
      "3x3 matrix from linear RGB in one space to another, adapting between their whites with `cat` (bradford, "
      "cat02, cat16, von-kries or xyz-scaling).\n\nExample: rimu.rgb_conversion_matrix('srgb-linear', 'acescg') @ rgb");
  m.def(
      "chromatic_adaptation_matrix",
      [](const Array& source_white, const Array& destination_white, const std::string& cat) {
        return matrix_array(chromatic_adaptation_matrix(white_of(source_white, "source_white"),
                                                        white_of(destination_white, "destination_white"),
                                                        cat_method_option(cat, argument("cat"))));
      },
      py::arg("source_white"), py::arg("destination_white"), py::arg("cat") = "bradford",
      "The 3x3 XYZ -> XYZ von Kries-type transform from source_white to destination_white (same scale) in the "
      "cone space of `cat` (bradford, cat02, cat16, von-kries or xyz-scaling); adapt() applies one to arrays.\n\n"
      "Example: rimu.chromatic_adaptation_matrix([95.047, 100, 108.883], [96.422, 100, 82.521])");
  m.def(
      "srgb_encode", [](const Array& linear) { return per_element(linear, "linear", &srgb_encode); }, py::arg("linear"),
      "The sRGB (IEC 61966-2-1) encoding curve, element by element: a float for a number, an array of the same "
      "shape for an array.\n\nExample: rimu.srgb_encode(0.18) -> 0.4614 (about)");
  m.def(
      "srgb_decode", [](const Array& encoded) { return per_element(encoded, "encoded", &srgb_decode); },
      py::arg("encoded"),
      "The sRGB decoding curve (the inverse of srgb_encode), element by element.\n\n"
      "Example: rimu.srgb_decode(0.5) -> 0.2140 (about)");

  auto lib = py::reinterpret_borrow<py::class_<SpectralLibrary>>(m.attr("Library"));
  lib.def(
         "upsample_reflectance",
         [](SpectralLibrary& l, const Array& rgb, const std::string& space) {
           return upsampled_arrays(l, rgb, space, false);
         },
         py::arg("rgb"), py::arg("space") = "srgb-linear",
         "The smoothest reflectance with this linear RGB (3,): (wavelengths_nm, values at 1 nm over 360-830 nm, "
         "gamut_mapped: True if the colour was moved into the reflectance gamut first).\n\n"
         "Example: wl, r, moved = lib.upsample_reflectance([0.8, 0.2, 0.1])")
      .def(
          "upsample_emission",
          [](SpectralLibrary& l, const Array& rgb, const std::string& space) {
            return upsampled_arrays(l, rgb, space, true);
          },
          py::arg("rgb"), py::arg("space") = "srgb-linear",
          "An emission spectrum with this linear RGB (3,): (wavelengths_nm, values at 1 nm over 360-830 nm, "
          "gamut_mapped).\n\nExample: wl, power, moved = lib.upsample_emission([1.0, 0.5, 0.2])");
}

}  // namespace rimu::python
