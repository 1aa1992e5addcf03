// Colour rendering (CIE 13.3 Ra) and colour fidelity (CIE 224:2017 Rf, TM-30-20 Rg and hue bins).
#include <pybind11/stl.h>

#include "bindings.h"
#include "spectral/colour_rendering/colour_fidelity.h"
#include "spectral/colour_rendering/colour_rendering_index.h"
#include "spectral/colorimetry/planckian_locus.h"

namespace rimu::python {

void bind_quality(py::module_& m) {
  auto lib = py::reinterpret_borrow<py::class_<SpectralLibrary>>(m.attr("Library"));
  lib.def(
         "cri",
         [](SpectralLibrary& l, const Array& wl, const Array& v) {
           const TabulatedSpectrum s = spectrum_from_arrays(wl, v, SpectrumKind::light, l);
           const ColourRenderingIndex c = for_argument("values", [&] { return colour_rendering_index(s, l); });
           py::dict d;
           d["ra"] = c.ra;
           d["special"] = std::vector<double>(c.special.begin(), c.special.end());
           d["cct_k"] = c.source.cct_k;
           d["duv"] = c.source.duv;
           d["cct_validity"] = cct_validity_name(c.source.validity);
           d["meaningful"] = c.duv_within_cie_limit;
           return d;
         },
         py::arg("wavelengths_nm"), py::arg("values"), "CIE 13.3-1995: {'ra', 'special' (R1-R14), 'cct_k', 'duv', 'cct_validity', 'meaningful'}.")
      .def(
          "fidelity",
          [](SpectralLibrary& l, const Array& wl, const Array& v) {
            const TabulatedSpectrum s = spectrum_from_arrays(wl, v, SpectrumKind::light, l);
            const ColourFidelity f = for_argument("values", [&] { return ColourFidelityEvaluator(l).evaluate(s); });
            py::dict d;
            d["rf"] = f.rf;
            d["rg"] = f.rg;
            d["cct_k"] = f.cct.cct_k;
            d["duv"] = f.cct.duv;
            d["cct_validity"] = cct_validity_name(f.cct.validity);
            d["reference"] = f.reference;
            d["sample_rf"] = std::vector<double>(f.sample_fidelity.begin(), f.sample_fidelity.end());
            std::vector<double> rf, rcs, rhs;
            for (const HueBin& b : f.bins) {
              rf.push_back(b.fidelity);
              rcs.push_back(b.chroma_shift);
              rhs.push_back(b.hue_shift);
            }
            d["bin_rf"] = rf;
            d["bin_chroma_shift"] = rcs;
            d["bin_hue_shift"] = rhs;
            return d;
          },
          py::arg("wavelengths_nm"), py::arg("values"),
          "CIE 224:2017 / TM-30-20: {'rf', 'rg', 'cct_k', 'duv', 'cct_validity', 'reference', 'sample_rf' (99), 'bin_rf', "
          "'bin_chroma_shift', 'bin_hue_shift' (16 each; shifts as fractions)}.");
}

}  // namespace rimu::python
