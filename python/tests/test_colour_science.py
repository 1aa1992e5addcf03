"""The colour science beyond CIELAB against published values (each names its source and the tolerance its printed
digits allow): u'v' and uv, CIELUV, ΔE94 and CMC(l:c), CIECAM02 / CAM16 and their UCS, CAT16, CCT -> xy."""
import unittest

import numpy as np

import rimu
from test_validation import finite

D65_XY = np.array([0.3127, 0.3290])
# colour-science 0.4's test values (colour/difference/tests/test_delta_e.py), printed to 8-10 decimals.
REFERENCE = np.array([100.0, 21.57210357, 272.22819350])
SAMPLES = np.array([[100.0, 426.67945353, 72.39590835], [100.0, 74.05216981, 276.45318193],
                    [100.0, 8.32281957, -73.58297716]])


class Chromaticity(unittest.TestCase):
    def test_uv_of_illuminants_a_and_d65_match_cie15_table_t3(self):
        # CIE 15:2004 Table T.3 (1931 2°): A XYZ (109.85, 100, 35.58), u' 0.2560, v' 0.5243; D65 XYZ (95.04, 100,
        # 108.88), u' 0.1978, v' 0.4683 - four decimals, so within 5e-5. v (1960) = 2/3 v'.
        xyz = np.array([[109.85, 100.0, 35.58], [95.04, 100.0, 108.88]])
        published = np.array([[0.2560, 0.5243], [0.1978, 0.4683]])
        uv76 = rimu.uv_1976(xyz)
        self.assertEqual(uv76.shape, (2, 2))
        np.testing.assert_allclose(uv76, published, atol=5e-5)
        uv60 = rimu.uv_1960(xyz)
        np.testing.assert_allclose(uv60[:, 0], uv76[:, 0], rtol=1e-15)
        np.testing.assert_allclose(uv60[:, 1], uv76[:, 1] * 2 / 3, rtol=1e-15)

    def test_black_has_no_uv(self):
        with self.assertRaisesRegex(ValueError, r"^xyz\[1\]: X \+ Y \+ Z"):
            rimu.uv_1976(np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]))

    def test_black_pixels_follow_the_black_policy(self):
        image = np.full((4, 5, 3), 20.0)
        image[1, 2] = 0.0
        with self.assertRaisesRegex(ValueError, r"^xyz\[1, 2\]: "):
            rimu.xy(image)                                          # the default: refused, named
        filled = rimu.xy(image, black=D65_XY)
        np.testing.assert_array_equal(filled[1, 2], D65_XY)
        np.testing.assert_array_equal(filled[0, 0], [1 / 3, 1 / 3])
        masked = rimu.uv_1976(image, black="nan")
        self.assertTrue(np.all(np.isnan(masked[1, 2])))
        self.assertEqual(np.count_nonzero(np.isnan(masked)), 2)
        image[0, 0, 1] = np.nan                                    # not black: refused whatever the policy
        with self.assertRaisesRegex(ValueError, r"^xyz\[0, 0\]: "):
            rimu.xy(image, black="nan")
        with self.assertRaisesRegex(ValueError, "^black: "):
            rimu.xy(image[1:], black="white")

    def test_xyz_from_xy_inverts_xy(self):
        xyz = rimu.xyz_from_xy(np.array([[0.3127, 0.3290], [0.64, 0.33]]), 100.0)
        np.testing.assert_allclose(rimu.xy(xyz), [[0.3127, 0.3290], [0.64, 0.33]], rtol=1e-14)
        np.testing.assert_allclose(xyz[:, 1], 100.0)


class Luv(unittest.TestCase):
    def test_luv_matches_colour_science_examples(self):
        # colour-science 0.4 (colour/models/tests/test_cie_luv.py): XYZ (Y = 1) against the D65 white xy (0.3127,
        # 0.3290), Luv to 8 decimals: within 5e-9 (plus rounding).
        xyz = np.array([[0.20654008, 0.12197225, 0.05136952], [0.14222010, 0.23042768, 0.10495772],
                        [0.07818780, 0.06157201, 0.28099326]])
        published = np.array([[41.52787529, 96.83626054, 17.75210149], [55.11636304, -37.59308176, 44.13768458],
                              [29.80565520, -10.96316802, -65.06751860]])
        white = rimu.xyz_from_xy(D65_XY)
        luv = rimu.luv(xyz, white)
        np.testing.assert_allclose(luv, published, atol=5e-9 + 1e-12)
        np.testing.assert_array_equal(rimu.xyz_to_luv(xyz, white), luv)
        np.testing.assert_allclose(rimu.luv_to_xyz(luv, white), xyz, atol=1e-14)
        # CIELAB of the first, same source (colour/models/tests/test_cie_lab.py).
        lab = rimu.lab(xyz[0], white)
        np.testing.assert_allclose(lab, [41.52787529, 52.63858304, 26.92317922], atol=5e-9 + 1e-12)
        np.testing.assert_allclose(rimu.lab_to_xyz(lab, white), xyz[0], atol=1e-14)


class Differences(unittest.TestCase):
    def test_cie94_matches_colour_science_both_sets_in_one_call(self):
        graphic_arts = rimu.delta_e_1994(REFERENCE, SAMPLES)
        self.assertEqual(graphic_arts.shape, (3,))
        np.testing.assert_allclose(graphic_arts, [83.7792255009, 10.0539319546, 57.5354537067], atol=5e-9)
        # 88.33555305 is printed truncated (the doctest shows 88.3355530...): one unit of its last digit.
        np.testing.assert_allclose(rimu.delta_e_1994(REFERENCE, SAMPLES, textiles=True),
                                   [88.33555305, 10.61265789, 60.3686872611], atol=1e-8)
        self.assertIsInstance(rimu.delta_e_1994(REFERENCE, SAMPLES[0]), float)

    def test_cmc_matches_colour_science(self):
        np.testing.assert_allclose(rimu.delta_e_cmc(REFERENCE, SAMPLES), [172.70477129, 20.59732717, 121.71841479],
                                   atol=5e-9)
        self.assertAlmostEqual(rimu.delta_e_cmc([48.99183622, -0.10561667, 400.65619925],
                                                [50.65907324, -0.11671910, 402.82235718], l=2, c=1),
                               0.899699975683419, delta=5e-9)
        with self.assertRaisesRegex(ValueError, "^l: "):
            rimu.delta_e_cmc(REFERENCE, SAMPLES, l=0)

    def test_weighted_differences_are_asymmetric(self):
        self.assertGreater(abs(rimu.delta_e_1994(SAMPLES[0], REFERENCE) - rimu.delta_e_1994(REFERENCE, SAMPLES[0])), 1)


class Appearance(unittest.TestCase):
    WHITE = np.array([95.05, 100.0, 108.88])

    def test_cam16_matches_colour_science_and_inverts(self):
        # colour-science 0.4 (colour/appearance/tests/test_cam16.py, implementing Li et al. 2017), 8 decimals.
        cases = [([19.01, 20.00, 21.78], 318.31, dict(J=41.73120791, C=0.10335574, h=217.06795977, s=2.34501507,
                                                      Q=195.37170899, M=0.10743677, H=275.59498615)),
                 ([57.06, 43.06, 31.96], 31.83, dict(J=65.42828069, C=49.67956420, h=17.48659243, s=52.94308868,
                                                     Q=152.06985268, M=42.62473321))]   # H: see colour_appearance_test.cpp
        for xyz, l_a, published in cases:
            with self.subTest(l_a=l_a):
                got = rimu.cam16(xyz, self.WHITE, adapting_luminance=l_a, background_y=20.0)
                for key, value in published.items():
                    self.assertAlmostEqual(got[key], value, delta=5e-9 + 1e-11, msg=key)
                back = rimu.cam16_to_xyz([got["J"], got["M"], got["h"]], self.WHITE, adapting_luminance=l_a)
                np.testing.assert_allclose(back, xyz, atol=1e-9)
                jab = rimu.cam16_ucs(xyz, self.WHITE, adapting_luminance=l_a)
                m_prime = np.log1p(0.0228 * published["M"]) / 0.0228        # Li et al. 2017 eq. for CAM16-UCS
                np.testing.assert_allclose(jab, [1.7 * published["J"] / (1 + 0.007 * published["J"]),
                                                 m_prime * np.cos(np.radians(published["h"])),
                                                 m_prime * np.sin(np.radians(published["h"]))], atol=1e-8)
                np.testing.assert_allclose(rimu.cam16_ucs_to_xyz(jab, self.WHITE, adapting_luminance=l_a), xyz,
                                           atol=1e-9)

    def test_ciecam02_matches_colour_science(self):
        # colour-science 0.4 (examples/appearance/examples_ciecam02.py and its tests), 8 decimals.
        got = rimu.ciecam02([19.01, 20.00, 21.78], self.WHITE, adapting_luminance=318.31, background_y=20.0)
        for key, value in dict(J=41.73109113, C=0.10470776, h=219.04843266, M=0.10884218).items():
            self.assertAlmostEqual(got[key], value, delta=5e-9 + 1e-11, msg=key)

    def test_cam02_ucs_is_tm30s_and_broadcasts(self):
        rng = np.random.default_rng(3)
        image = rng.uniform(1.0, 90.0, size=(16, 16, 3))
        jab = rimu.cam02_ucs(image, self.WHITE, adapting_luminance=100.0, discount_illuminant=True)
        self.assertEqual(jab.shape, (16, 16, 3))
        np.testing.assert_array_equal(jab[4, 7], rimu.cam02_ucs(image[4, 7], self.WHITE, adapting_luminance=100.0,
                                                                discount_illuminant=True))
        np.testing.assert_allclose(rimu.cam02_ucs_to_xyz(jab, self.WHITE, adapting_luminance=100.0,
                                                         discount_illuminant=True), image, rtol=1e-10)
        d = rimu.cam16(image, self.WHITE, surround="dim")
        self.assertEqual(d["J"].shape, (16, 16))

    def test_bad_viewing_conditions_are_refused(self):
        with self.assertRaisesRegex(ValueError, "^surround: "):
            rimu.cam16([20, 20, 20], self.WHITE, surround="bright")
        with self.assertRaisesRegex(ValueError, "^adapting_luminance: "):
            rimu.cam16([20, 20, 20], self.WHITE, adapting_luminance=0)
        with self.assertRaisesRegex(ValueError, "^white: "):
            rimu.cam16([20, 20, 20], [0, 100, 100])


class Adaptation(unittest.TestCase):
    def test_every_cat_maps_the_white_and_cat16_is_accepted(self):
        d65, d50 = np.array([95.047, 100.0, 108.883]), np.array([96.422, 100.0, 82.521])
        for cat in ("bradford", "cat02", "cat16", "von-kries", "xyz-scaling"):
            with self.subTest(cat):
                np.testing.assert_allclose(rimu.adapt(d65, d65, d50, cat), d50, rtol=1e-12)
        self.assertEqual(rimu.rgb_conversion_matrix("srgb-linear", "acescg", "cat16").shape, (3, 3))
        # CAT16's M_16 (Li et al. 2017) differs from CAT02's: so do the corresponding colours.
        red = np.array([41.24, 21.26, 1.93])
        self.assertGreater(np.max(np.abs(rimu.adapt(red, d65, d50, "cat16") - rimu.adapt(red, d65, d50, "cat02"))), 1e-3)


class ColourTemperature(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()

    def test_daylight_xy_of_d65(self):
        # CIE 15:2004 eq. 3.3 at D65's CCT (6500 K × 1.4388/1.4380) gives the x of Table T.3, 0.31272 (5 decimals);
        # y follows eq. 3.4 (a fit to daylight, 1e-4 from T.3's y: see tests/spectral/spectrum_test.cpp).
        x, y = rimu.daylight_xy(6500.0 * 1.4388 / 1.4380)
        self.assertLessEqual(abs(x - 0.31272), 5e-6)
        self.assertAlmostEqual(y, -3 * x * x + 2.87 * x - 0.275, delta=1e-15)
        self.assertEqual(rimu.daylight_xy(np.array([[5000.0, 6504.0]])).shape, (1, 2, 2))
        with self.assertRaisesRegex(ValueError, r"^cct_k\[1\]: "):
            rimu.daylight_xy([5000.0, 3000.0])

    def test_planckian_xy_is_the_blackbodys_and_inverts(self):
        for t in (1500.0, 2856.0, 6500.0, 20000.0):
            with self.subTest(t=t):
                # The locus and the blackbody Spectrum summed the same way (1 nm, 360-830 nm): to rounding.
                by_spectrum = rimu.xy(rimu.blackbody(t).to_xyz())
                np.testing.assert_allclose(self.lib.planckian_xy(t), by_spectrum, atol=1e-9)
        xy = self.lib.planckian_xy(np.array([2700.0, 4000.0, 6500.0]), duv=0.01)
        cct, duv, valid = self.lib.xy_to_cct(xy)
        np.testing.assert_allclose(cct, [2700.0, 4000.0, 6500.0], atol=0.02)   # cct_test.cpp's bounds
        np.testing.assert_allclose(duv, 0.01, atol=1e-8)
        self.assertTrue(np.all(valid))
        self.assertFalse(self.lib.xy_to_cct([0.3, 0.5])[2])

    def test_robertson_1968_beside_ohno_2013(self):
        # Robertson's table lies on today's locus, so the two agree within the 0.1 MK^-1 that
        # tests/spectral/robertson_cct_test.cpp bounds Robertson's interpolation by (Ohno's error is 0.011 K).
        xy = self.lib.planckian_xy(np.array([[2000.0, 2856.0], [6500.0, 15000.0]]), duv=0.005)
        ohno, duv_ohno, _ = self.lib.xy_to_cct(xy)
        rob, duv_rob, valid = self.lib.xy_to_cct(xy, method="robertson1968")
        self.assertEqual(rob.shape, (2, 2))
        self.assertTrue(np.all(valid))
        np.testing.assert_allclose(1e6 / rob, 1e6 / ohno, atol=0.1)
        np.testing.assert_allclose(duv_rob, duv_ohno, atol=1.1e-4)
        # The same method through a spectrum: illuminant A, 2848 K at c2 = 1.435e-2, is 2855.5 K on today's c2;
        # 0.1 MK^-1 is 0.8 K there.
        cct, _, validity = rimu.illuminant("A").cct(method="robertson1968")
        self.assertEqual(validity, "ok")
        self.assertAlmostEqual(cct, 2848.0 * 1.438777 / 1.435, delta=0.8)
        # Robertson's range ends at 1667 K, and says so in its own words.
        self.assertEqual(rimu.blackbody(1200.0).cct(method="robertson1968")[2], "below 1667 K")
        with self.assertRaisesRegex(ValueError, r"^method: unknown CCT method 'robertson'"):
            self.lib.xy_to_cct([0.31, 0.33], method="robertson")
        with self.assertRaisesRegex(ValueError, r"^observer: robertson1968 is tabulated for the CIE 1931 2"):
            self.lib.xy_to_cct([0.31, 0.33], observer=10, method="robertson1968")


class NewFunctionsRefuseOrAnswerFinite(unittest.TestCase):
    """The sweep of test_validation.py, for the functions added with #28."""

    def test_sweep(self):
        white = np.array([95.047, 100.0, 108.883])
        lab = np.array([50.0, 10.0, -10.0])

        def triples(name, f, arg, zero_refused=False, negative_refused=False):
            """(case, call, the argument a refusal must name, whether it must refuse)."""
            return [
                (name + ": NaN", lambda: f(np.array([np.nan, 1.0, 1.0])), arg, True),
                (name + ": Inf", lambda: f(np.array([1.0, np.inf, 1.0])), arg, True),
                (name + ": 1e308", lambda: f(np.array([1e308, 1.0, 1.0])), arg, True),
                (name + ": empty", lambda: f(np.array([])), arg, True),
                (name + ": 4 values", lambda: f(np.ones(4)), arg, True),
                (name + ": negative", lambda: f(np.array([-0.5, 0.2, 0.1])), arg, negative_refused),
                (name + ": zero", lambda: f(np.zeros(3)), arg, zero_refused),
            ]

        rows = []
        rows += triples("uv_1960", rimu.uv_1960, "xyz", True, True)
        rows += triples("uv_1976", rimu.uv_1976, "xyz", True, True)
        rows += triples("luv", lambda v: rimu.luv(v, white), "xyz")
        rows += triples("luv white", lambda v: rimu.luv(white, v), "white", True, True)
        rows += triples("luv_to_xyz", lambda v: rimu.luv_to_xyz(v, white), "luv")
        rows += triples("lab_to_xyz", lambda v: rimu.lab_to_xyz(v, white), "lab")
        rows += triples("delta_e_1994", lambda v: rimu.delta_e_1994(v, lab), "reference")
        rows += triples("delta_e_cmc", lambda v: rimu.delta_e_cmc(lab, v), "sample")
        rows += triples("adapt", lambda v: rimu.adapt(v, white, white), "xyz")
        rows += triples("adapt white", lambda v: rimu.adapt(white, v, white), "source_white", True, True)
        for name in ("ciecam02", "cam16", "cam02_ucs", "cam16_ucs"):
            f = getattr(rimu, name)
            inverse = getattr(rimu, name + "_to_xyz")
            rows += triples(name, lambda v, f=f: f(v, white), "xyz")
            rows += triples(name + " white", lambda v, f=f: f(white, v), "white", True, True)
            rows += triples(name + "_to_xyz", lambda v, g=inverse: g(v, white), "jab" if "ucs" in name else "jmh")
        self.assertGreater(len(rows), 150)
        for name, call, argument, must_refuse in rows:
            with self.subTest(name):
                try:
                    result = call()
                except ValueError as e:   # a refusal names the argument; NaN or Inf is never an answer
                    self.assertTrue(str(e).startswith(argument), f"{name}: {e!s} does not name {argument}")
                    continue
                self.assertFalse(must_refuse, f"{name}: answered instead of refusing")
                self.assertTrue(finite(result), name)


if __name__ == "__main__":
    unittest.main()
