"""Tests of the rimu Python module against published values (each names its table and tolerance)."""
import math
import unittest

import numpy as np

import rimu


class Colorimetry(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()

    def test_f2_xy_matches_cie15_table_t8(self):
        # CIE 15:2004 Table T.8: F2 (0.3721, 0.3751), 4 decimals; summed at the table's own 5 nm.
        wl, power = self.lib.illuminant("F2")
        self.assertEqual(self.lib.tristimulus_method(wl, power), "native")
        x, y = rimu.xy(self.lib.light_xyz(wl, power))
        self.assertLessEqual(abs(x - 0.3721), 5e-5)
        self.assertLessEqual(abs(y - 0.3751), 5e-5)

    def test_cct_of_illuminant_a(self):
        # CIE 15:2004: illuminant A has a CCT of about 2856 K (2848 K with the old c2); within 1 K.
        cct, duv, validity = self.lib.cct_duv(*self.lib.illuminant("A"))
        self.assertEqual(validity, "ok")
        self.assertLess(abs(cct - 2856), 1.0)
        self.assertLess(abs(duv), 1e-4)

    def test_ciede2000_sharma_pair_1(self):
        # Sharma, Wu & Dalal (2005) Table 1, pair 1: 2.0425 (4 decimals).
        d = rimu.delta_e_2000(np.array([50.0, 2.6772, -79.7751]), np.array([50.0, 0.0, -82.7485]))
        self.assertAlmostEqual(d, 2.0425, delta=5e-5)

    def test_colorchecker_dark_skin_under_d50(self):
        # BabelColor average, D50 2°: xyY (0.4325, 0.3788, 0.1034) with the ICC D50 white; 0.2 dE00 (the patch's
        # 3-decimal reflectances allow that much, see tests/spectral/reflectance_report_test.cpp).
        wl, r = self.lib.colorchecker("dark skin")
        xyz = self.lib.reflectance_xyz(wl, r, "D50")
        white = self.lib.white_xyz(wl, "D50")
        x, y, big_y = 0.4325, 0.3788, 10.34
        published = rimu.lab(np.array([x / y * big_y, big_y, (1 - x - y) / y * big_y]), np.array([96.42, 100, 82.49]))
        self.assertLess(rimu.delta_e_2000(rimu.lab(xyz, white), published), 0.2)

    def test_e308_table5_keeps_the_white_and_moves_a_colour(self):
        # ASTM E308 Table 5 (bandpass_corrected=False) is Table 6 with the Stearns correction folded in: each column
        # of the correction sums to 1, so the perfect diffuser keeps its white (9-decimal files: 1e-6), while a
        # coloured patch moves (by more than the 1e-3 the tables' rounding could explain).
        wl, r = self.lib.colorchecker("red")
        white5 = self.lib.white_xyz(wl, "D65", bandpass_corrected=False)
        white6 = self.lib.white_xyz(wl, "D65")
        self.assertLess(np.max(np.abs(white5 - white6)), 1e-6)
        moved = self.lib.reflectance_xyz(wl, r, "D65", bandpass_corrected=False) - self.lib.reflectance_xyz(wl, r, "D65")
        self.assertGreater(np.max(np.abs(moved)), 1e-3)

    def test_unknown_illuminant_is_a_value_error(self):
        with self.assertRaisesRegex(ValueError, "unknown illuminant 'D66'"):
            self.lib.illuminant("D66")


class Quality(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()

    def test_ra_of_f4(self):
        # CIE 15:2004 Table T.8: F4 Ra = 51 (integer): within 0.5.
        self.assertLessEqual(abs(self.lib.cri(*self.lib.illuminant("F4"))["ra"] - 51), 0.5)

    def test_rf_rg_of_f2(self):
        # CIE 2017 calculator: F2 Rf 70.1 (0.1); TM-30-18 calculator: Rg 86 (integer, 0.75).
        f = self.lib.fidelity(*self.lib.illuminant("F2"))
        self.assertLessEqual(abs(f["rf"] - 70.1), 0.1)
        self.assertLessEqual(abs(f["rg"] - 86), 0.75)
        self.assertEqual(len(f["bin_rf"]), 16)
        self.assertEqual(len(f["sample_rf"]), 99)


class SpacesAndUpsampling(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()

    def test_srgb_white_is_d65(self):
        # sRGB (IEC 61966-2-1) white: D65 xy (0.3127, 0.3290).
        x, y = rimu.xy(rimu.rgb_to_xyz(np.array([1.0, 1.0, 1.0]), "srgb-linear"))
        self.assertAlmostEqual(x, 0.3127, delta=5e-5)
        self.assertAlmostEqual(y, 0.3290, delta=5e-5)

    def test_srgb_to_itself_is_identity(self):
        np.testing.assert_allclose(rimu.rgb_conversion_matrix("srgb-linear", "srgb-linear"), np.eye(3), atol=1e-12)

    def test_upsampled_grey_reflectance_round_trips(self):
        # A mid grey upsamples to a spectrum in [0, 1] whose colour under D65 is the grey again (to 1 %).
        wl, r, mapped = self.lib.upsample_reflectance(np.array([0.5, 0.5, 0.5]))
        self.assertFalse(mapped)
        self.assertTrue(np.all((r >= 0) & (r <= 1)))
        rgb = rimu.xyz_to_rgb(self.lib.reflectance_xyz(wl, r, "D65") / 100.0, "srgb-linear")
        np.testing.assert_allclose(rgb, [0.5, 0.5, 0.5], atol=5e-3)


class LightUnits(unittest.TestCase):
    def test_ev100_zero_is_an_eighth_of_a_nit(self):
        # ISO 2720 reflected meter, K = 12.5: EV 0 at ISO 100 <-> 0.125 cd/m²; incident, C = 250: 2.5 lx.
        self.assertAlmostEqual(rimu.luminance_from_ev100(0.0), 0.125)
        self.assertAlmostEqual(rimu.illuminance_from_ev100(0.0), 2.5)
        self.assertAlmostEqual(rimu.ev100_from_luminance(rimu.luminance_from_ev100(7.3)), 7.3)

    def test_light_scale_is_linear_in_the_amount(self):
        lib = rimu.Library()
        wl, s = lib.illuminant("D65")
        self.assertAlmostEqual(lib.light_scale(wl, s, "800 lm") / lib.light_scale(wl, s, "400 lm"), 2.0)
        # lm / W of the shape is the ratio of the two scales.
        self.assertAlmostEqual(lib.light_scale(wl, s, "1 W") / lib.light_scale(wl, s, "1 lm"),
                               lib.luminous_efficacy(wl, s), places=9)


class Render(unittest.TestCase):
    def test_cornell_box_renders_deterministically(self):
        lib = rimu.Library()
        first = lib.render(width=8, height=8, samples_per_pixel=2, seed=3, threads=2)
        second = lib.render(width=8, height=8, samples_per_pixel=2, seed=3, threads=1)
        self.assertEqual(first.shape, (8, 8, 3))
        self.assertTrue(np.all(np.isfinite(first)))
        self.assertGreater(first[..., 1].mean(), 0.0)
        np.testing.assert_array_equal(first, second)

    def test_the_sample_clamp_bounds_every_pixel(self):
        # The box's Gaussian filter averages samples with positive weights: a pixel of clamped samples is clamped.
        lib = rimu.Library()
        plain = lib.render(width=16, height=16, samples_per_pixel=2, seed=3, threads=2)
        clamped = lib.render(width=16, height=16, samples_per_pixel=2, seed=3, threads=2, max_sample_value=0.05)
        self.assertGreater(plain.max(), 0.05)
        self.assertLessEqual(clamped.max(), 0.05 * (1 + 1e-5))
        self.assertLess(clamped[..., 1].mean(), plain[..., 1].mean())
        with self.assertRaisesRegex(ValueError, r"^max_sample_value: expected a number"):
            lib.render(width=8, samples_per_pixel=1, max_sample_value=-1.0)


if __name__ == "__main__":
    unittest.main()
