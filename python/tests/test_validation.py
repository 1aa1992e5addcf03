"""The module refuses what the tools refuse, with their explanation and Python's argument names, and never answers
NaN or Inf (docs/python.md: "bad input raises ValueError with the same message the tools print")."""
import math
import unittest

import numpy as np

import rimu


def finite(result):
    """True if every number in a result (number, array, tuple, dict) is finite."""
    if isinstance(result, dict):
        return all(finite(v) for v in result.values())
    if isinstance(result, (tuple, list)):
        return all(finite(v) for v in result)
    if isinstance(result, (str, bool)):
        return True
    return bool(np.all(np.isfinite(np.asarray(result, dtype=float))))


class ToolsCases(unittest.TestCase):
    """Each case of the hardening report: silent nonsense before, a ValueError (or the tools' flag) now."""

    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()
        cls.wl, cls.power = cls.lib.illuminant("F2")
        cls.patch_wl, cls.patch = cls.lib.colorchecker("dark skin")

    def test_negative_power_is_refused(self):
        # Relative XYZ divides by Y: an all-negative light gave the colour of the positive one.
        with self.assertRaisesRegex(ValueError, r"^values\[0\]: spectral power cannot be negative"):
            self.lib.light_xyz(self.wl, -self.power)

    def test_reflectance_in_percent_is_refused(self):
        with self.assertRaisesRegex(ValueError, r"^values\[0\]: reflectance factor [0-9.]+ is above 1\.5"):
            self.lib.reflectance_xyz(self.patch_wl, 100 * self.patch)

    def test_negative_reflectance_is_refused(self):
        r = self.patch.copy()
        r[3] = -0.5
        with self.assertRaisesRegex(ValueError, r"^values\[3\]: reflectance factor -0\.5 is negative"):
            self.lib.reflectance_xyz(self.patch_wl, r)

    def test_wavelengths_in_micrometres_are_refused(self):
        with self.assertRaisesRegex(ValueError, r"^wavelengths_nm\[\d+\]: .*micrometres"):
            self.lib.light_xyz(self.wl / 1000, self.power)

    def test_lab_with_a_zero_white_is_refused(self):
        with self.assertRaisesRegex(ValueError, r"^white: a reference white needs X, Y and Z in"):
            rimu.lab(np.array([10.0, 10.0, 10.0]), np.zeros(3))

    def test_emission_that_overflows_is_refused(self):
        with self.assertRaisesRegex(ValueError, r"^rgb: expected three finite components in \[-1e30, 1e30\]"):
            self.lib.upsample_emission(np.array([1e308, 0.0, 0.0]))

    def test_subnormal_light_is_refused(self):
        with self.assertRaisesRegex(ValueError, r"^values"):
            self.lib.fidelity(self.wl, self.power * 1e-310)

    def test_light_that_overflows_is_refused(self):
        with self.assertRaisesRegex(ValueError, r"^values"):
            self.lib.light_xyz(self.wl, self.power / self.power.max() * 1.7e308)

    def test_zero_spectrum_has_no_cct(self):
        with self.assertRaisesRegex(ValueError, r"^values: .*has no power in 360-830 nm"):
            self.lib.cct_duv(self.wl, np.zeros_like(self.power))

    def test_cct_carries_the_validity_the_tools_print(self):
        # A 550 nm line lies far above the locus: the CLI prints "(|Duv| > 0.05)" beside its CCT.
        wl = np.array([549.0, 550.0, 551.0])
        cct, duv, validity = self.lib.cct_duv(wl, np.array([0.0, 1.0, 0.0]))
        self.assertEqual(validity, "|Duv| > 0.05")
        self.assertGreater(abs(duv), 0.05)
        self.assertEqual(self.lib.cct_duv(*self.lib.illuminant("A"))[2], "ok")
        self.assertEqual(self.lib.fidelity(self.wl, self.power)["cct_validity"], "ok")

    def test_ev_of_zero_luminance_is_refused(self):
        with self.assertRaisesRegex(ValueError, r"^luminance_nt: a light's amount must be in \[1e-30, 1e\+30\] nt; got 0"):
            rimu.ev100_from_luminance(0.0)

    def test_messages_name_arguments_not_options(self):
        with self.assertRaises(ValueError) as patch:
            self.lib.colorchecker("dark skinn")
        self.assertTrue(str(patch.exception).startswith("patch: unknown ColorChecker patch 'dark skinn'"))
        with self.assertRaises(ValueError) as method:
            self.lib.reflectance_xyz(self.patch_wl, self.patch, "F3")  # no E308 weights for F3
        self.assertRegex(str(method.exception), r"^method: no ASTM E308 weights .*use the native or 1nm")
        for error in (patch.exception, method.exception):
            self.assertNotIn("--", str(error))
        with self.assertRaisesRegex(ValueError, r"^method: unknown tristimulus method 'trapezoid'; use auto, native"):
            self.lib.light_xyz(self.wl, self.power, method="trapezoid")
        with self.assertRaisesRegex(ValueError, r"^observer: expected 2 or 10"):
            self.lib.light_xyz(self.wl, self.power, observer=4)
        with self.assertRaisesRegex(ValueError, r"^illuminant: unknown illuminant 'D66'"):
            self.lib.reflectance_xyz(self.patch_wl, self.patch, "D66")

    def test_render_with_one_dimension_keeps_the_aspect_ratio(self):
        # data/scenes/cornell_box/scene.json is 256 x 256; a 2:1 request on one side keeps 1:1.
        image = self.lib.render(width=12, samples_per_pixel=1, seed=1)
        self.assertEqual(image.shape, (12, 12, 3))
        image = self.lib.render(height=10, samples_per_pixel=1, seed=1)
        self.assertEqual(image.shape, (10, 10, 3))
        with self.assertRaisesRegex(ValueError, r"^width: expected a whole number in 1-32768, got 0"):
            self.lib.render(width=0)
        with self.assertRaisesRegex(ValueError, r"^samples_per_pixel: expected a whole number in 1-16777216"):
            self.lib.render(width=8, samples_per_pixel=-1)


class Sweep(unittest.TestCase):
    """Every function against NaN, Inf, negative, zero, empty and mismatched inputs: a ValueError naming the
    argument, or (where the input is meaningful) a finite answer. Never NaN or Inf."""

    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()

    def cases(self):
        lib = self.lib
        wl, p = lib.illuminant("D65")
        rwl, r = lib.colorchecker("orange")
        xyz, white, lab = np.array([20.0, 21.0, 22.0]), np.array([95.047, 100.0, 108.883]), np.array([50.0, 10.0, -5.0])
        rgb = np.array([0.5, 0.2, 0.1])

        def spectra(f, kind):
            """The sweep of a function of (wavelengths_nm, values)."""
            values = p if kind == "light" else r
            grid = wl if kind == "light" else rwl
            bad_nan, bad_inf, neg, zero = values.copy(), values.copy(), values.copy(), np.zeros_like(values)
            bad_nan[5], bad_inf[5], neg[5] = np.nan, np.inf, -0.25
            wl_nan = grid.copy()
            wl_nan[2] = np.nan
            rows = [
                ("values NaN", lambda: f(grid, bad_nan), "values[5]"),
                ("values Inf", lambda: f(grid, bad_inf), "values[5]"),
                ("values negative", lambda: f(grid, neg), "values[5]"),
                ("wavelengths NaN", lambda: f(wl_nan, values), "wavelengths_nm[2]"),
                ("wavelengths negative", lambda: f(-grid[::-1], values), "wavelengths_nm"),
                ("empty", lambda: f(np.array([]), np.array([])), "wavelengths_nm"),
                ("mismatched", lambda: f(grid, values[:-1]), "values"),
                # A stack of reflectances is a stack (..., N); a light is one spectrum.
                ("2-D", lambda: f(grid, np.stack([values, values])), "values" if kind == "light" else None),
            ]
            rows.append(("zero", lambda: f(grid, zero), "values" if kind == "light" else None))
            return rows

        rows = []
        for name in ("light_xyz", "cct_duv", "luminous_efficacy", "cri", "fidelity", "tristimulus_method"):
            rows += [(name + ": " + c, call, arg) for c, call, arg in spectra(getattr(lib, name), "light")]
        rows += [("light_scale: " + c, call, arg)
                 for c, call, arg in spectra(lambda a, b: lib.light_scale(a, b, "800 lm"), "light")]
        rows += [("reflectance_xyz: " + c, call, arg) for c, call, arg in spectra(lib.reflectance_xyz, "reflectance")]

        def triples(name, f, arg):
            return [
                (name + ": NaN", lambda: f(np.array([np.nan, 1.0, 1.0])), arg),
                (name + ": Inf", lambda: f(np.array([1.0, np.inf, 1.0])), arg),
                (name + ": 1e308", lambda: f(np.array([1e308, 1.0, 1.0])), arg),
                (name + ": empty", lambda: f(np.array([])), arg),
                (name + ": 4 values", lambda: f(np.ones(4)), arg),
                (name + ": negative", lambda: f(np.array([-0.5, 0.2, 0.1])), arg if name == "xy" else None),
                (name + ": zero", lambda: f(np.zeros(3)), arg if name in ("xy", "lab white") else None),
            ]

        rows += triples("xy", rimu.xy, "xyz")
        rows += triples("lab xyz", lambda v: rimu.lab(v, white), "xyz")
        rows += [r_ for r_ in triples("lab white", lambda v: rimu.lab(xyz, v), "white") if "negative" not in r_[0]]
        rows.append(("lab white: negative", lambda: rimu.lab(xyz, np.array([-95.0, 100.0, 108.0])), "white"))
        rows += triples("delta_e_2000 lab1", lambda v: rimu.delta_e_2000(v, lab), "lab1")
        rows += triples("delta_e_2000 lab2", lambda v: rimu.delta_e_2000(lab, v), "lab2")
        rows += triples("delta_e_1976 lab1", lambda v: rimu.delta_e_1976(v, lab), "lab1")
        rows += triples("rgb_to_xyz", lambda v: rimu.rgb_to_xyz(v), "rgb")
        rows += triples("xyz_to_rgb", lambda v: rimu.xyz_to_rgb(v), "xyz")
        rows += triples("upsample_reflectance", lambda v: lib.upsample_reflectance(v), "rgb")
        rows += triples("upsample_emission", lambda v: lib.upsample_emission(v), "rgb")
        for w in ("source_white", "destination_white"):
            def cam(v, w=w):
                return rimu.chromatic_adaptation_matrix(v, white) if w == "source_white" else \
                    rimu.chromatic_adaptation_matrix(white, v)
            rows += [(c, call, w) for c, call, _ in triples("chromatic_adaptation_matrix " + w, cam, w)]
        rows += [
            ("rgb_to_xyz: space", lambda: rimu.rgb_to_xyz(rgb, "srgb-lin"), "space"),
            ("rgb_conversion_matrix: cat", lambda: rimu.rgb_conversion_matrix("srgb-linear", "acescg", "cat97"), "cat"),
            ("rgb_conversion_matrix: destination", lambda: rimu.rgb_conversion_matrix("srgb-linear", "p3"), "destination"),
            ("srgb_encode: NaN", lambda: rimu.srgb_encode(np.array([0.1, np.nan])), "linear[1]"),
            ("srgb_decode: Inf", lambda: rimu.srgb_decode(np.array([[0.1], [np.inf]])), "encoded[1, 0]"),
            ("srgb_encode: negative", lambda: rimu.srgb_encode(-0.5), None),
            ("white_xyz: NaN", lambda: lib.white_xyz(np.array([400.0, np.nan, 700.0])), "wavelengths_nm[1]"),
            ("white_xyz: empty", lambda: lib.white_xyz(np.array([])), "wavelengths_nm"),
            ("white_xyz: illuminant", lambda: lib.white_xyz(rwl, "D66"), "illuminant"),
            ("illuminant: unknown", lambda: lib.illuminant("D66"), "illuminant"),
        ]
        for f, arg in ((rimu.luminance_from_ev100, "ev100"), (rimu.illuminance_from_ev100, "ev100"),
                       (rimu.ev100_from_luminance, "luminance_nt"), (rimu.ev100_from_illuminance, "illuminance_lx")):
            ev = arg == "ev100"
            rows += [
                (f.__name__ + ": NaN", lambda f=f: f(math.nan), arg),
                (f.__name__ + ": Inf", lambda f=f: f(math.inf), arg),
                (f.__name__ + ": 1e308", lambda f=f: f(1e308), arg),
                (f.__name__ + ": negative", lambda f=f: f(-1.0), None if ev else arg),
                (f.__name__ + ": zero", lambda f=f: f(0.0), None if ev else arg),
            ]
        return rows

    def test_every_function_refuses_or_answers_finite(self):
        rows = self.cases()
        self.assertGreater(len(rows), 150)
        for name, call, argument in rows:
            with self.subTest(name):
                if argument is None:
                    self.assertTrue(finite(call()), name)
                else:
                    with self.assertRaises(ValueError) as caught:
                        call()
                    self.assertTrue(str(caught.exception).startswith(argument),
                                    f"{name}: {caught.exception!s} does not name {argument}")


if __name__ == "__main__":
    unittest.main()
