// The `rimu` Python module: one SpectralLibrary object (rimu.Library) that owns the published tables, and free
// functions for what needs no tables. Errors: rimu's InputError becomes ValueError with the same message.
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "bindings.h"
#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/error.h"
#include "spectral/library/spectrum_source.h"
#include "spectral/spectra/spectrum_values_check.h"
#include "spectral/version.h"

namespace rimu::python {

namespace {

// Where element i of argument `name` came from: "values[3]".
SampleLocation element_of(const std::string& name) {
  return [name](size_t i) { return argument(name + "[" + std::to_string(i) + "]"); };
}

std::vector<double> vector_of(const Array& a) { return std::vector<double>(a.data(), a.data() + a.size()); }

}  // namespace

std::string element_name(const std::string& name, const std::vector<py::ssize_t>& shape, py::ssize_t flat_index) {
  if (shape.empty()) return name;
  std::string indices;
  for (size_t d = shape.size(); d-- > 0;) {
    indices = std::to_string(flat_index % shape[d]) + (indices.empty() ? "" : ", ") + indices;
    flat_index /= shape[d];
  }
  return name + "[" + indices + "]";
}

namespace {

std::string shape_text(const Array& a) {
  std::string out = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) out += (d ? ", " : "") + std::to_string(a.shape(d));
  return out + (a.ndim() == 1 ? ",)" : ")");
}

// The table's own checks (at least two samples) reported against the wavelengths argument.
TabulatedSpectrum table_at_argument(std::vector<double> l, std::vector<double> v, Extrapolation extrapolation) {
  try {
    return TabulatedSpectrum(std::move(l), std::move(v), extrapolation, "(wavelengths_nm, values)");
  } catch (const InputError& e) {
    throw InputError(argument("wavelengths_nm"), e.explanation());
  }
}

void check_one_dimensional(const Array& a, const std::string& name) {
  if (a.ndim() != 1)
    throw InputError(argument(name), "expected a 1-D array, got " + std::to_string(a.ndim()) + " dimensions");
}

}  // namespace

TabulatedSpectrum spectrum_from_arrays(const Array& wavelengths_nm, const Array& values, SpectrumKind kind,
                                       SpectralLibrary& library) {
  check_one_dimensional(wavelengths_nm, "wavelengths_nm");
  check_one_dimensional(values, "values");
  if (values.size() != wavelengths_nm.size())
    throw InputError(argument("values"), "expected one value per wavelength (" + std::to_string(wavelengths_nm.size()) +
                                             "), got " + std::to_string(values.size()));
  std::vector<double> l = vector_of(wavelengths_nm), v = vector_of(values);
  check_wavelengths_nm(l, element_of("wavelengths_nm"));
  if (kind == SpectrumKind::light)
    check_spectral_power(v, element_of("values"));
  else if (kind == SpectrumKind::reflectance)
    check_reflectance_factors(v, element_of("values"));
  else
    for (size_t i = 0; i < v.size(); ++i) check_colour_component(v[i], element_of("values")(i));
  TabulatedSpectrum s = table_at_argument(
      std::move(l), std::move(v), kind == SpectrumKind::reflectance ? Extrapolation::clamp : Extrapolation::zero);
  if (kind == SpectrumKind::light) check_emission_spectrum(s, library, argument("values"));
  return s;
}

TabulatedSpectrum sampling_from_array(const Array& wavelengths_nm) {
  check_one_dimensional(wavelengths_nm, "wavelengths_nm");
  std::vector<double> l = vector_of(wavelengths_nm);
  check_wavelengths_nm(l, element_of("wavelengths_nm"));
  const size_t n = l.size();
  return table_at_argument(std::move(l), std::vector<double>(n, 1.0), Extrapolation::clamp);
}

py::tuple arrays_from_spectrum(const TabulatedSpectrum& s) {
  py::array_t<double> l(py::ssize_t(s.wavelengths_nm().size())), v(py::ssize_t(s.values().size()));
  std::copy(s.wavelengths_nm().begin(), s.wavelengths_nm().end(), l.mutable_data());
  std::copy(s.values().begin(), s.values().end(), v.mutable_data());
  return py::make_tuple(l, v);
}

py::tuple arrays_at_1nm(const Spectrum& s) {
  py::array_t<double> l(471), v(471);
  for (int i = 0; i <= 470; ++i) {
    l.mutable_data()[i] = 360.0 + i;
    v.mutable_data()[i] = s.value(360.0 + i);
  }
  return py::make_tuple(l, v);
}

py::array_t<double> array_of(const std::vector<double>& values) {
  py::array_t<double> out(py::ssize_t(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::array_t<double> vec3(double a, double b, double c) {
  py::array_t<double> out(3);
  out.mutable_data()[0] = a;
  out.mutable_data()[1] = b;
  out.mutable_data()[2] = c;
  return out;
}

std::array<double, 3> read_triple(const Array& a, const std::string& name) {
  if (a.size() != 3) throw InputError(argument(name), "expected 3 values, got an array of shape " + shape_text(a));
  const std::array<double, 3> t{a.data()[0], a.data()[1], a.data()[2]};
  check_colour_components(t[0], t[1], t[2], argument(name));
  return t;
}

const RgbColourSpace& space_named(const std::string& name, const std::string& argument_name) {
  return for_argument(argument_name, [&]() -> const RgbColourSpace& { return RgbColourSpace::named(name); });
}

std::string default_data_root() {
  if (const char* env = std::getenv("RIMU_DATA")) return env;
  Dl_info info{};
  const bool located = dladdr(reinterpret_cast<void*>(&default_data_root), &info) && info.dli_fname;
  const std::filesystem::path module_folder = located ? std::filesystem::path(info.dli_fname).parent_path() : "";
  // `pip install ./python` puts the tables beside the module (python/setup.py): first, so an installed module
  // never reads a build tree's data.
  if (located && std::filesystem::is_directory(module_folder / "rimu_data" / "cmf"))
    return (module_folder / "rimu_data").string();
  if (std::filesystem::is_directory(std::filesystem::path(RIMU_PYTHON_BUILD_DATA) / "cmf"))
    return RIMU_PYTHON_BUILD_DATA;
  if (located) {
    // cmake --install: <prefix>/lib/python3/dist-packages/rimu*.so -> <prefix>/share/rimu/data
    const auto installed = module_folder / "../../../share/rimu/data";
    if (std::filesystem::is_directory(installed / "cmf")) return std::filesystem::weakly_canonical(installed).string();
  }
  throw InputError({}, "cannot find Rimu's data folder: set RIMU_DATA to the repository's data/ folder");
}

}  // namespace rimu::python

PYBIND11_MODULE(rimu, m) {
  using namespace rimu::python;
  m.doc() = "Rimu: spectral colorimetry (CIE 15, ASTM E308, CIE 13.3, CIE 224 / TM-30), colour appearance (CIECAM02, "
            "CAM16), colour differences, colour spaces, RGB upsampling, light units and spectral rendering. Colour "
            "functions broadcast over (..., 3) arrays; spectra are rimu.Spectrum objects or (wavelengths_nm, values) "
            "numpy arrays. docs/python.md is the tutorial.";
  m.attr("__version__") = rimu::rimu_version();
  m.attr("__git_commit__") = rimu::rimu_git_commit();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const rimu::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  py::class_<rimu::SpectralLibrary>(m, "Library",
                                    "Rimu's published tables (observers, illuminants, reflectances), loaded on first use.")
      .def(py::init([](const std::string& root) {
             return std::make_unique<rimu::SpectralLibrary>(root.empty() ? default_data_root() : root);
           }),
           py::arg("data_root") = "",
           "Opens Rimu's data folder. data_root: the data/ folder; default RIMU_DATA, else rimu_data/ beside the "
           "module (pip install), else the build tree's or the install's share/rimu/data.\n\nExample: lib = rimu.Library()")
      .def_property_readonly(
          "root", [](const rimu::SpectralLibrary& l) { return l.root().string(); }, "The data folder in use (a path).");
  bind_colorimetry(m);
  bind_quality(m);
  bind_spaces(m);
  bind_colour_arrays(m);
  bind_appearance(m);
  bind_spectrum(m);
  bind_render(m);
}
