// Colour appearance over arrays: CIECAM02 / CAM16 forward and inverse and their UCS, chromatic adaptation
// (Bradford, CAT02, CAT16, von Kries, XYZ scaling), and CCT -> xy (Planckian with Duv, CIE daylight) and back.
#include <pybind11/stl.h>

#include <cmath>
#include <numbers>

#include "bindings.h"
#include "broadcast.h"
#include "spectral/colour_spaces/chromatic_adaptation.h"
#include "spectral/library/colorimetry_options.h"
#include "spectral/colour_spaces/colour_appearance.h"
#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/colorimetry/planckian_locus.h"
#include "spectral/colorimetry/daylight.h"

namespace rimu::python {
namespace {

// The viewing conditions from the Python arguments, each checked against its name.
ViewingConditions viewing_conditions(const ArrayLike& white, double adapting_luminance, double background_y,
                                     const std::string& surround, bool discount_illuminant) {
  const Colours w = whites_of(white, "white");
  if (!w.leading.empty()) throw InputError(argument("white"), "expected one white (3 values) for the whole call");
  if (!(adapting_luminance > 0.0 && adapting_luminance <= 1e6))
    throw InputError(argument("adapting_luminance"),
                     "expected an adapting luminance L_A in (0, 1e6] cd/m², got " + std::to_string(adapting_luminance));
  if (!(background_y > 0.0 && background_y <= 1e30))
    throw InputError(argument("background_y"),
                     "expected a positive background luminance factor Y_b, got " + std::to_string(background_y));
  ViewingConditions v;
  v.white = xyz_at(w, 0);
  v.adapting_luminance_cd_m2 = adapting_luminance;
  v.background_y = background_y;
  v.surround = surround_option(surround, argument("surround"));
  if (discount_illuminant) v.degree_of_adaptation = 1.0;
  return v;
}

// Every number of `out` finite, or a ValueError naming the input element (colours far outside the spectrum locus
// can leave a model's domain: a negative cone response to a fractional power).
void check_finite_results(const py::array_t<double>& out, std::size_t per_item, const std::vector<py::ssize_t>& leading,
                          const std::string& name) {
  const double* o = out.data();
  for (py::ssize_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(o[i]))
      throw InputError(argument(leading.empty() ? name : element_name(name, leading, i / py::ssize_t(per_item))),
                       "this colour has no appearance correlates under these viewing conditions (outside the "
                       "model's domain)");
}

// The keyword arguments every appearance function takes, after its first two.
#define RIMU_VIEWING_ARGS                                                                                          \
  py::arg("white"), py::arg("adapting_luminance") = 64.0 / std::numbers::pi * 0.2, py::arg("background_y") = 20.0,             \
      py::arg("surround") = "average", py::arg("discount_illuminant") = false

const char* const kViewingDoc =
    "white: the adopted white XYZ (3,) on the colours' scale (Y_w = 100 usually); adapting_luminance: L_A in cd/m² "
    "(default 64/π·0.2 = 4.07, sRGB's 64 lx surround at 20 % grey); background_y: Y_b on the white's scale "
    "(default 20); surround: 'average', 'dim' or 'dark' (F, c, N_c of CIE 159:2004 Table 1); discount_illuminant: "
    "D = 1 instead of D = F·(1 − e^((−L_A − 42)/92)/3.6).";

void bind_model(py::module_& m, AppearanceModel which, const std::string& name, const std::string& ucs_name,
                const std::string& reference) {
  m.def(
      name.c_str(),
      [which](const ArrayLike& xyz, const ArrayLike& white, double l_a, double y_b, const std::string& surround,
              bool discount) {
        const ColourAppearanceModel model(which, viewing_conditions(white, l_a, y_b, surround, discount));
        const Colours c = colours_of(xyz, "xyz");
        py::array_t<double> all = map_items<7>(c.leading, c.count(), [&](std::size_t i) {
          const Appearance a = model.forward(xyz_at(c, i));
          return std::array<double, 7>{a.j, a.c, a.h_deg, a.m, a.s, a.q, a.hue_quadrature};
        });
        check_finite_results(all, 7, c.leading, "xyz");
        py::dict d;
        const char* keys[7] = {"J", "C", "h", "M", "s", "Q", "H"};
        for (py::ssize_t k = 0; k < 7; ++k) {
          py::array_t<double> column = result_array(c.leading, 0);
          for (std::size_t i = 0; i < c.count(); ++i) column.mutable_data()[i] = all.data()[7 * i + size_t(k)];
          d[keys[k]] = c.leading.empty() ? py::object(py::float_(column.data()[0])) : py::object(column);
        }
        return d;
      },
      py::arg("xyz"), RIMU_VIEWING_ARGS,
      (reference + " appearance correlates of XYZ (..., 3): a dict of arrays of the leading shape (floats for one "
                   "colour): 'J' lightness, 'C' chroma, 'h' hue angle (degrees), 'M' colourfulness, 's' saturation, "
                   "'Q' brightness, 'H' hue quadrature (0-400).\n\n" +
       kViewingDoc + "\n\nExample: rimu." + name +
       "([19.01, 20.0, 21.78], [95.05, 100.0, 108.88], adapting_luminance=318.31)['J'] -> 41.731...")
          .c_str());
  m.def(
      (name + "_to_xyz").c_str(),
      [which](const ArrayLike& jmh, const ArrayLike& white, double l_a, double y_b, const std::string& surround,
              bool discount) {
        const ColourAppearanceModel model(which, viewing_conditions(white, l_a, y_b, surround, discount));
        const Colours c = colours_of(jmh, "jmh");
        py::array_t<double> out = map_items<3>(c.leading, c.count(), [&](std::size_t i) {
          const Xyz x = model.inverse(c.at(i)[0], c.at(i)[1], c.at(i)[2]);
          return std::array<double, 3>{x.x, x.y, x.z};
        });
        check_finite_results(out, 3, c.leading, "jmh");
        return out;
      },
      py::arg("jmh"), RIMU_VIEWING_ARGS,
      ("XYZ (..., 3) from " + reference + " lightness J, colourfulness M and hue angle h (degrees) in the last axis: "
                                          "the inverse of " + name + "().\n\n" + kViewingDoc)
          .c_str());
  m.def(
      ucs_name.c_str(),
      [which](const ArrayLike& xyz, const ArrayLike& white, double l_a, double y_b, const std::string& surround,
              bool discount) {
        const ColourAppearanceModel model(which, viewing_conditions(white, l_a, y_b, surround, discount));
        const Colours c = colours_of(xyz, "xyz");
        py::array_t<double> out = map_items<3>(c.leading, c.count(), [&](std::size_t i) {
          const Jab j = ColourAppearanceModel::ucs_of(model.forward(xyz_at(c, i)));
          return std::array<double, 3>{j.j, j.a, j.b};
        });
        check_finite_results(out, 3, c.leading, "xyz");
        return out;
      },
      py::arg("xyz"), RIMU_VIEWING_ARGS,
      ("Uniform colour space J', a', b' of " + reference +
       " (J' = 1.7 J / (1 + 0.007 J), M' = ln(1 + 0.0228 M) / 0.0228): XYZ (..., 3) -> (..., 3); Euclidean "
       "distances in it are colour differences.\n\n" +
       kViewingDoc)
          .c_str());
  m.def(
      (ucs_name + "_to_xyz").c_str(),
      [which](const ArrayLike& jab, const ArrayLike& white, double l_a, double y_b, const std::string& surround,
              bool discount) {
        const ColourAppearanceModel model(which, viewing_conditions(white, l_a, y_b, surround, discount));
        const Colours c = colours_of(jab, "jab");
        py::array_t<double> out = map_items<3>(c.leading, c.count(), [&](std::size_t i) {
          const Appearance a = ColourAppearanceModel::appearance_of_ucs({c.at(i)[0], c.at(i)[1], c.at(i)[2]});
          const Xyz x = model.inverse(a.j, a.m, a.h_deg);
          return std::array<double, 3>{x.x, x.y, x.z};
        });
        check_finite_results(out, 3, c.leading, "jab");
        return out;
      },
      py::arg("jab"), RIMU_VIEWING_ARGS,
      ("XYZ (..., 3) from " + ucs_name + " J', a', b': the inverse of " + ucs_name + "().\n\n" + kViewingDoc).c_str());
}

// Argument `name` as numbers of any shape, each checked by `check` (a refusal names its indices).
template <typename Check>
Array checked_numbers(const ArrayLike& value, const std::string& name, Check check) {
  const Array a = numeric_array(value, name);
  const std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    const SourceLocation at = argument(element_name(name, shape, i));
    check_colour_component(a.data()[i], at);
    check(a.data()[i], at);
  }
  return a;
}

std::vector<py::ssize_t> shape_of(const Array& a) { return {a.shape(), a.shape() + a.ndim()}; }

}  // namespace

void bind_appearance(py::module_& m) {
  bind_model(m, AppearanceModel::ciecam02, "ciecam02", "cam02_ucs", "CIECAM02 (CIE 159:2004)");
  bind_model(m, AppearanceModel::cam16, "cam16", "cam16_ucs", "CAM16 (Li et al. 2017)");

  m.def(
      "adapt",
      [](const ArrayLike& xyz, const ArrayLike& source_white, const ArrayLike& destination_white,
         const std::string& cat) {
        const Colours s = whites_of(source_white, "source_white"), d = whites_of(destination_white, "destination_white");
        if (!s.leading.empty() || !d.leading.empty())
          throw InputError(argument(s.leading.empty() ? "destination_white" : "source_white"),
                           "expected one white (3 values) for the whole call");
        const Matrix3 matrix =
            chromatic_adaptation_matrix(xyz_at(s, 0), xyz_at(d, 0), cat_method_option(cat, argument("cat")));
        return transform_colours(xyz, "xyz", matrix);
      },
      py::arg("xyz"), py::arg("source_white"), py::arg("destination_white"), py::arg("cat") = "cat16",
      "Corresponding colours: XYZ (..., 3) seen under source_white to XYZ under destination_white by a von "
      "Kries-type transform (cat: 'bradford', 'cat02', 'cat16' (Li et al. 2017), 'von-kries' (Hunt-Pointer-"
      "Estevez) or 'xyz-scaling'), complete adaptation. The whites share the colours' scale.\n\n"
      "Example: rimu.adapt([95.047, 100, 108.883], [95.047, 100, 108.883], [96.422, 100, 82.521]) -> "
      "array([96.422, 100., 82.521])");

  m.def(
      "daylight_xy",
      [](const ArrayLike& cct_k) {
        const Array t = checked_numbers(cct_k, "cct_k", [](double v, const SourceLocation& at) {
          for_argument(at.key, [&] { return daylight_chromaticity(v); });
        });
        return map_items<2>(shape_of(t), size_t(t.size()), [&](std::size_t i) {
          const Chromaticity c = daylight_chromaticity(t.data()[i]);
          return std::array<double, 2>{c.x, c.y};
        });
      },
      py::arg("cct_k"),
      "Chromaticity (x, y) of CIE daylight at a correlated colour temperature (CIE 15:2018 eqs. 4.7-4.8, "
      "4000-25000 K): cct_k of any shape -> (..., 2).\n\n"
      "Example: rimu.daylight_xy(6504) -> array([0.31271, 0.32912])");

  auto lib = py::reinterpret_borrow<py::class_<SpectralLibrary>>(m.attr("Library"));
  lib.def(
         "planckian_xy",
         [](SpectralLibrary& l, const ArrayLike& cct_k, double duv, int observer) {
           const Array t = checked_numbers(cct_k, "cct_k", [](double v, const SourceLocation& at) {
             if (!(v >= 500.0 && v <= 1e6))
               throw InputError(at, "expected a temperature in 500-1e6 K, got " + std::to_string(v));
           });
           if (!(std::abs(duv) <= PlanckianLocus::kMaxAbsDuv))
             throw InputError(argument("duv"), "expected |Duv| <= 0.05 (beyond it a CCT means nothing), got " +
                                                   std::to_string(duv));
           const PlanckianLocus locus(l.observer(standard_observer_option(observer, argument("observer"))));
           return map_items<2>(shape_of(t), size_t(t.size()), [&](std::size_t i) {
             const Chromaticity c = locus.chromaticity_at(t.data()[i], duv);
             return std::array<double, 2>{c.x, c.y};
           });
         },
         py::arg("cct_k"), py::arg("duv") = 0.0, py::arg("observer") = 2,
         "Chromaticity (x, y) of the Planckian radiator at cct_k (500 K - 1e6 K, any shape -> (..., 2)), moved "
         "duv along the locus' normal in CIE 1960 (u, v) (positive: above the locus, greenish; Ohno 2013). "
         "Planck's law with today's c2, summed at 1 nm over 360-830 nm (CIE 15:2018 §9.4).\n\n"
         "Example: lib.planckian_xy(2856) -> array([0.4475, 0.4074]) (about illuminant A)")
      .def(
          "xy_to_cct",
          [](SpectralLibrary& l, const ArrayLike& xy, int observer, const std::string& method) {
            const Array a = numeric_array(xy, "xy");
            const std::vector<py::ssize_t> shape = shape_of(a);
            if (shape.empty() || shape.back() != 2)
              throw InputError(argument("xy"), "expected 2 values (x, y), or an array of shape (..., 2)");
            const std::vector<py::ssize_t> leading(shape.begin(), shape.end() - 1);
            for (py::ssize_t i = 0; i < a.size() / 2; ++i) {
              const SourceLocation at = argument(element_name("xy", leading, i));
              check_colour_components(a.data()[2 * i], a.data()[2 * i + 1], 0.0, at);
              if (!(a.data()[2 * i + 1] > 0.0 && a.data()[2 * i] >= 0.0))
                throw InputError(at, "expected a chromaticity with x >= 0 and y > 0");
            }
            const CctSolver solver = cct_solver(l, method, standard_observer_option(observer, argument("observer")));
            const std::size_t n = size_t(a.size() / 2);
            std::vector<CctDuv> results(n);
            for_each_range(n, [&](std::size_t begin, std::size_t end) {
              for (std::size_t i = begin; i < end; ++i)
                results[i] = solver.cct_duv(uv1960_of(Chromaticity{a.data()[2 * i], a.data()[2 * i + 1]}));
            });
            py::array_t<double> cct = result_array(leading, 0), duv = result_array(leading, 0);
            py::array_t<bool> valid(leading);
            for (std::size_t i = 0; i < n; ++i) {
              cct.mutable_data()[i] = results[i].cct_k;
              duv.mutable_data()[i] = results[i].duv;
              valid.mutable_data()[i] = results[i].valid();
            }
            return py::make_tuple(cct, duv, valid);
          },
          py::arg("xy"), py::arg("observer") = 2, py::arg("method") = "ohno2013",
          "CCT (K) and Duv of chromaticities (..., 2) by Ohno (2013) or, with method='robertson1968', by "
          "Robertson's isotemperature lines (2° observer only; within 0.08 MK⁻¹ of the exact CCT, Duv within "
          "1.1e-4), with `valid` False where the tools print a warning instead of a CCT (outside the "
          "method's range: Ohno 1000-25000 K, Robertson 1667 K to infinity; or |Duv| > 0.05): (cct_k, duv, "
          "valid), each of the leading shape.\n\n"
          "Example: lib.xy_to_cct([0.31271, 0.32902]) -> (array(6503.5...), array(0.0032...), array(True))");
}

}  // namespace rimu::python
