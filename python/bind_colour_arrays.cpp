// The colour arithmetic over arrays: xy, u'v', CIELAB, CIELUV, ΔE and RGB <-> XYZ of a single colour, a (24, 3) stack or an
// (H, W, 3) image alike, through the checks the tools use (colour_value_check.h) and the loop in C++ without the GIL.
#include <cmath>

#include "bindings.h"
#include "broadcast.h"
#include "spectral/colorimetry/cielab.h"
#include "spectral/colorimetry/colour_value_check.h"
#include "spectral/colorimetry/delta_e.h"
#include "spectral/colorimetry/delta_e_94_cmc.h"
#include "spectral/colour_spaces/rgb_colour_space.h"

namespace rimu::python {
namespace {

Lab lab_at(const Colours& c, std::size_t i) { return {c.at(i)[0], c.at(i)[1], c.at(i)[2]}; }

// A (..., 3) conversion relative to a white (xyz, white) -> (..., 3), the white broadcast like any colour.
template <typename Convert>
py::array_t<double> relative_to_white(const ArrayLike& value, const std::string& name, const ArrayLike& white,
                                      Convert convert) {
  Colours x = colours_of(value, name), w = whites_of(white, "white");
  broadcast_colours(x, name, w, "white");
  return map_items<3>(x.leading, x.count(), [&](std::size_t i) { return convert(xyz_at(x, i), xyz_at(w, i)); });
}

// What a chromaticity function answers for a colour that has none (black): refuse (the default), or the
// caller's value for it: a chromaticity (x, y) such as the white's, or NaN when asked for by name.
struct BlackPolicy {
  bool refuse = true;
  std::array<double, 2> value{};
};

BlackPolicy black_policy(const ArrayLike& black) {
  if (black.is_none()) return {};
  if (py::isinstance<py::str>(black)) {
    if (black.cast<std::string>() != "nan")
      throw InputError(argument("black"), "expected None, 'nan' or a chromaticity (2 numbers)");
    return {false, {std::nan(""), std::nan("")}};
  }
  const Array a = numeric_array(black, "black");
  if (a.size() != 2) throw InputError(argument("black"), "expected None, 'nan' or a chromaticity (2 numbers)");
  check_colour_components(a.data()[0], a.data()[1], 0.0, argument("black"));
  return {false, {a.data()[0], a.data()[1]}};
}

// (x, y)-type coordinates of every XYZ: (..., 3) -> (..., 2). `check` refuses a colour without them (black),
// naming it; with a black policy that does not refuse, a colour `has` says has none gets the policy's value.
template <typename Check, typename Has, typename Of>
py::array_t<double> chromaticities(const ArrayLike& xyz, const ArrayLike& black, Check check, Has has, Of of) {
  const Colours c = colours_of(xyz, "xyz");
  const BlackPolicy policy = black_policy(black);
  if (policy.refuse) check_each(c, "xyz", check);
  return map_items<2>(c.leading, c.count(), [&](std::size_t i) {
    const Xyz v = xyz_at(c, i);
    return has(v) ? of(v) : policy.value;
  });
}

bool has_chromaticity(const Xyz& v) { return v.x + v.y + v.z > 0.0; }
bool has_ucs_chromaticity(const Xyz& v) { return has_chromaticity(v) && v.x + 15.0 * v.y + 3.0 * v.z > 0.0; }

// (u, v)-type coordinates of every XYZ: (..., 3) -> (..., 2), black handled as for xy.
template <typename Uv, Uv (*uv_of)(const Xyz&)>
py::array_t<double> ucs_chromaticity(const ArrayLike& xyz, const ArrayLike& black) {
  return chromaticities(xyz, black, &check_has_ucs_chromaticity, &has_ucs_chromaticity, [](const Xyz& v) {
    const Uv uv = uv_of(v);
    return std::array<double, 2>{uv.u, uv.v};
  });
}

py::array_t<double> lab_of_arrays(const ArrayLike& xyz, const ArrayLike& white) {
  return relative_to_white(xyz, "xyz", white, [](const Xyz& v, const Xyz& w) {
    const Lab l = lab_of(v, w);
    return std::array<double, 3>{l.l, l.a, l.b};
  });
}

py::array_t<double> luv_of_arrays(const ArrayLike& xyz, const ArrayLike& white) {
  return relative_to_white(xyz, "xyz", white, [](const Xyz& v, const Xyz& w) {
    const Luv l = luv_of(v, w);
    return std::array<double, 3>{l.l, l.u, l.v};
  });
}

template <typename Difference>
FloatOrArray delta_e_of_arrays(const ArrayLike& lab1, const ArrayLike& lab2, Difference difference,
                               const char* name1 = "lab1", const char* name2 = "lab2") {
  Colours a = colours_of(lab1, name1), b = colours_of(lab2, name2);
  broadcast_colours(a, name1, b, name2);
  return map_scalars(a.leading, a.count(), [&](std::size_t i) { return difference(lab_at(a, i), lab_at(b, i)); });
}

}  // namespace

void bind_colour_arrays(py::module_& m) {
  m.def(
      "xy",
      [](const ArrayLike& xyz, const ArrayLike& black) {
        return chromaticities(xyz, black, &check_has_chromaticity, &has_chromaticity, [](const Xyz& v) {
          const Chromaticity xy = chromaticity_of(v);
          return std::array<double, 2>{xy.x, xy.y};
        });
      },
      py::arg("xyz"), py::arg("black") = py::none(),
      "CIE 1931 chromaticity (x, y) of XYZ (any scale): shape (..., 3) -> (..., 2).\n\n"
      "Black (X + Y + Z <= 0) has none. black=None (the default) refuses it: ValueError naming its indices. "
      "black=(x, y) gives that chromaticity to every such colour (e.g. the white's, as colour-science does), "
      "black='nan' gives NaN there (the only way a NaN comes out of rimu). Any other invalid colour (NaN, Inf) is "
      "refused whatever `black` says.\n\n"
      "Example: rimu.xy([[95.047, 100.0, 108.883], [0, 0, 0]], black=(0.3127, 0.329)) -> "
      "array([[0.3127, 0.3290], [0.3127, 0.329]])");
  m.def("uv_1960", &ucs_chromaticity<Uv1960, &uv1960_of>, py::arg("xyz"), py::arg("black") = py::none(),
        "CIE 1960 UCS (u, v) of XYZ, the diagram CCT and Duv are measured in: u = 4X / (X + 15Y + 3Z), "
        "v = 6Y / (X + 15Y + 3Z). Shape (..., 3) -> (..., 2); black (and X + 15Y + 3Z <= 0) handled as by xy(), "
        "`black` then being a (u, v).\n\n"
        "Example: rimu.uv_1960([109.85, 100.0, 35.58]) -> array([0.2560, 0.3495]) (illuminant A)");
  m.def("uv_1976", &ucs_chromaticity<Uv1976, &uv1976_of>, py::arg("xyz"), py::arg("black") = py::none(),
        "CIE 1976 UCS (u', v') of XYZ (CIE 15:2018 §8.1): u' = 4X / (X + 15Y + 3Z), v' = 9Y / (X + 15Y + 3Z). "
        "Shape (..., 3) -> (..., 2); black handled as by uv_1960().\n\n"
        "Example: rimu.uv_1976([109.85, 100.0, 35.58]) -> array([0.2560, 0.5243]) (illuminant A, CIE 15 Table T.3)");
  m.def("lab", &lab_of_arrays, py::arg("xyz"), py::arg("white"),
        "CIELAB (CIE 15:2018 §8.2.1) of XYZ relative to a white on the same scale (both Y = 100 or both Y = 1): "
        "xyz (..., 3) and white (3,) or broadcastable (..., 3) -> (..., 3) L*, a*, b*.\n\n"
        "Example: rimu.lab([41.24, 21.26, 1.93], [95.047, 100, 108.883]) -> array([53.23, 80.11, 67.22])");
  m.def("xyz_to_lab", &lab_of_arrays, py::arg("xyz"), py::arg("white"), "The same as lab(): CIELAB of XYZ.");
  m.def(
      "lab_to_xyz",
      [](const ArrayLike& lab, const ArrayLike& white) {
        return relative_to_white(lab, "lab", white, [](const Xyz& v, const Xyz& w) {
          const Xyz x = xyz_from_lab(Lab{v.x, v.y, v.z}, w);
          return std::array<double, 3>{x.x, x.y, x.z};
        });
      },
      py::arg("lab"), py::arg("white"),
      "XYZ (on the white's scale) of CIELAB: the inverse of lab(). Shapes as lab().\n\n"
      "Example: rimu.lab_to_xyz([100, 0, 0], [95.047, 100, 108.883]) -> array([95.047, 100., 108.883])");
  m.def("luv", &luv_of_arrays, py::arg("xyz"), py::arg("white"),
        "CIELUV (CIE 15:2018 §8.2.2) of XYZ relative to a white on the same scale: (..., 3) -> (..., 3) L*, u*, v*.\n\n"
        "Example: rimu.luv([20.654008, 12.197225, 5.136952], rimu.xyz_from_xy([0.3127, 0.3290]) * 100)"
        " -> array([41.5279, 96.8363, 17.7521])");
  m.def("xyz_to_luv", &luv_of_arrays, py::arg("xyz"), py::arg("white"), "The same as luv(): CIELUV of XYZ.");
  m.def(
      "luv_to_xyz",
      [](const ArrayLike& luv, const ArrayLike& white) {
        return relative_to_white(luv, "luv", white, [](const Xyz& v, const Xyz& w) {
          const Xyz x = xyz_from_luv(Luv{v.x, v.y, v.z}, w);
          return std::array<double, 3>{x.x, x.y, x.z};
        });
      },
      py::arg("luv"), py::arg("white"), "XYZ of CIELUV: the inverse of luv(). L* = 0 gives black.");
  m.def(
      "xyz_from_xy",
      [](const ArrayLike& xy, double luminance_y) {
        check_colour_component(luminance_y, argument("luminance_y"));
        const Array a = numeric_array(xy, "xy");
        const std::vector<py::ssize_t> shape(a.shape(), a.shape() + a.ndim());
        if (shape.empty() || shape.back() != 2)
          throw InputError(argument("xy"), "expected 2 values (x, y), or an array of shape (..., 2)");
        const std::vector<py::ssize_t> leading(shape.begin(), shape.end() - 1);
        const double* v = a.data();
        for (py::ssize_t i = 0; i < a.size() / 2; ++i) {
          check_colour_components(v[2 * i], v[2 * i + 1], 0.0, argument(element_name("xy", leading, i)));
          if (!(v[2 * i + 1] > 0.0))
            throw InputError(argument(element_name("xy", leading, i)), "y must be positive to give XYZ");
        }
        return map_items<3>(leading, size_t(a.size() / 2), [&](std::size_t i) {
          const Xyz x = xyz_from_xyY({v[2 * i], v[2 * i + 1]}, luminance_y);
          return std::array<double, 3>{x.x, x.y, x.z};
        });
      },
      py::arg("xy"), py::arg("luminance_y") = 1.0,
      "XYZ of a chromaticity (x, y) at luminance Y: (..., 2) -> (..., 3). y must be positive.\n\n"
      "Example: rimu.xyz_from_xy([0.3127, 0.3290], 100) -> array([95.04559..., 100., 108.9057...])");
  m.def(
      "delta_e_2000",
      [](const ArrayLike& lab1, const ArrayLike& lab2) {
        return delta_e_of_arrays(lab1, lab2, [](const Lab& a, const Lab& b) { return delta_e_2000(a, b); });
      },
      py::arg("lab1"), py::arg("lab2"),
      "CIEDE2000 ΔE00 (CIE 142-2001; kL = kC = kH = 1) between two CIELAB arrays (..., 3) that broadcast: a float "
      "for one pair, an array of the leading shape otherwise. Symmetric.\n\n"
      "Example: rimu.delta_e_2000([50, 2.6772, -79.7751], [50, 0, -82.7485]) -> 2.0425 (Sharma et al. 2005, pair 1)");
  m.def(
      "delta_e_1976",
      [](const ArrayLike& lab1, const ArrayLike& lab2) {
        return delta_e_of_arrays(lab1, lab2, [](const Lab& a, const Lab& b) { return delta_e_1976(a, b); });
      },
      py::arg("lab1"), py::arg("lab2"),
      "CIE 1976 ΔE*ab, the Euclidean distance in CIELAB; broadcast as delta_e_2000.\n\n"
      "Example: rimu.delta_e_1976([50, 0, 0], [53, 4, 0]) -> 5.0");
  m.def(
      "delta_e_1994",
      [](const ArrayLike& reference, const ArrayLike& sample, bool textiles) {
        const Cie94Factors f = textiles ? Cie94Factors::textiles() : Cie94Factors::graphic_arts();
        return delta_e_of_arrays(reference, sample, [&](const Lab& a, const Lab& b) { return delta_e_1994(a, b, f); },
                                 "reference", "sample");
      },
      py::arg("reference"), py::arg("sample"), py::arg("textiles") = false,
      "CIE94 ΔE*94 (CIE 116-1995) of `sample` against `reference` (CIELAB, (..., 3), broadcast as delta_e_2000). "
      "Not symmetric: the reference's chroma sets the weights. textiles=False uses the graphic-arts constants "
      "(kL = 1, K1 = 0.045, K2 = 0.015), True the textiles ones (kL = 2, K1 = 0.048, K2 = 0.014).\n\n"
      "Example: rimu.delta_e_1994([100, 21.5721, 272.2282], [100, 426.6795, 72.3959]) -> 83.779...");
  m.def(
      "delta_e_cmc",
      [](const ArrayLike& reference, const ArrayLike& sample, double l, double c) {
        for (const auto& [value, name] : {std::pair{l, "l"}, std::pair{c, "c"}})
          if (!(value > 0.0 && value <= 100.0))
            throw InputError(argument(name), "expected a weight in (0, 100], got " + std::to_string(value));
        return delta_e_of_arrays(reference, sample, [&](const Lab& a, const Lab& b) { return delta_e_cmc(a, b, l, c); },
                                 "reference", "sample");
      },
      py::arg("reference"), py::arg("sample"), py::arg("l") = 2.0, py::arg("c") = 1.0,
      "CMC(l:c) (Clarke, McDonald & Rigg 1984; ISO 105-J03) of `sample` against `reference` (CIELAB, (..., 3), "
      "broadcast as delta_e_2000). l = 2, c = 1 (the default) for acceptability, l = c = 1 for perceptibility. "
      "Not symmetric.\n\n"
      "Example: rimu.delta_e_cmc([100, 21.5721, 272.2282], [100, 426.6795, 72.3959]) -> 172.70...");
  m.def(
      "rgb_to_xyz",
      [](const ArrayLike& rgb, const std::string& space) {
        return transform_colours(rgb, "rgb", space_named(space, "space").rgb_to_xyz());
      },
      py::arg("rgb"), py::arg("space") = "srgb-linear",
      "Linear RGB (..., 3) in a built-in space (colour_spaces()) to XYZ with the space's white at Y = 1.\n\n"
      "Example: rimu.rgb_to_xyz([1, 1, 1]) -> array([0.9505, 1., 1.089])");
  m.def(
      "xyz_to_rgb",
      [](const ArrayLike& xyz, const std::string& space) {
        return transform_colours(xyz, "xyz", space_named(space, "space").xyz_to_rgb());
      },
      py::arg("xyz"), py::arg("space") = "srgb-linear",
      "XYZ (..., 3) to linear RGB in a built-in space, without adaptation (adapt() first if the whites differ).\n\n"
      "Example: rimu.xyz_to_rgb([0.9505, 1.0, 1.089]) -> array([1., 1., 1.]) (about)");
}

}  // namespace rimu::python
