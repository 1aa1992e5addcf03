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
           d["special"] = array_of(std::vector<double>(c.special.begin(), c.special.end()));
           d["cct_k"] = c.source.cct_k;
           d["duv"] = c.source.duv;
           d["cct_validity"] = cct_validity_name(c.source.validity);
           d["meaningful"] = c.duv_within_cie_limit;
           return d;
         },
         py::arg("wavelengths_nm"), py::arg("values"), "CIE 13.3-1995 colour rendering of a light (wavelengths_nm, values): a dict {'ra': Ra, 'special': "
         "R1-R14 (numpy array of 14), 'cct_k', 'duv', 'cct_validity', 'meaningful' (False when |Duv| > 5.4e-3, "
         "where CIE 13.3 says Ra means little)}.\n\nExample: lib.cri(*lib.illuminant('F2'))['ra'] -> 64.2 (about)")
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
            d["sample_rf"] = array_of(std::vector<double>(f.sample_fidelity.begin(), f.sample_fidelity.end()));
            std::vector<double> rf, rcs, rhs;
            for (const HueBin& b : f.bins) {
              rf.push_back(b.fidelity);
              rcs.push_back(b.chroma_shift);
              rhs.push_back(b.hue_shift);
            }
            d["bin_rf"] = array_of(rf);
            d["bin_chroma_shift"] = array_of(rcs);
            d["bin_hue_shift"] = array_of(rhs);
            py::array_t<double> reference_ab({kTm30HueBins, 2}), test_ab({kTm30HueBins, 2});
            for (int j = 0; j < kTm30HueBins; ++j) {
              reference_ab.mutable_at(j, 0) = f.bins[size_t(j)].reference_a;
              reference_ab.mutable_at(j, 1) = f.bins[size_t(j)].reference_b;
              test_ab.mutable_at(j, 0) = f.bins[size_t(j)].test_a;
              test_ab.mutable_at(j, 1) = f.bins[size_t(j)].test_b;
            }
            d["bin_reference_ab"] = reference_ab;
            d["bin_test_ab"] = test_ab;
            return d;
          },
          py::arg("wavelengths_nm"), py::arg("values"),
          "CIE 224:2017 / ANSI/IES TM-30-20 colour fidelity of a light (wavelengths_nm, values): a dict {'rf', "
          "'rg', 'cct_k', 'duv', 'cct_validity', 'reference' (the reference illuminant's description), 'sample_rf' "
          "(numpy array of 99, one per colour evaluation sample), 'bin_rf', 'bin_chroma_shift', 'bin_hue_shift' "
          "(numpy arrays of 16 hue bins; shifts as fractions of the reference chroma), 'bin_reference_ab', 'bin_test_ab' (16 x 2: the bins' mean CAM02-UCS a', b', the colour vector graphic's data)}.\n\n"
          "Example: lib.fidelity(*lib.illuminant('F2'))['rf'] -> 70 (about)");
}

}  // namespace rimu::python
