"""The module as a Python package: a version, numpy arrays for every array-like result, a docstring with an example
on every function, and type stubs (python/rimu.pyi, installed beside the module) that list every public name with
the module's own parameter names."""
import ast
import inspect
import os
import re
import unittest

import numpy as np

import rimu

STUB = os.path.join(os.path.dirname(__file__), "..", "rimu.pyi")


def public_functions():
    """(qualified name, object) of every public function of the module and method of its classes."""
    for name, obj in vars(rimu).items():
        if name.startswith("_"):
            continue
        if inspect.isclass(obj):
            for member, value in vars(obj).items():
                if callable(value) or isinstance(value, (property, staticmethod)):
                    if not member.startswith("_") or member in ("__init__", "__call__"):
                        yield f"{name}.{member}", getattr(obj, member)
        elif callable(obj):
            yield name, obj


def signature_parameters(doc, name):
    """The parameter names of every overload in a pybind11 docstring ("name(a: T, b: U = ...) -> R")."""
    out = []
    for line in doc.splitlines():
        m = re.match(rf"^(?:\d+\. )?{re.escape(name)}\((.*)\) -> ", line)
        if m:
            params, depth, current = [], 0, ""
            for ch in m.group(1):
                depth += ch in "([{"
                depth -= ch in ")]}"
                if ch == "," and depth == 0:
                    params.append(current)
                    current = ""
                else:
                    current += ch
            params.append(current)
            out.append([p.split(":")[0].strip() for p in params if p.strip()])
    return out


def stub_definitions():
    """{qualified name: [parameter names of each definition]} from rimu.pyi."""
    with open(STUB, encoding="utf-8") as f:
        tree = ast.parse(f.read())
    defs = {}

    def add(prefix, node):
        if isinstance(node, ast.FunctionDef):
            defs.setdefault(prefix + node.name, []).append([a.arg for a in node.args.args + node.args.kwonlyargs])
        elif isinstance(node, ast.ClassDef):
            defs.setdefault(prefix + node.name, [])
            for child in node.body:
                add(prefix + node.name + ".", child)
        elif isinstance(node, (ast.AnnAssign,)) and isinstance(node.target, ast.Name):
            defs.setdefault(prefix + node.target.id, [])

    for node in tree.body:
        add("", node)
    return defs


class Package(unittest.TestCase):
    def test_version_and_commit(self):
        self.assertRegex(rimu.__version__, r"^\d+\.\d+\.\d+$")
        self.assertRegex(rimu.__git_commit__, r"^([0-9a-f]{7,40}|unknown)")

    def test_quality_results_are_numpy_arrays(self):
        lib = rimu.Library()
        wl, power = lib.illuminant("F2")
        f = lib.fidelity(wl, power)
        for key, shape in (("bin_rf", (16,)), ("bin_chroma_shift", (16,)), ("bin_hue_shift", (16,)),
                           ("sample_rf", (99,)), ("bin_reference_ab", (16, 2)), ("bin_test_ab", (16, 2))):
            self.assertIsInstance(f[key], np.ndarray, key)
            self.assertEqual(f[key].shape, shape, key)
        self.assertIsInstance(lib.cri(wl, power)["special"], np.ndarray)
        self.assertEqual(lib.cri(wl, power)["special"].shape, (14,))

    def test_every_function_has_a_docstring_beyond_its_signature(self):
        for name, f in public_functions():
            with self.subTest(name):
                doc = getattr(f, "__doc__", None) or ""
                text = "\n".join(line for line in doc.splitlines()
                                 if not re.match(r"^(\d+\. )?\w+\(.*\) -> ", line) and line.strip() != "Overloaded function.")
                self.assertGreater(len(text.strip()), 15, f"{name} has no docstring")

    def test_no_signature_is_typed_object(self):
        for name, f in public_functions():
            with self.subTest(name):
                self.assertNotRegex(getattr(f, "__doc__", "") or "", r"-> object\b")

    def test_the_stub_lists_every_public_name_with_the_modules_parameters(self):
        stub = stub_definitions()
        self.assertIn("__version__", stub)
        for name, f in public_functions():
            with self.subTest(name):
                self.assertIn(name, stub, f"{name} is missing from python/rimu.pyi")
                doc = getattr(f, "__doc__", None) or ""
                short = name.split(".")[-1]
                expected = signature_parameters(doc, short)
                for params in expected:
                    params = [p for p in params if p != "self"]
                    got = [[p for p in s if p != "self"] for s in stub[name]]
                    self.assertIn(params, got, f"{name}: the stub's parameters {got} differ from the module's {params}")


if __name__ == "__main__":
    unittest.main()
