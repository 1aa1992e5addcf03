// The `rimu` Python module: one SpectralLibrary object (rimu.Library) that owns the published tables, and free
// functions for what needs no tables. Errors: rimu's InputError becomes ValueError with the same message.
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "bindings.h"
#include "spectral/error.h"

namespace rimu::python {

TabulatedSpectrum spectrum_from_arrays(const Array& wavelengths_nm, const Array& values, Extrapolation extrapolation,
                                       const std::string& what) {
  if (wavelengths_nm.ndim() != 1 || values.ndim() != 1 || wavelengths_nm.size() != values.size())
    throw InputError({}, what + ": wavelengths and values must be 1-D arrays of the same length");
  std::vector<double> l(wavelengths_nm.data(), wavelengths_nm.data() + wavelengths_nm.size());
  std::vector<double> v(values.data(), values.data() + values.size());
  return TabulatedSpectrum(std::move(l), std::move(v), extrapolation, what);
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

py::array_t<double> vec3(double a, double b, double c) {
  py::array_t<double> out(3);
  out.mutable_data()[0] = a;
  out.mutable_data()[1] = b;
  out.mutable_data()[2] = c;
  return out;
}

void read3(const Array& a, double& x, double& y, double& z, const char* what) {
  if (a.size() != 3) throw InputError({}, std::string(what) + ": expected 3 values");
  x = a.data()[0];
  y = a.data()[1];
  z = a.data()[2];
}

std::string default_data_root() {
  if (const char* env = std::getenv("RIMU_DATA")) return env;
  if (std::filesystem::is_directory(std::filesystem::path(RIMU_PYTHON_BUILD_DATA) / "cmf"))
    return RIMU_PYTHON_BUILD_DATA;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&default_data_root), &info) && info.dli_fname) {
    // <prefix>/lib/python3/dist-packages/rimu*.so -> <prefix>/share/rimu/data
    const auto installed = std::filesystem::path(info.dli_fname).parent_path() / "../../../share/rimu/data";
    if (std::filesystem::is_directory(installed / "cmf")) return std::filesystem::weakly_canonical(installed).string();
  }
  throw InputError({}, "cannot find Rimu's data folder: set RIMU_DATA to the repository's data/ folder");
}

}  // namespace rimu::python

PYBIND11_MODULE(rimu, m) {
  using namespace rimu::python;
  m.doc() = "Rimu: spectral colorimetry (CIE 15, ASTM E308, CIE 13.3, CIE 224 / TM-30), colour spaces, RGB "
            "upsampling, light units and spectral rendering. Spectra are (wavelengths_nm, values) numpy arrays.";
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
           py::arg("data_root") = "", "data_root: the data/ folder; default RIMU_DATA or the build/install location")
      .def_property_readonly("root", [](const rimu::SpectralLibrary& l) { return l.root().string(); });
  bind_colorimetry(m);
  bind_quality(m);
  bind_spaces(m);
  bind_render(m);
}
