// rimu.Spectrum: a tabulated spectrum (wavelengths in nm, values, and what they are: a light's spectral power, a
// reflectance factor or another curve) with interpolation, alignment, arithmetic and colorimetry; the data library
// by name (illuminants, observers, the ColorChecker, cameras) and the blackbody and daylight generators.
#include <pybind11/stl.h>

#include <memory>

#include "bindings.h"
#include "broadcast.h"
#include "render/film/spectral_response.h"
#include "spectral/library/colorimetry_options.h"
#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/io/csv_table.h"
#include "spectral/reports/reflectance_report.h"
#include "spectral/spectra/blackbody_spectrum.h"
#include "spectral/colorimetry/daylight.h"
#include "spectral/spectra/spectrum_resampling.h"
#include "spectral/library/spectrum_source.h"
#include "spectral/spectra/spectrum_values_check.h"

namespace rimu::python {
namespace {

struct PySpectrum {
  std::shared_ptr<const TabulatedSpectrum> table;
  SpectrumKind kind = SpectrumKind::light;
  std::string name;
};

const char* kind_name(SpectrumKind k) {
  return k == SpectrumKind::light ? "light" : k == SpectrumKind::reflectance ? "reflectance" : "other";
}

SpectrumKind kind_option(const std::string& name) {
  if (name == "light") return SpectrumKind::light;
  if (name == "reflectance") return SpectrumKind::reflectance;
  if (name == "other") return SpectrumKind::other;
  throw InputError(argument("kind"), "expected light, reflectance or other, got '" + name + "'");
}

SpectralLibrary& default_library() {
  static SpectralLibrary library(default_data_root());
  return library;
}
SpectralLibrary& library_of(const OptionalLibrary& library) {
  return library.is_none() ? default_library() : library.cast<SpectralLibrary&>();
}
py::object library_object(SpectralLibrary& l) { return py::cast(&l, py::return_value_policy::reference); }

PySpectrum spectrum_of(const TabulatedSpectrum& table, SpectrumKind kind, std::string name) {
  return {std::make_shared<const TabulatedSpectrum>(table), kind, std::move(name)};
}

// A new spectrum from numbers computed here (a resampling, an arithmetic result), through the checks of its kind;
// a refusal names `place` (the operation's argument).
PySpectrum checked(const TabulatedSpectrum& t, SpectrumKind kind, std::string name, const std::string& place) {
  const SampleLocation at = [&](size_t i) { return argument(place + " (result[" + std::to_string(i) + "])"); };
  if (kind == SpectrumKind::light) check_spectral_power(t.values(), at);
  if (kind == SpectrumKind::reflectance) check_reflectance_factors(t.values(), at);
  for (size_t i = 0; i < t.values().size(); ++i) check_colour_component(t.values()[i], at(i));
  return spectrum_of(t, kind, std::move(name));
}

std::vector<double> wavelengths_of(const ArrayLike& value, const std::string& name) {
  const Array a = numeric_array(value, name);
  return sampling_from_array(a).wavelengths_nm();
}

PySpectrum scaled(const PySpectrum& s, double factor, const std::string& place) {
  check_colour_component(factor, argument(place));
  std::vector<double> v = s.table->values();
  for (double& x : v) x *= factor;
  return checked(TabulatedSpectrum(s.table->wavelengths_nm(), std::move(v), s.table->extrapolation(), s.name), s.kind,
                 s.name, place);
}

// The kind of a product: a light times anything is a light (a filtered or reflected light); two reflectances give
// a reflectance; anything else is "other".
SpectrumKind product_kind(SpectrumKind a, SpectrumKind b) {
  if (a == SpectrumKind::light || b == SpectrumKind::light) return SpectrumKind::light;
  if (a == SpectrumKind::reflectance && b == SpectrumKind::reflectance) return SpectrumKind::reflectance;
  return SpectrumKind::other;
}

PySpectrum combine(const PySpectrum& a, const PySpectrum& b, SpectrumKind kind, double (*op)(double, double),
                   const char* symbol) {
  const std::string name = "(" + a.name + " " + symbol + " " + b.name + ")";
  const Extrapolation e = kind == SpectrumKind::reflectance ? Extrapolation::clamp : Extrapolation::zero;
  return checked(combined(*a.table, *b.table, op, e, name), kind, name, "other");
}

py::tuple arrays_of(const PySpectrum& s) { return arrays_from_spectrum(*s.table); }

// The three curves of a camera file (raw, as measured: the film normalises them, this does not).
py::tuple camera_curves(SpectralLibrary& l, const std::string& name) {
  std::string stem;
  try {
    stem = SpectralResponse::camera_rgb(l, name).camera_name();
  } catch (const InputError& e) {
    throw InputError(argument("name"), e.explanation());
  }
  const CsvTable& table = l.table(std::filesystem::path("spectra/cameras") / (stem + ".csv"));
  py::list out;
  for (const char* channel : {"R", "G", "B"})
    out.append(spectrum_of(TabulatedSpectrum::from_csv(table, channel, Extrapolation::zero), SpectrumKind::other,
                           stem + " " + channel));
  return py::tuple(out);
}

}  // namespace

void bind_spectrum(py::module_& m) {
  m.def("library", &default_library, py::return_value_policy::reference,
        "The module's shared Library (opened on first use at the default data folder): what the functions taking "
        "library=None use.\n\nExample: rimu.library().root");

  py::class_<PySpectrum>(m, "Spectrum",
                         "A tabulated spectrum: wavelengths in nm (strictly increasing), values, and a kind that says "
                         "what they are and how they continue outside the data: 'light' (spectral power, relative or "
                         "in W/nm-type units; never negative; zero outside), 'reflectance' (reflectance factor 0-1.5; "
                         "its end values outside, CIE 15) or 'other' (any finite curve; zero outside). Linear "
                         "between samples.")
      .def(py::init([](const Array& wavelengths_nm, const Array& values, const std::string& kind,
                       const std::string& name) {
             const SpectrumKind k = kind_option(kind);
             return spectrum_of(spectrum_from_arrays(wavelengths_nm, values, k, default_library()), k,
                                name.empty() ? std::string("spectrum") : name);
           }),
           py::arg("wavelengths_nm"), py::arg("values"), py::arg("kind") = "light", py::arg("name") = "",
           "A spectrum from two 1-D arrays of the same length, through the tools' checks for its kind.\n\n"
           "Example: rimu.Spectrum([400, 500, 600, 700], [0.1, 0.5, 0.6, 0.4], kind='reflectance')")
      .def_static(
          "from_csv",
          [](const std::string& path, const std::string& column, const std::string& kind) {
            const SpectrumKind k = kind_option(kind);
            const CsvTable table = CsvTable::read(path);
            const std::string col = column.empty() ? (table.column_count() > 1 ? table.header()[1] : "") : column;
            const Extrapolation e = k == SpectrumKind::reflectance ? Extrapolation::clamp : Extrapolation::zero;
            const TabulatedSpectrum t = TabulatedSpectrum::from_csv(table, col, e);
            const SampleLocation at = [&](size_t i) { return SourceLocation{path, table.line_of_row(i), col}; };
            check_wavelengths_nm(t.wavelengths_nm(), at);
            if (k == SpectrumKind::light) {
              check_spectral_power(t.values(), at);
              check_emission_spectrum(t, default_library(), SourceLocation{path, 0, col});
            }
            if (k == SpectrumKind::reflectance) check_reflectance_factors(t.values(), at);
            return spectrum_of(t, k, std::filesystem::path(path).stem().string() + (column.empty() ? "" : ":" + col));
          },
          py::arg("path"), py::arg("column") = "", py::arg("kind") = "light",
          "A spectrum from a CSV file read by the tools' reader and checks (a header line, the first column the "
          "wavelength in nm; errors name the file and line). column: the values' column (default: the second).\n\n"
          "Example: rimu.Spectrum.from_csv('data/spectra/illuminants/cie_a_5nm.csv')")
      .def_property_readonly(
          "wavelengths_nm", [](const PySpectrum& s) { return py::array_t<double>(arrays_of(s)[0]); }, "The wavelengths (nm), a new array.")
      .def_property_readonly(
          "values", [](const PySpectrum& s) { return py::array_t<double>(arrays_of(s)[1]); }, "The values, a new array.")
      .def_property_readonly(
          "kind", [](const PySpectrum& s) { return std::string(kind_name(s.kind)); },
          "'light', 'reflectance' or 'other'.")
      .def_property_readonly(
          "name", [](const PySpectrum& s) { return s.name; }, "What the spectrum is (a table's name, an operation).")
      .def("__len__", [](const PySpectrum& s) { return s.table->wavelengths_nm().size(); },
           "The number of samples.")
      .def("__repr__",
           [](const PySpectrum& s) {
             const auto& l = s.table->wavelengths_nm();
             return "<rimu.Spectrum '" + s.name + "' (" + kind_name(s.kind) + "), " + std::to_string(l.size()) +
                    " samples, " + std::to_string(l.front()) + "-" + std::to_string(l.back()) + " nm>";
           },
           "A one-line description.")
      .def(
          "__call__",
          [](const PySpectrum& s, const ArrayLike& wavelengths_nm) {
            const Array a = numeric_array(wavelengths_nm, "wavelengths_nm");
            const std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
            for (py::ssize_t i = 0; i < a.size(); ++i)
              check_colour_component(a.data()[i], argument(element_name("wavelengths_nm", shape, i)));
            return map_scalars(shape, size_t(a.size()), [&](std::size_t i) { return s.table->value(a.data()[i]); });
          },
          py::arg("wavelengths_nm"),
          "The values at any wavelengths (a number or an array of any shape), interpolated linearly and "
          "continued by the kind's rule.\n\nExample: rimu.illuminant('D65')(560.0) -> 100.0")
      .def(
          "align",
          [](const PySpectrum& s, const ArrayLike& wavelengths_nm) {
            return checked(resampled(*s.table, wavelengths_of(wavelengths_nm, "wavelengths_nm")), s.kind, s.name,
                           "wavelengths_nm");
          },
          py::arg("wavelengths_nm"),
          "The spectrum on other wavelengths (1-D, strictly increasing), by its interpolation and extrapolation.\n\n"
          "Example: rimu.illuminant('A').align(np.arange(380, 781, 10))")
      .def(
          "interpolate",
          [](const PySpectrum& s, double interval_nm) {
            const auto& l = s.table->wavelengths_nm();
            return checked(resampled(*s.table, regular_wavelength_grid(l.front(), l.back(), interval_nm,
                                                                       argument("interval_nm"))),
                           s.kind, s.name, "interval_nm");
          },
          py::arg("interval_nm") = 1.0,
          "The spectrum on a regular grid over its own range (first wavelength, then every interval_nm), linear "
          "between the original samples.\n\nExample: rimu.colorchecker('dark skin').interpolate(5.0)")
      .def(
          "__mul__", [](const PySpectrum& a, const PySpectrum& b) {
            return combine(a, b, product_kind(a.kind, b.kind), [](double x, double y) { return x * y; }, "*");
          },
          py::arg("other"),
          "Product on the union of both samplings (a light times a reflectance or a filter is a light).")
      .def(
          "__mul__", [](const PySpectrum& a, double factor) { return scaled(a, factor, "other"); }, py::arg("other"),
          "The values times a number.")
      .def(
          "__rmul__", [](const PySpectrum& a, double factor) { return scaled(a, factor, "other"); }, py::arg("other"),
          "The values times a number.")
      .def(
          "__truediv__",
          [](const PySpectrum& a, double divisor) {
            if (divisor == 0.0) throw InputError(argument("other"), "cannot divide a spectrum by 0");
            return scaled(a, 1.0 / divisor, "other");
          },
          py::arg("other"), "The values divided by a number.")
      .def(
          "__add__",
          [](const PySpectrum& a, const PySpectrum& b) {
            return combine(a, b, a.kind == b.kind ? a.kind : SpectrumKind::other,
                           [](double x, double y) { return x + y; }, "+");
          },
          py::arg("other"), "Sum on the union of both samplings (two lights give a light).")
      .def(
          "to_xyz",
          [](const PySpectrum& s, const std::string& illuminant, int observer, const std::string& method,
             const OptionalLibrary& library) {
            const py::object lib = library_object(library_of(library));
            const py::tuple a = arrays_of(s);
            if (s.kind == SpectrumKind::light)
              return py::array_t<double>(lib.attr("light_xyz")(a[0], a[1], observer, method));
            if (s.kind == SpectrumKind::reflectance)
              return py::array_t<double>(lib.attr("reflectance_xyz")(a[0], a[1], illuminant, observer, method));
            throw InputError(argument("self"), "XYZ is defined for a light or a reflectance, not for kind 'other'");
          },
          py::arg("illuminant") = "D50", py::arg("observer") = 2, py::arg("method") = "auto",
          py::arg("library") = py::none(),
          "CIE XYZ (Y = 100): of a light, relative (Library.light_xyz); of a reflectance under a CIE illuminant "
          "(Library.reflectance_xyz; `illuminant` is ignored for a light). method: auto, native, 1nm or "
          "astm-e308.\n\nExample: rimu.colorchecker('dark skin').to_xyz('D65')")
      .def(
          "cct",
          [](const PySpectrum& s, const OptionalLibrary& library, const std::string& method) {
            const py::tuple a = arrays_of(s);
            return py::tuple(library_object(library_of(library)).attr("cct_duv")(a[0], a[1], method));
          },
          py::arg("library") = py::none(), py::arg("method") = "ohno2013",
          "(CCT in K, Duv, validity) of a light (Library.cct_duv; method 'ohno2013' or 'robertson1968')."
          "\n\nExample: rimu.illuminant('A').cct(method='robertson1968')")
      .def(
          "cri",
          [](const PySpectrum& s, const OptionalLibrary& library) {
            const py::tuple a = arrays_of(s);
            return py::dict(library_object(library_of(library)).attr("cri")(a[0], a[1]));
          },
          py::arg("library") = py::none(),
          "CIE 13.3 colour rendering of a light (Library.cri).\n\nExample: rimu.illuminant('F2').cri()['ra']")
      .def(
          "fidelity",
          [](const PySpectrum& s, const OptionalLibrary& library) {
            const py::tuple a = arrays_of(s);
            return py::dict(library_object(library_of(library)).attr("fidelity")(a[0], a[1]));
          },
          py::arg("library") = py::none(),
          "CIE 224 / TM-30 colour fidelity of a light (Library.fidelity).\n\n"
          "Example: rimu.illuminant('F11').fidelity()['rf']");

  m.def(
      "illuminant",
      [](const std::string& name, const OptionalLibrary& library) {
        SpectralLibrary& l = library_of(library);
        const SpectrumPtr s = for_argument("name", [&] { return l.illuminant(name); });
        return spectrum_of(dynamic_cast<const TabulatedSpectrum&>(*s), SpectrumKind::light, name);
      },
      py::arg("name"), py::arg("library") = py::none(),
      "A CIE illuminant (relative power) by name: A, D50, D55, D65, D75, E, F1-F12, FL3.1-FL3.15, HP1-HP5, LED-B1 "
      "... LED-V2 (Library.illuminant_names()).\n\nExample: rimu.illuminant('F11')");
  m.def(
      "cie_led",
      [](const std::string& name, const OptionalLibrary& library) {
        SpectralLibrary& l = library_of(library);
        // "B3" or the table's full name "LED-B3" (what illuminant() and illuminant_names() use).
        const std::string full = name.rfind("LED-", 0) == 0 ? name : "LED-" + name;
        const SpectrumPtr s = for_argument("name", [&] { return l.illuminant(full); });
        return spectrum_of(dynamic_cast<const TabulatedSpectrum&>(*s), SpectrumKind::light, full);
      },
      py::arg("name"), py::arg("library") = py::none(),
      "A CIE 15:2018 LED illuminant by its short name (B1-B5, BH1, RGB1, V1, V2) or its full name (LED-B3)."
      "\n\nExample: rimu.cie_led('B3')");
  m.def(
      "colorchecker",
      [](const std::string& patch, const OptionalLibrary& library) {
        return spectrum_of(colorchecker_patch(library_of(library), patch, argument("patch")),
                           SpectrumKind::reflectance, patch);
      },
      py::arg("patch"), py::arg("library") = py::none(),
      "A ColorChecker Classic patch's reflectance (BabelColor average, 10 nm) by name, e.g. 'dark skin' "
      "(colorchecker_names()).\n\nExample: rimu.colorchecker('dark skin')");
  m.def(
      "colorchecker_names", [](const OptionalLibrary& library) { return library_of(library).colorchecker_patch_names(); },
      py::arg("library") = py::none(), "The 24 ColorChecker patch names in chart order.");
  m.def(
      "observer",
      [](const py::object& which, const OptionalLibrary& library) {
        SpectralLibrary& l = library_of(library);
        StandardObserver o = StandardObserver::cie1931_2deg;
        if (py::isinstance<py::str>(which)) {
          const std::string name = which.cast<std::string>();
          if (name == l.observer(StandardObserver::cie1964_10deg).name)
            o = StandardObserver::cie1964_10deg;
          else if (name != l.observer(StandardObserver::cie1931_2deg).name)
            throw InputError(argument("which"), "expected 'CIE 1931 2°', 'CIE 1964 10°', 2 or 10, got '" + name + "'");
        } else {
          o = standard_observer_option(which.cast<int>(), argument("which"));
        }
        const Observer& obs = l.observer(o);
        return py::make_tuple(spectrum_of(obs.x_bar, SpectrumKind::other, obs.name + " x̄"),
                              spectrum_of(obs.y_bar, SpectrumKind::other, obs.name + " ȳ"),
                              spectrum_of(obs.z_bar, SpectrumKind::other, obs.name + " z̄"));
      },
      py::arg("which") = 2, py::arg("library") = py::none(),
      "A CIE standard observer's colour-matching functions (x̄, ȳ, z̄) as three Spectrum objects: which = 2 or "
      "'CIE 1931 2°', 10 or 'CIE 1964 10°'.\n\nExample: x, y, z = rimu.observer('CIE 1964 10°')");
  m.def(
      "camera", [](const std::string& name, const OptionalLibrary& library) { return camera_curves(library_of(library), name); },
      py::arg("name"), py::arg("library") = py::none(),
      "A camera's measured R, G, B sensitivities (as in the data file, not normalised) as three Spectrum "
      "objects, by short name ('nikon_d850') or file stem (camera_names()).\n\nExample: r, g, b = rimu.camera('nikon_d850')");
  m.def(
      "camera_names",
      [](const OptionalLibrary& library) { return SpectralResponse::camera_file_stems(library_of(library)); },
      py::arg("library") = py::none(), "Every camera file stem in data/spectra/cameras.");
  m.def(
      "blackbody",
      [](double temperature_k, const ArrayLike& wavelengths_nm, bool absolute) {
        if (!(temperature_k > 0.0 && temperature_k <= 1e6))
          throw InputError(argument("temperature_k"), "expected a temperature in (0, 1e6] K, got " +
                                                          std::to_string(temperature_k));
        const BlackbodySpectrum planck(temperature_k, absolute ? BlackbodySpectrum::Scale::absolute_radiance
                                                               : BlackbodySpectrum::Scale::peak_one);
        const std::vector<double> grid = wavelengths_nm.is_none()
                                             ? regular_wavelength_grid(360.0, 830.0, 1.0, argument("wavelengths_nm"))
                                             : wavelengths_of(wavelengths_nm, "wavelengths_nm");
        std::vector<double> v(grid.size());
        for (size_t i = 0; i < grid.size(); ++i) v[i] = planck.value(grid[i]);
        return checked(TabulatedSpectrum(grid, std::move(v), Extrapolation::zero, planck.describe()),
                       SpectrumKind::light, planck.describe(), "temperature_k");
      },
      py::arg("temperature_k"), py::arg("wavelengths_nm") = py::none(), py::arg("absolute") = false,
      "A black body (Planck's law, SI 2019 constants) on wavelengths_nm (default 360-830 nm at 1 nm): scaled to "
      "a peak of 1, or with absolute=True in W/(m²·sr·nm).\n\nExample: rimu.blackbody(2856).cct()");
  m.def(
      "daylight",
      [](double cct_k, const OptionalLibrary& library) {
        SpectralLibrary& l = library_of(library);
        const TabulatedSpectrum s =
            for_argument("cct_k", [&] { return daylight_spectrum(l.daylight_basis(), cct_k); });
        return spectrum_of(s, SpectrumKind::light, "CIE daylight " + std::to_string(int(cct_k + 0.5)) + " K");
      },
      py::arg("cct_k"), py::arg("library") = py::none(),
      "CIE daylight at a correlated colour temperature of 4000-25000 K (CIE 15:2018 §4.1: S0 + M1 S1 + M2 S2, M1 "
      "and M2 unrounded; 5 nm, relative, about 100 at 560 nm). D65 is daylight(6504).\n\n"
      "Example: rimu.daylight(5000).cri()['ra']");
}

}  // namespace rimu::python
