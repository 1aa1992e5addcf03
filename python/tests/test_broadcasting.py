"""The colour functions broadcast over (..., 3) arrays and stacks of spectra: the same numbers for one colour, a
(24, 3) stack and a (64, 64, 3) image; float32, integer and strided arrays converted, other dtypes refused."""
import os
import unittest

import numpy as np

import rimu

DATA = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "data")
D65 = np.array([95.047, 100.0, 108.883])


class Broadcasting(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lib = rimu.Library()
        rng = np.random.default_rng(7)
        cls.xyz = rng.uniform(0.5, 100.0, size=(64, 64, 3))   # every pixel has a chromaticity
        cls.lab2 = rng.uniform([0, -80, -80], [100, 80, 80], size=(64, 64, 3))

    def each(self, f, *arrays):
        """f applied one colour at a time (the scalar path), stacked back into the arrays' leading shape."""
        lead = arrays[0].shape[:-1]
        flat = [a.reshape(-1, 3) for a in arrays]
        return np.array([f(*(a[i] for a in flat)) for i in range(flat[0].shape[0])]).reshape(lead + np.shape(f(*(a[0] for a in flat))))

    def test_same_numbers_for_one_colour_a_stack_and_an_image(self):
        image = self.xyz
        stack = image[0, :24]
        for name, f in (("xy", rimu.xy), ("lab", lambda v: rimu.lab(v, D65)), ("xyz_to_rgb", rimu.xyz_to_rgb),
                        ("rgb_to_xyz", lambda v: rimu.rgb_to_xyz(v / 100, "acescg"))):
            with self.subTest(name):
                whole = f(image)
                self.assertEqual(whole.shape[:2], (64, 64))
                np.testing.assert_array_equal(whole, self.each(f, image))        # bit for bit, the same C++ per colour
                np.testing.assert_array_equal(f(stack), whole[0, :24])
                np.testing.assert_array_equal(f(image[3, 5]), whole[3, 5])
        lab1 = rimu.lab(image, D65)
        d = rimu.delta_e_2000(lab1, self.lab2)
        self.assertEqual(d.shape, (64, 64))
        np.testing.assert_array_equal(d, self.each(rimu.delta_e_2000, lab1, self.lab2))
        self.assertIsInstance(rimu.delta_e_2000(lab1[0, 0], self.lab2[0, 0]), float)
        self.assertEqual(rimu.delta_e_2000(lab1[0, 0], self.lab2[0, 0]), d[0, 0])
        # One colour pairs with every colour of the other argument (numpy's rule).
        np.testing.assert_array_equal(rimu.delta_e_2000(lab1, self.lab2[0, 0]),
                                      rimu.delta_e_2000(lab1, np.broadcast_to(self.lab2[0, 0], lab1.shape)))

    def test_large_arrays_run_in_parallel_chunks_with_the_same_numbers(self):
        # 256 x 256 colours are split into parallel chunks (kParallelCount = 16384); each row alone runs in one piece.
        rng = np.random.default_rng(11)
        xyz = rng.uniform(0.5, 100.0, size=(256, 256, 3))
        lab = rimu.lab(xyz, D65)
        d = rimu.delta_e_2000(lab, lab[::-1])
        for row in (0, 77, 255):
            np.testing.assert_array_equal(lab[row], rimu.lab(xyz[row], D65))
            np.testing.assert_array_equal(d[row], rimu.delta_e_2000(lab[row], lab[255 - row]))

    def test_sharma_ciede2000_set_as_one_call(self):
        # Sharma, Wu & Dalal (2005) Table 1: 34 pairs, dE00 to 4 decimals (tests/data/README.md names the source).
        data = np.loadtxt(os.path.join(DATA, "sharma2005_ciede2000.csv"), delimiter=",", skiprows=1)
        self.assertEqual(data.shape, (34, 7))
        d = rimu.delta_e_2000(data[:, 0:3], data[:, 3:6])
        self.assertEqual(d.shape, (34,))
        np.testing.assert_allclose(d, data[:, 6], rtol=0, atol=5e-5)

    def test_stacks_of_reflectances(self):
        wl, _ = self.lib.colorchecker("dark skin")
        names = ["dark skin", "light skin", "blue sky", "foliage", "orange", "cyan"]
        stack = np.array([self.lib.colorchecker(n)[1] for n in names])       # (6, 36)
        xyz = self.lib.reflectance_xyz(wl, stack, "D50")
        self.assertEqual(xyz.shape, (6, 3))
        for i, n in enumerate(names):
            np.testing.assert_array_equal(xyz[i], self.lib.reflectance_xyz(wl, stack[i], "D50"))
        grid = stack.reshape(2, 3, -1)
        np.testing.assert_array_equal(self.lib.reflectance_xyz(wl, grid, "D50"), xyz.reshape(2, 3, 3))
        bad = stack.copy()
        bad[4, 7] = 45.0
        with self.assertRaisesRegex(ValueError, r"^values\[4, 7\]: reflectance factor 45 is above 1\.5"):
            self.lib.reflectance_xyz(wl, bad)
        with self.assertRaisesRegex(ValueError, r"^values: expected .*36"):
            self.lib.reflectance_xyz(wl, stack[:, :-1])

    def test_errors_name_the_element(self):
        image = self.xyz.copy()
        image[12, 40] = 0.0
        with self.assertRaisesRegex(ValueError, r"^xyz\[12, 40\]: X \+ Y \+ Z of \(0, 0, 0\) is not positive"):
            rimu.xy(image)
        image[12, 40] = [1.0, np.nan, 1.0]
        with self.assertRaisesRegex(ValueError, r"^xyz\[12, 40\]: expected three finite components"):
            rimu.lab(image, D65)
        with self.assertRaisesRegex(ValueError, r"^white\[1\]: a reference white needs"):
            rimu.lab(self.xyz[:2, 0], np.array([D65, [0.0, 0.0, 0.0]]))
        with self.assertRaisesRegex(ValueError, r"^lab2: shape \(5,\) does not broadcast with lab1's \(4,\)"):
            rimu.delta_e_2000(np.zeros((4, 3)), np.zeros((5, 3)))
        with self.assertRaisesRegex(ValueError, r"^xyz: expected 3 values, or an array of shape \(\.\.\., 3\); got shape \(4, 4\)"):
            rimu.xy(np.ones((4, 4)))

    def test_dtypes_and_strides(self):
        xyz = self.xyz[:8, :8]
        expected = rimu.lab(xyz, D65)
        # float32 is converted (the float32 values, exactly), integers too; strided and transposed views are read
        # through their strides.
        np.testing.assert_array_equal(rimu.lab(xyz.astype(np.float32), D65),
                                      rimu.lab(xyz.astype(np.float32).astype(np.float64), D65))
        ints = np.rint(xyz).astype(np.int32)
        np.testing.assert_array_equal(rimu.lab(ints, np.array([95, 100, 109])),
                                      rimu.lab(ints.astype(float), np.array([95.0, 100.0, 109.0])))
        np.testing.assert_array_equal(rimu.lab(self.xyz[::8, ::8], D65),
                                      rimu.lab(np.ascontiguousarray(self.xyz[::8, ::8]), D65))
        planar = np.ascontiguousarray(np.moveaxis(xyz, -1, 0))               # (3, 8, 8): the view below is strided
        np.testing.assert_array_equal(rimu.lab(np.moveaxis(planar, 0, -1), D65), expected)
        np.testing.assert_array_equal(rimu.xy([20.0, 21.0, 22.0]), rimu.xy(np.array([20.0, 21.0, 22.0])))
        for bad, dtype in ((xyz.astype(np.complex128), "complex128"), (xyz > 50, "bool"),
                           (np.array(["1", "2", "3"]), "<U1")):
            with self.subTest(dtype):
                with self.assertRaisesRegex(ValueError, r"^xyz: expected real numbers .*dtype " + dtype):
                    rimu.lab(bad, D65)


if __name__ == "__main__":
    unittest.main()
