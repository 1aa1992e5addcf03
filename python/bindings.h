// Shared pieces of the `rimu` Python module: numpy <-> spectrum conversion and the per-area binding functions.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "spectral/spectral_library.h"
#include "spectral/tabulated_spectrum.h"

namespace rimu::python {

namespace py = pybind11;
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A table from two 1-D arrays of equal length (wavelengths in nm, strictly increasing). InputError (which
/// Python sees as ValueError) names `what` when they do not fit.
TabulatedSpectrum spectrum_from_arrays(const Array& wavelengths_nm, const Array& values, Extrapolation extrapolation,
                                       const std::string& what);
/// (wavelengths_nm, values) as two new numpy arrays.
py::tuple arrays_from_spectrum(const TabulatedSpectrum& spectrum);
/// Any spectrum sampled at 1 nm over 360-830 nm, as (wavelengths_nm, values).
py::tuple arrays_at_1nm(const Spectrum& spectrum);
/// A 3-vector array from three numbers, and back.
py::array_t<double> vec3(double a, double b, double c);
void read3(const Array& a, double& x, double& y, double& z, const char* what);

/// The data folder the module uses unless told otherwise: RIMU_DATA, then the build tree's share/rimu/data, then
/// the install layout's share/rimu/data beside lib/python3/dist-packages.
std::string default_data_root();

void bind_colorimetry(py::module_& m);
void bind_quality(py::module_& m);
void bind_spaces(py::module_& m);
void bind_render(py::module_& m);

}  // namespace rimu::python
