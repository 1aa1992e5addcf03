"""rimu.Spectrum and the data library by name: construction and checks, interpolation and alignment, arithmetic,
CSV reading, colorimetry through the same functions as the arrays, and the blackbody and daylight generators."""
import os
import tempfile
import unittest

import numpy as np

import rimu

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


class SpectrumType(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()

    def test_arrays_round_trip_and_interpolate_linearly(self):
        s = rimu.Spectrum([400.0, 500.0, 600.0], [0.2, 0.6, 0.4], kind="reflectance", name="test")
        self.assertEqual((s.kind, s.name, len(s)), ("reflectance", "test", 3))
        np.testing.assert_array_equal(s.wavelengths_nm, [400, 500, 600])
        self.assertAlmostEqual(s(450.0), 0.4, delta=1e-15)
        np.testing.assert_allclose(s(np.array([[380.0, 650.0]])), [[0.2, 0.4]])      # reflectance: held at its ends
        light = rimu.Spectrum([400.0, 500.0, 600.0], [1.0, 2.0, 1.0])
        self.assertEqual(light(700.0), 0.0)                                           # light: zero outside
        fine = s.interpolate(10.0)
        self.assertEqual(len(fine), 21)
        np.testing.assert_allclose(fine.values, s(np.arange(400.0, 601.0, 10.0)), rtol=1e-15)
        aligned = s.align(np.array([410.0, 420.0]))
        np.testing.assert_allclose(aligned.values, [0.24, 0.28], rtol=1e-14)

    def test_the_tools_checks_apply(self):
        with self.assertRaisesRegex(ValueError, r"^values\[1\]: "):
            rimu.Spectrum([400.0, 500.0], [1.0, -1.0])
        with self.assertRaisesRegex(ValueError, "^values"):
            rimu.Spectrum([400.0, 500.0], [20.0, 50.0], kind="reflectance")              # percent
        with self.assertRaisesRegex(ValueError, "^kind: "):
            rimu.Spectrum([400.0, 500.0], [1.0, 1.0], kind="power")
        with self.assertRaisesRegex(ValueError, "^interval_nm: "):
            rimu.illuminant("A").interpolate(0.0)

    def test_arithmetic_on_the_union_of_samplings(self):
        light = rimu.illuminant("D65")
        patch = rimu.colorchecker("dark skin")
        reflected = light * patch
        self.assertEqual(reflected.kind, "light")
        for wl in (380.0, 555.0, 712.0, 715.0):   # at the knots of the union (linear between them)
            self.assertAlmostEqual(reflected(wl), light(wl) * patch(wl), delta=1e-12 * light(wl))
        doubled = 2 * light
        np.testing.assert_allclose(doubled.values, 2 * light.values)
        np.testing.assert_allclose((light / 4).values, light.values / 4)
        self.assertEqual((light + light).kind, "light")
        with self.assertRaisesRegex(ValueError, "^other"):
            light * -1.0

    def test_colorimetry_is_the_librarys(self):
        patch = rimu.colorchecker("dark skin")
        np.testing.assert_array_equal(patch.to_xyz("D50"), self.lib.reflectance_xyz(*self.lib.colorchecker("dark skin"), "D50"))
        f11 = rimu.illuminant("F11")
        np.testing.assert_allclose(rimu.xy(f11.to_xyz()), [0.3805, 0.3769], atol=5e-5)   # CIE 15:2004 Table T.8
        self.assertEqual(f11.cri()["special"].shape, (14,))
        self.assertEqual(f11.fidelity()["bin_rf"].shape, (16,))
        cct, duv, validity = rimu.blackbody(2856.0).cct()
        self.assertLess(abs(cct - 2856.0), 0.02)
        self.assertLess(abs(duv), 1e-6)
        with self.assertRaisesRegex(ValueError, "^self: "):
            rimu.observer()[1].to_xyz()

    def test_csv_reading_names_the_line(self):
        a = rimu.Spectrum.from_csv(os.path.join(ROOT, "data", "spectra", "illuminants", "cie_a_5nm.csv"))
        np.testing.assert_allclose(a.values, rimu.illuminant("A").align(a.wavelengths_nm).values, rtol=1e-12)
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "bad.csv")
            with open(path, "w") as f:
                f.write("wavelength_nm,value\n400,1\n500,-2\n600,1\n")
            with self.assertRaisesRegex(ValueError, r"bad\.csv:3"):
                rimu.Spectrum.from_csv(path)

    def test_library_by_name(self):
        x, y, z = rimu.observer("CIE 1964 10°")
        self.assertEqual(y.kind, "other")
        self.assertAlmostEqual(rimu.observer(2)[1](555.0), 1.0, delta=1e-6)   # V(λ) peaks at 1 at 555 nm
        r, g, b = rimu.camera("nikon_d850")
        self.assertGreater(g(530.0), r(530.0))
        self.assertIn("pbrt_physlight_nikon_d850_10nm", rimu.camera_names())
        with self.assertRaisesRegex(ValueError, "^name: unknown camera"):
            rimu.camera("nikon_d851")
        self.assertEqual(len(rimu.colorchecker_names()), 24)
        self.assertEqual(rimu.cie_led("B3").name, "LED-B3")
        # The table's full name works too, and names the same spectrum.
        full = rimu.cie_led("LED-B3")
        self.assertEqual(full.name, "LED-B3")
        np.testing.assert_array_equal(full.values, rimu.cie_led("B3").values)
        with self.assertRaisesRegex(ValueError, "^name: "):
            rimu.cie_led("LED-B9")
        with self.assertRaisesRegex(ValueError, "^name: "):
            rimu.illuminant("D66")

    def test_daylight_generator_gives_d65(self):
        # CIE 15:2004: D65 is daylight at 6504 K; Rimu keeps M1, M2 unrounded for a generated CCT, and the 1 nm D65
        # table is the 5 nm one interpolated, so the two agree in xy to the 4 decimals of Table T.3.
        np.testing.assert_allclose(rimu.xy(rimu.daylight(6504.0).to_xyz()), rimu.xy(rimu.illuminant("D65").to_xyz()),
                                   atol=5e-5)
        with self.assertRaisesRegex(ValueError, "^cct_k: "):
            rimu.daylight(3000.0)
        with self.assertRaisesRegex(ValueError, "^temperature_k: "):
            rimu.blackbody(-5.0)

    def test_blackbody_scales(self):
        peak = rimu.blackbody(5000.0)
        self.assertLessEqual(np.max(peak.values), 1.0)
        self.assertGreater(np.max(peak.values), 0.999)
        absolute = rimu.blackbody(5000.0, wavelengths_nm=np.array([500.0, 600.0]), absolute=True)
        # Planck's law at 500 nm, 5000 K: 2hc²/λ⁵/(exp(hc/λkT) − 1) = 1.2107e13 W/(m²·sr·m) = 1.2107e4 per nm.
        self.assertAlmostEqual(absolute(500.0) / 1.2107e4, 1.0, delta=1e-4)


if __name__ == "__main__":
    unittest.main()
