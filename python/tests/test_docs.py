"""docs/python.md's session runs as written (from the repository root)."""
import os
import re
import unittest

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")


class DocsSession(unittest.TestCase):
    def test_python_md_session_runs(self):
        with open(os.path.join(ROOT, "docs", "python.md"), encoding="utf-8") as f:
            blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
        self.assertEqual(len(blocks), 1)
        cwd = os.getcwd()
        os.chdir(ROOT)
        try:
            scope = {}
            exec(compile(blocks[0], "docs/python.md", "exec"), scope)
        finally:
            os.chdir(cwd)
        self.assertEqual(scope["image"].shape, (32, 32, 3))
        self.assertAlmostEqual(scope["rimu"].xy(scope["xyz"])[0], 0.3805, delta=5e-5)
        # The ColorChecker comparison is against BabelColor, the reference docs/colour-measurement.md's 0.2 is about.
        self.assertLessEqual(scope["rimu"].delta_e_2000(scope["lab"], scope["babelcolor"]), 0.2)


if __name__ == "__main__":
    unittest.main()
