// rimu.Library: tables, tristimulus values of lights and reflectances (by method), CCT/Duv and light units.
#include <pybind11/stl.h>

#include "bindings.h"
#include "broadcast.h"
#include "spectral/colorimetry/colorimetry.h"
#include "spectral/library/colorimetry_options.h"
#include "spectral/error.h"
#include "spectral/photometry/light_units.h"
#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/reports/reflectance_report.h"
#include "spectral/spectra/spectrum_values_check.h"
#include "spectral/library/tabulated_colorimetry.h"

namespace rimu::python {
namespace {

StandardObserver observer_of(int degrees) { return standard_observer_option(degrees, argument("observer")); }

/// "auto" = the default for the data's spacing; otherwise native, 1nm or astm-e308.
TristimulusMethod method_of(const std::string& name, const TabulatedSpectrum& s) {
  return tristimulus_method_option(name, argument("method")).value_or(default_tristimulus_method(s));
}

E308Table e308_table_of(bool bandpass_corrected) {
  return bandpass_corrected ? E308Table::table6_bandpass_corrected : E308Table::table5_uncorrected;
}

/// An illuminant's name is checked first, so that an unknown one is reported against `illuminant` (the E308 weights
/// that follow may fail too, against `method`).
void check_illuminant(SpectralLibrary& l, const std::string& name) {
  for_argument("illuminant", [&] { return l.illuminant(name); });
}

// reflectance_xyz of every spectrum of a stack `v` (..., N) on the wavelengths `wl` (N,): the checks of a single
// spectrum, each value named by its indices (values[4, 7]), then the sums in C++ without the GIL.
py::array_t<double> reflectance_stack_xyz(SpectralLibrary& l, const Array& wl, const Array& v,
                                          const std::string& illuminant, int observer, const std::string& method,
                                          bool bandpass_corrected) {
  const TabulatedSpectrum sampling = sampling_from_array(wl);
  const std::vector<py::ssize_t> shape(v.shape(), v.shape() + v.ndim());
  if (shape.back() != wl.size())
    throw InputError(argument("values"), "expected the last axis to hold one value per wavelength (" +
                                             std::to_string(wl.size()) + "), got " + std::to_string(shape.back()));
  const std::vector<double> all(v.data(), v.data() + v.size());
  {
    py::gil_scoped_release release;
    check_reflectance_factors(all, [&](size_t i) { return argument(element_name("values", shape, py::ssize_t(i))); });
  }
  check_illuminant(l, illuminant);
  const StandardObserver o = observer_of(observer);
  const TristimulusMethod used = method_of(method, sampling);
  const E308Table table = e308_table_of(bandpass_corrected);
  const size_t n = size_t(wl.size());
  const auto xyz_of_row = [&](size_t row) {
    const TabulatedSpectrum s(sampling.wavelengths_nm(), std::vector<double>(all.begin() + row * n, all.begin() + (row + 1) * n),
                              Extrapolation::clamp, "(wavelengths_nm, values)");
    return reflectance_xyz(s, illuminant, o, used, l, table);
  };
  const std::vector<py::ssize_t> leading(shape.begin(), shape.end() - 1);
  py::array_t<double> out = result_array(leading, 3);
  const size_t rows = all.size() / n;
  if (rows == 0) return out;
  const Xyz first = for_argument("method", [&] { return xyz_of_row(0); });  // E308's refusals, before the loop
  double* o3 = out.mutable_data();
  o3[0] = first.x, o3[1] = first.y, o3[2] = first.z;
  for_each_range(rows - 1, [&](size_t begin, size_t end) {
    for (size_t row = begin + 1; row < end + 1; ++row) {
      const Xyz xyz = xyz_of_row(row);
      o3[3 * row] = xyz.x, o3[3 * row + 1] = xyz.y, o3[3 * row + 2] = xyz.z;
    }
  });
  return out;
}

py::tuple cct_tuple(const CctDuv& c, const CctSolver& solver) {
  return py::make_tuple(c.cct_k, c.duv, solver.validity_name(c.validity));
}

}  // namespace

CctSolver cct_solver(SpectralLibrary& library, const std::string& method, StandardObserver observer) {
  if (cct_method_from_name(method, argument("method")) == CctMethod::ohno2013)
    return CctSolver(library.observer(observer));
  if (observer != StandardObserver::cie1931_2deg)
    throw InputError(argument("observer"), "robertson1968 is tabulated for the CIE 1931 2° observer only: "
                                           "use observer=2, or method='ohno2013' for the 10° observer");
  return CctSolver(RobertsonCct::from_csv(library.table("cmf/robertson_1968_isotemperature_lines.csv")));
}

void bind_colorimetry(py::module_& m) {
  auto lib = py::reinterpret_borrow<py::class_<SpectralLibrary>>(m.attr("Library"));
  lib.def(
         "illuminant",
         [](SpectralLibrary& l, const std::string& name) {
           const SpectrumPtr s = for_argument("illuminant", [&] { return l.illuminant(name); });
           return arrays_from_spectrum(dynamic_cast<const TabulatedSpectrum&>(*s));
         },
         py::arg("name"), "A CIE illuminant's table (A, D50, D65, E, F1-F12, FL3.x, HP1-5, LED-...) as (wavelengths_nm, relative "
         "power); rimu.illuminant() gives it as a Spectrum.\n\nExample: wl, power = lib.illuminant('F11')")
      .def_static("illuminant_names", &SpectralLibrary::illuminant_names,
                  "The names illuminant() accepts (A, D50, D65, F1-F12, FL3.x, HP1-5, LED-B1 ... LED-V2, ...).")
      .def(
          "colorchecker",
          [](SpectralLibrary& l, const std::string& patch) {
            return arrays_from_spectrum(colorchecker_patch(l, patch, argument("patch")));
          },
          py::arg("patch"), "A ColorChecker Classic patch's reflectance factor (BabelColor average, 10 nm) as (wavelengths_nm, values)."
          "\n\nExample: wl, r = lib.colorchecker('dark skin')")
      .def(
          "tristimulus_method",
          [](SpectralLibrary& l, const Array& wl, const Array& v) {
            return std::string(method_name(default_tristimulus_method(spectrum_from_arrays(wl, v, SpectrumKind::light, l))));
          },
          py::arg("wavelengths_nm"), py::arg("values"),
          "The method 'auto' picks for this sampling: native (1, 5 nm), astm-e308 (10, 20 nm) or 1nm."
          "\n\nExample: lib.tristimulus_method(*lib.illuminant('F11')) -> 'native'")
      .def(
          "light_xyz",
          [](SpectralLibrary& l, const Array& wl, const Array& v, int observer, const std::string& method) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, SpectrumKind::light, l);
            const StandardObserver o = observer_of(observer);
            const TristimulusMethod used = method_of(method, s);
            const Xyz xyz = for_argument("method", [&] { return light_xyz(s, o, used, l); });
            return vec3(xyz.x, xyz.y, xyz.z);
          },
          py::arg("wavelengths_nm"), py::arg("values"), py::arg("observer") = 2, py::arg("method") = "auto",
          "Relative XYZ (Y = 100) of a light's spectral power (CIE 15:2004 §7 / ASTM E308); observer 2 (CIE 1931) "
          "or 10 (CIE 1964).\n\nExample: rimu.xy(lib.light_xyz(*lib.illuminant('F11'))) -> array([0.3805, 0.3769])")
      .def(
          "reflectance_xyz",
          [](SpectralLibrary& l, const ArrayLike& wavelengths_nm, const ArrayLike& values,
             const std::string& illuminant, int observer, const std::string& method, bool bandpass_corrected) {
            const Array wl = numeric_array(wavelengths_nm, "wavelengths_nm"), v = numeric_array(values, "values");
            if (v.ndim() > 1) return reflectance_stack_xyz(l, wl, v, illuminant, observer, method, bandpass_corrected);
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, SpectrumKind::reflectance, l);
            check_illuminant(l, illuminant);
            const StandardObserver o = observer_of(observer);
            const TristimulusMethod used = method_of(method, s);
            const Xyz xyz = for_argument("method", [&] {
              return reflectance_xyz(s, illuminant, o, used, l, e308_table_of(bandpass_corrected));
            });
            return vec3(xyz.x, xyz.y, xyz.z);
          },
          py::arg("wavelengths_nm"), py::arg("values"), py::arg("illuminant") = "D50", py::arg("observer") = 2,
          py::arg("method") = "auto", py::arg("bandpass_corrected") = true,
          "XYZ of a reflectance factor under a CIE illuminant (perfect diffuser Y = 100): values of shape (N,) give "
          "(3,), a stack (..., N) on the shared wavelengths gives (..., 3). For astm-e308, "
          "bandpass_corrected picks E308 Table 6 (True: data corrected for the instrument's bandpass) or Table 5 "
          "(False: uncorrected data, triangular bandpass = interval).\n\n"
          "Example: lib.reflectance_xyz(*lib.colorchecker('dark skin'), illuminant='D65')")
      .def(
          "white_xyz",
          [](SpectralLibrary& l, const Array& wl, const std::string& illuminant, int observer, const std::string& method,
             bool bandpass_corrected) {
            const TabulatedSpectrum s = sampling_from_array(wl);
            check_illuminant(l, illuminant);
            const StandardObserver o = observer_of(observer);
            const TristimulusMethod used = method_of(method, s);
            const Xyz xyz = for_argument("method", [&] {
              return perfect_diffuser_xyz(s, illuminant, o, used, l, e308_table_of(bandpass_corrected));
            });
            return vec3(xyz.x, xyz.y, xyz.z);
          },
          py::arg("wavelengths_nm"), py::arg("illuminant") = "D50", py::arg("observer") = 2,
          py::arg("method") = "auto", py::arg("bandpass_corrected") = true,
          "The perfect diffuser's XYZ sampled and summed like reflectance_xyz would (CIELAB's white)."
          "\n\nExample: white = lib.white_xyz(np.arange(380, 781, 10), 'D50')")
      .def(
          "cct_duv",
          [](SpectralLibrary& l, const Array& wl, const Array& v, const std::string& method) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, SpectrumKind::light, l);
            const CctSolver solver = cct_solver(l, method, StandardObserver::cie1931_2deg);
            const Xyz xyz = for_argument("wavelengths_nm", [&] {
              return light_xyz(s, StandardObserver::cie1931_2deg, default_tristimulus_method(s), l);
            });
            return cct_tuple(solver.cct_duv(uv1960_of(xyz)), solver);
          },
          py::arg("wavelengths_nm"), py::arg("values"), py::arg("method") = "ohno2013",
          "(CCT in K, Duv, validity), CIE 1931 2°. method: 'ohno2013' (Ohno 2013 on the exact locus, 1000-25000 K, "
          "today's c2, within 0.011 K) or 'robertson1968' (Robertson's isotemperature lines, 1667 K to infinity, "
          "within 0.08 MK⁻¹: 0.5 K at 6500 K). validity is 'ok', or what the tools print "
          "beside a CCT that must not be presented as one: 'below 1000 K' / 'below 1667 K', 'above 25000 K' / "
          "'bluer than an infinite temperature' (the nearest end of the method's range) or '|Duv| > 0.05' (too far "
          "from the locus for a colour temperature to mean anything)."
          "\n\nExample: lib.cct_duv(*lib.illuminant('A')) -> (2855.5, 2.4e-08, 'ok')")
      .def(
          "luminous_efficacy",
          [](SpectralLibrary& l, const Array& wl, const Array& v) {
            return shape_integrals(spectrum_from_arrays(wl, v, SpectrumKind::light, l), l.photopic_v()).efficacy_lm_W();
          },
          py::arg("wavelengths_nm"), py::arg("values"), "Luminous efficacy of radiation, lm/W (360-830 nm).\n\nExample: lib.luminous_efficacy(*lib.illuminant('D65'))")
      .def(
          "light_scale",
          [](SpectralLibrary& l, const Array& wl, const Array& v, const std::string& amount_text) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, SpectrumKind::light, l);
            const LightAmount amount = parse_light_amount(amount_text, argument("amount"));
            const ShapeIntegrals i = for_argument("values", [&] { return shape_integrals(s, l.photopic_v()); });
            return shape_scale(i, amount, argument("values"));
          },
          py::arg("wavelengths_nm"), py::arg("values"), py::arg("amount"),
          "The factor that gives the shape this amount ('800 lm', '2 W/sr', '12 EV' as luminance): "
          "amount / (K_m Σ S V Δλ) for photometric units, amount / ∫ S dλ for radiometric ones."
          "\n\nExample: lib.light_scale(*lib.illuminant('D65'), '800 lm')");

  // Each takes the amount the tools take (check_light_amount_range: EV in [-50, 50], cd/m² and lx in [1e-30, 1e30]),
  // so no result is 0, Inf or NaN.
  const auto checked = [](double (*convert)(double), LightUnit unit, const char* name) {
    return [convert, unit, name](double value) {
      check_light_amount_range({value, unit}, argument(name));
      return convert(value);
    };
  };
  m.def("luminance_from_ev100", checked(&luminance_nt_from_ev100, LightUnit::ev100, "ev100"), py::arg("ev100"),
        "cd/m² a reflected meter reads as EV (ISO 100, K = 12.5).\n\nExample: rimu.luminance_from_ev100(12.0)");
  m.def("ev100_from_luminance", checked(&ev100_from_luminance_nt, LightUnit::nit, "luminance_nt"),
        py::arg("luminance_nt"), "The EV at ISO 100 a reflected meter (K = 12.5) reads for this luminance, cd/m².\n\n"
        "Example: rimu.ev100_from_luminance(100.0)");
  m.def("illuminance_from_ev100", checked(&illuminance_lx_from_ev100, LightUnit::ev100, "ev100"), py::arg("ev100"),
        "lx an incident meter reads as EV (C = 250).\n\nExample: rimu.illuminance_from_ev100(10.0)");
  m.def("ev100_from_illuminance", checked(&ev100_from_illuminance_lx, LightUnit::lux, "illuminance_lx"),
        py::arg("illuminance_lx"), "The EV at ISO 100 an incident meter (C = 250) reads for this illuminance, lx.\n\n"
        "Example: rimu.ev100_from_illuminance(500.0)");
}

}  // namespace rimu::python
