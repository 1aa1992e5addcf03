// rimu.Library: tables, tristimulus values of lights and reflectances (by method), CCT/Duv and light units.
#include <pybind11/stl.h>

#include "bindings.h"
#include "spectral/colorimetry.h"
#include "spectral/error.h"
#include "spectral/light_units.h"
#include "spectral/planckian_locus.h"
#include "spectral/reflectance_report.h"
#include "spectral/tabulated_colorimetry.h"

namespace rimu::python {
namespace {

StandardObserver observer_of(int degrees) {
  if (degrees == 2) return StandardObserver::cie1931_2deg;
  if (degrees == 10) return StandardObserver::cie1964_10deg;
  throw InputError({}, "observer: expected 2 (CIE 1931) or 10 (CIE 1964), got " + std::to_string(degrees));
}

/// "auto" = the default for the data's spacing; otherwise native, 1nm or astm-e308.
TristimulusMethod method_of(const std::string& name, const TabulatedSpectrum& s) {
  if (name == "auto") return default_tristimulus_method(s);
  if (auto m = parse_tristimulus_method(name)) return *m;
  throw InputError({}, "method: expected auto, native, 1nm or astm-e308, got '" + name + "'");
}

E308Table e308_table_of(bool bandpass_corrected) {
  return bandpass_corrected ? E308Table::table6_bandpass_corrected : E308Table::table5_uncorrected;
}

}  // namespace

void bind_colorimetry(py::module_& m) {
  auto lib = py::reinterpret_borrow<py::class_<SpectralLibrary>>(m.attr("Library"));
  lib.def(
         "illuminant",
         [](SpectralLibrary& l, const std::string& name) {
           const SpectrumPtr s = l.illuminant(name);
           return arrays_from_spectrum(dynamic_cast<const TabulatedSpectrum&>(*s));
         },
         py::arg("name"), "A CIE illuminant's table (A, D50, D65, E, F1-F12, FL3.x, HP1-5, LED-...) as (wavelengths_nm, power).")
      .def_static("illuminant_names", &SpectralLibrary::illuminant_names)
      .def(
          "colorchecker",
          [](SpectralLibrary& l, const std::string& patch) { return arrays_from_spectrum(colorchecker_patch(l, patch)); },
          py::arg("patch"), "A ColorChecker Classic patch (BabelColor average, 10 nm), e.g. 'dark skin'.")
      .def(
          "tristimulus_method",
          [](SpectralLibrary&, const Array& wl, const Array& v) {
            return std::string(method_name(default_tristimulus_method(spectrum_from_arrays(wl, v, Extrapolation::zero, "spectrum"))));
          },
          py::arg("wavelengths_nm"), py::arg("values"),
          "The method 'auto' picks for this sampling: native (1, 5 nm), astm-e308 (10, 20 nm) or 1nm.")
      .def(
          "light_xyz",
          [](SpectralLibrary& l, const Array& wl, const Array& v, int observer, const std::string& method) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, Extrapolation::zero, "light");
            const Xyz xyz = light_xyz(s, observer_of(observer), method_of(method, s), l);
            return vec3(xyz.x, xyz.y, xyz.z);
          },
          py::arg("wavelengths_nm"), py::arg("values"), py::arg("observer") = 2, py::arg("method") = "auto",
          "Relative XYZ (Y = 100) of a light's spectral power (CIE 15:2004 §7 / ASTM E308).")
      .def(
          "reflectance_xyz",
          [](SpectralLibrary& l, const Array& wl, const Array& v, const std::string& illuminant, int observer,
             const std::string& method, bool bandpass_corrected) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, Extrapolation::clamp, "reflectance");
            const Xyz xyz = reflectance_xyz(s, illuminant, observer_of(observer), method_of(method, s), l,
                                            e308_table_of(bandpass_corrected));
            return vec3(xyz.x, xyz.y, xyz.z);
          },
          py::arg("wavelengths_nm"), py::arg("values"), py::arg("illuminant") = "D50", py::arg("observer") = 2,
          py::arg("method") = "auto", py::arg("bandpass_corrected") = true,
          "XYZ of a reflectance factor under a CIE illuminant (perfect diffuser Y = 100). For astm-e308, "
          "bandpass_corrected picks E308 Table 6 (True: data corrected for the instrument's bandpass) or Table 5 "
          "(False: uncorrected data, triangular bandpass = interval).")
      .def(
          "white_xyz",
          [](SpectralLibrary& l, const Array& wl, const std::string& illuminant, int observer, const std::string& method,
             bool bandpass_corrected) {
            const TabulatedSpectrum s(std::vector<double>(wl.data(), wl.data() + wl.size()),
                                      std::vector<double>(size_t(wl.size()), 1.0), Extrapolation::clamp, "sampling");
            const Xyz xyz = perfect_diffuser_xyz(s, illuminant, observer_of(observer), method_of(method, s), l,
                                                 e308_table_of(bandpass_corrected));
            return vec3(xyz.x, xyz.y, xyz.z);
          },
          py::arg("wavelengths_nm"), py::arg("illuminant") = "D50", py::arg("observer") = 2,
          py::arg("method") = "auto", py::arg("bandpass_corrected") = true,
          "The perfect diffuser's XYZ sampled and summed like reflectance_xyz would (CIELAB's white).")
      .def(
          "cct_duv",
          [](SpectralLibrary& l, const Array& wl, const Array& v) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, Extrapolation::zero, "light");
            const Xyz xyz = light_xyz(s, StandardObserver::cie1931_2deg, default_tristimulus_method(s), l);
            const CctDuv c = PlanckianLocus(l.observer(StandardObserver::cie1931_2deg)).cct_duv(uv1960_of(xyz));
            return py::make_tuple(c.cct_k, c.duv);
          },
          py::arg("wavelengths_nm"), py::arg("values"), "(CCT in K, Duv) by Ohno (2013), CIE 1931 2°.")
      .def(
          "luminous_efficacy",
          [](SpectralLibrary& l, const Array& wl, const Array& v) {
            return shape_integrals(spectrum_from_arrays(wl, v, Extrapolation::zero, "light"), l.photopic_v()).efficacy_lm_W();
          },
          py::arg("wavelengths_nm"), py::arg("values"), "Luminous efficacy of radiation, lm/W (360-830 nm).")
      .def(
          "light_scale",
          [](SpectralLibrary& l, const Array& wl, const Array& v, const std::string& amount_text) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, Extrapolation::zero, "light");
            const LightAmount amount = parse_light_amount(amount_text, {"", 0, "amount"});
            const ShapeIntegrals i = shape_integrals(s, l.photopic_v());
            if (amount.unit == LightUnit::ev100) return luminance_nt_from_ev100(amount.value) / i.luminous;
            return amount.value / (is_photometric(amount.unit) ? i.luminous : i.radiant);
          },
          py::arg("wavelengths_nm"), py::arg("values"), py::arg("amount"),
          "The factor that gives the shape this amount ('800 lm', '2 W/sr', '12 EV' as luminance): "
          "amount / (K_m Σ S V Δλ) for photometric units, amount / ∫ S dλ for radiometric ones.");

  m.def("luminance_from_ev100", &luminance_nt_from_ev100, py::arg("ev100"), "cd/m² a reflected meter reads as EV (ISO 100, K = 12.5).");
  m.def("ev100_from_luminance", &ev100_from_luminance_nt, py::arg("luminance_nt"));
  m.def("illuminance_from_ev100", &illuminance_lx_from_ev100, py::arg("ev100"), "lx an incident meter reads as EV (C = 250).");
  m.def("ev100_from_illuminance", &ev100_from_illuminance_lx, py::arg("illuminance_lx"));
}

}  // namespace rimu::python
