// Colour arithmetic that needs no tables: xy, CIELAB, ΔE, RGB spaces and chromatic adaptation; and the RGB
// upsampler (which does: rimu.Library.upsample_*).
#include <pybind11/stl.h>

#include "bindings.h"
#include "spectral/chromatic_adaptation.h"
#include "spectral/cielab.h"
#include "spectral/delta_e.h"
#include "spectral/error.h"
#include "spectral/rgb_upsampler.h"

namespace rimu::python {
namespace {

Xyz xyz_of(const Array& a, const char* what) {
  Xyz x;
  read3(a, x.x, x.y, x.z, what);
  return x;
}

Lab lab_of_array(const Array& a, const char* what) {
  Lab l;
  read3(a, l.l, l.a, l.b, what);
  return l;
}

CatMethod cat_of(const std::string& name) {
  if (name == "bradford") return CatMethod::bradford;
  if (name == "cat02") return CatMethod::cat02;
  if (name == "von-kries") return CatMethod::von_kries;
  if (name == "xyz-scaling") return CatMethod::xyz_scaling;
  throw InputError({}, "cat: expected bradford, cat02, von-kries or xyz-scaling, got '" + name + "'");
}

// (wavelengths_nm, values at 1 nm, gamut_mapped) of `upsample`(upsampler of `space`, `rgb`): the reflectance and
// emission upsamplings return the same shape of result.
template <typename Upsample>
py::tuple upsampled_arrays(SpectralLibrary& library, const Array& rgb, const std::string& space, Upsample upsample) {
  Rgb c;
  read3(rgb, c.r, c.g, c.b, "rgb");
  const RgbUpsampler upsampler(library, RgbColourSpace::named(space));
  const auto u = upsample(upsampler, c);
  const py::tuple arrays = arrays_at_1nm(u.spectrum);
  return py::make_tuple(arrays[0], arrays[1], u.gamut_mapped);
}

py::array_t<double> matrix_array(const Matrix3& m) {
  py::array_t<double> out({3, 3});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.mutable_at(i, j) = m(i, j);
  return out;
}

}  // namespace

void bind_spaces(py::module_& m) {
  m.def(
      "xy",
      [](const Array& xyz) {
        const Chromaticity c = chromaticity_of(xyz_of(xyz, "xyz"));
        py::array_t<double> out(2);
        out.mutable_data()[0] = c.x;
        out.mutable_data()[1] = c.y;
        return out;
      },
      py::arg("xyz"), "CIE 1931 (x, y) of XYZ.");
  m.def(
      "lab",
      [](const Array& xyz, const Array& white) {
        const Lab l = lab_of(xyz_of(xyz, "xyz"), xyz_of(white, "white"));
        return vec3(l.l, l.a, l.b);
      },
      py::arg("xyz"), py::arg("white"), "CIELAB of XYZ relative to a white on the same scale.");
  m.def(
      "delta_e_2000",
      [](const Array& a, const Array& b) { return delta_e_2000(lab_of_array(a, "lab1"), lab_of_array(b, "lab2")); },
      py::arg("lab1"), py::arg("lab2"), "CIEDE2000 (kL = kC = kH = 1).");
  m.def(
      "delta_e_1976",
      [](const Array& a, const Array& b) { return delta_e_1976(lab_of_array(a, "lab1"), lab_of_array(b, "lab2")); },
      py::arg("lab1"), py::arg("lab2"), "CIE 1976 ΔE*ab.");
  m.def("colour_spaces", &RgbColourSpace::names, "Names of the built-in RGB spaces.");
  m.def(
      "rgb_to_xyz",
      [](const Array& rgb, const std::string& space) {
        Rgb c;
        read3(rgb, c.r, c.g, c.b, "rgb");
        const Xyz x = RgbColourSpace::named(space).to_xyz(c);
        return vec3(x.x, x.y, x.z);
      },
      py::arg("rgb"), py::arg("space") = "srgb-linear", "Linear RGB to XYZ (white at Y = 1).");
  m.def(
      "xyz_to_rgb",
      [](const Array& xyz, const std::string& space) {
        const Rgb c = RgbColourSpace::named(space).from_xyz(xyz_of(xyz, "xyz"));
        return vec3(c.r, c.g, c.b);
      },
      py::arg("xyz"), py::arg("space") = "srgb-linear", "XYZ to linear RGB (no adaptation).");
  m.def(
      "rgb_conversion_matrix",
      [](const std::string& source, const std::string& destination, const std::string& cat) {
        return matrix_array(rgb_conversion_matrix(RgbColourSpace::named(source), RgbColourSpace::named(destination),
                                                  cat_of(cat)));
      },
      py::arg("source"), py::arg("destination"), py::arg("cat") = "bradford",
      "3x3 matrix from linear RGB in one space to another, adapting their whites.");
  m.def(
      "chromatic_adaptation_matrix",
      [](const Array& source_white, const Array& destination_white, const std::string& cat) {
        return matrix_array(chromatic_adaptation_matrix(xyz_of(source_white, "source_white"),
                                                        xyz_of(destination_white, "destination_white"), cat_of(cat)));
      },
      py::arg("source_white"), py::arg("destination_white"), py::arg("cat") = "bradford",
      "XYZ->XYZ von Kries-type transform between two whites.");
  m.def("srgb_encode", py::vectorize(&srgb_encode), py::arg("linear"), "The sRGB transfer function.");
  m.def("srgb_decode", py::vectorize(&srgb_decode), py::arg("encoded"));

  auto lib = py::reinterpret_borrow<py::class_<SpectralLibrary>>(m.attr("Library"));
  lib.def(
         "upsample_reflectance",
         [](SpectralLibrary& l, const Array& rgb, const std::string& space) {
           return upsampled_arrays(l, rgb, space,
                                   [](const RgbUpsampler& u, const Rgb& c) { return u.upsample_reflectance(c); });
         },
         py::arg("rgb"), py::arg("space") = "srgb-linear",
         "The smoothest reflectance with this linear RGB: (wavelengths_nm, values at 1 nm, gamut_mapped).")
      .def(
          "upsample_emission",
          [](SpectralLibrary& l, const Array& rgb, const std::string& space) {
            return upsampled_arrays(l, rgb, space,
                                    [](const RgbUpsampler& u, const Rgb& c) { return u.upsample_emission(c); });
          },
          py::arg("rgb"), py::arg("space") = "srgb-linear",
          "An emission spectrum with this linear RGB: (wavelengths_nm, values at 1 nm, gamut_mapped).");
}

}  // namespace rimu::python
