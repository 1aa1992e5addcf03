// Shared pieces of the `rimu` Python module: numpy <-> spectrum conversion and the per-area binding functions.
//
// Validation lives in src/spectral, in the checks the tools call too (spectrum_values_check.h, colour_value_check.h,
// colorimetry_options.h, spectrum_source.h's check_emission_spectrum, light_units.h's ranges): the bindings only
// pass each check the Python argument's name as the place the value came from, so a ValueError reads like the
// tools' message with `values[3]` or `white` where the tool would name a file line or an option.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <string>
#include <vector>

#include "spectral/colorimetry/cct_method.h"
#include "spectral/colorimetry/chromaticity.h"
#include "spectral/error.h"
#include "spectral/colour_spaces/rgb_colour_space.h"
#include "spectral/library/spectral_library.h"
#include "spectral/spectra/tabulated_spectrum.h"

namespace rimu::python {

namespace py = pybind11;
/// Any numeric array-like, converted to contiguous float64 (float32, integers and strided views included).
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The place an error about argument `name` points to: {"", 0, name}.
inline SourceLocation argument(const std::string& name) { return {"", 0, name}; }

/// "name[2, 5]": element `flat_index` (in C order) of an array of `shape`, named by its indices; "name" for a 0-d one.
std::string element_name(const std::string& name, const std::vector<py::ssize_t>& shape, py::ssize_t flat_index);

/// Runs `f`; an InputError that names no place of its own is re-raised naming the argument `name` (an unknown
/// illuminant or colour space found deep in the library is reported against the argument that named it).
template <typename F>
auto for_argument(const std::string& name, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    if (!e.where().file.empty() || !e.where().key.empty()) throw;
    throw InputError(argument(name), e.explanation());
  }
}

/// What a pair of (wavelengths_nm, values) arrays holds, which decides the checks they pass.
enum class SpectrumKind {
  light,        ///< spectral power: never negative, some power in 360-830 nm (zero outside the data)
  reflectance,  ///< reflectance factor in 0-1.5 (held at its end values outside the data)
  other,        ///< anything else (a sensitivity, a colour-matching function): finite values, zero outside the data
};

/// A table from the arguments `wavelengths_nm` and `values` (1-D, the same length), through the tools' checks for
/// its kind. InputError (ValueError in Python) names the argument and the index.
TabulatedSpectrum spectrum_from_arrays(const Array& wavelengths_nm, const Array& values, SpectrumKind kind,
                                       SpectralLibrary& library);
/// A sampling (wavelengths_nm only, through the same wavelength checks) as a constant reflectance of 1.
TabulatedSpectrum sampling_from_array(const Array& wavelengths_nm);
/// (wavelengths_nm, values) as two new numpy arrays.
py::tuple arrays_from_spectrum(const TabulatedSpectrum& spectrum);
/// Any spectrum sampled at 1 nm over 360-830 nm, as (wavelengths_nm, values).
py::tuple arrays_at_1nm(const Spectrum& spectrum);
/// A new 1-D numpy array holding `values`.
py::array_t<double> array_of(const std::vector<double>& values);
/// A 3-vector array from three numbers.
py::array_t<double> vec3(double a, double b, double c);
/// The three components of argument `name` (exactly 3 numbers, finite and within ±1e30: check_colour_components).
std::array<double, 3> read_triple(const Array& a, const std::string& name);

/// The built-in RGB space `name`; an unknown one is reported against `argument_name`.
const RgbColourSpace& space_named(const std::string& name, const std::string& argument_name);

/// The data folder the module uses unless told otherwise: RIMU_DATA, then rimu_data/ beside the module (pip
/// install), then the build tree's share/rimu/data, then the install layout's share/rimu/data beside
/// lib/python3/dist-packages.
std::string default_data_root();

/// The CCT method named by the Python argument `method` ("ohno2013" or "robertson1968"), set up for `observer`
/// (Robertson's table exists for the 1931 2° observer only: anything else is a ValueError naming `observer`).
CctSolver cct_solver(SpectralLibrary& library, const std::string& method, StandardObserver observer);

void bind_colorimetry(py::module_& m);
void bind_quality(py::module_& m);
void bind_spaces(py::module_& m);
void bind_colour_arrays(py::module_& m);
void bind_appearance(py::module_& m);
void bind_spectrum(py::module_& m);
void bind_render(py::module_& m);

}  // namespace rimu::python
