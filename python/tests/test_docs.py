"""docs/python.md's session runs as written (from the repository root)."""
import os
import re
import unittest

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


class DocsSession(unittest.TestCase):
    def test_python_md_session_runs(self):
        with open(os.path.join(ROOT, "docs", "python.md"), encoding="utf-8") as f:
            blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
        self.assertEqual(len(blocks), 2)      # the session, then the tutorial: run in order, in one scope
        cwd = os.getcwd()
        os.chdir(ROOT)
        try:
            scope = {}
            for block in blocks:
                exec(compile(block, "docs/python.md", "exec"), scope)
        finally:
            os.chdir(cwd)
        self.assertEqual(scope["image"].shape, (32, 32, 3))
        self.assertAlmostEqual(scope["rimu"].xy(scope["xyz"])[0], 0.3805, delta=5e-5)
        # The ColorChecker comparison is against BabelColor, the reference docs/colour-measurement.md's 0.2 is about.
        self.assertLessEqual(scope["rimu"].delta_e_2000(scope["lab"], scope["babelcolor"]), 0.2)
        # The tutorial: the chart as stacks, the differences per patch, the round trip and the greys' CCT.
        self.assertEqual(scope["chart_lab"].shape, (24, 3))
        self.assertEqual(scope["de94"].shape, (24,))
        self.assertEqual(scope["appearance"]["J"].shape, (24,))
        self.assertLess(abs(scope["back"] - scope["chart_xyz"]).max(), 1e-8)
        self.assertTrue(all(abs(t - 6504) < 300 for t in scope["cct"]))


if __name__ == "__main__":
    unittest.main()
