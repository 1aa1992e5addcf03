"""Builds the rimu module with the project's CMake build and packages it for pip (docs/python.md, "Installing").

The extension is not compiled by setuptools: build_ext runs CMake on the repository (the build folder in
RIMU_BUILD_DIR, default <repo>/build, configured if it is not yet, with the Python module on) and copies what it
built, the module, its type stubs (rimu.pyi) and the data tables (as rimu_data/ beside the module, where the module
looks for them first), into the wheel.
"""
import os
import pathlib
import re
import shutil
import subprocess

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

REPOSITORY = pathlib.Path(__file__).resolve().parent.parent
BUILD = pathlib.Path(os.environ.get("RIMU_BUILD_DIR", REPOSITORY / "build")).resolve()
# setuptools' own files (build/, rimu.egg-info/) go into the CMake build folder, not into the source tree.
SETUPTOOLS_FILES = BUILD / "python-setuptools"
SETUPTOOLS_FILES.mkdir(parents=True, exist_ok=True)


def project_version():
    """The version CMake's project() declares, so the package and rimu.__version__ agree."""
    text = (REPOSITORY / "CMakeLists.txt").read_text()
    return re.search(r"project\(Rimu VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = BUILD
        cache = build / "CMakeCache.txt"
        if not cache.exists():
            subprocess.run(["cmake", "-S", str(REPOSITORY), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                            "-DRIMU_BUILD_TESTS=OFF", "-DRIMU_BUILD_BENCHMARKS=OFF", "-DRIMU_PYTHON=ON"],
                           check=True, stdout=subprocess.DEVNULL)
        elif "RIMU_PYTHON:BOOL=ON" not in cache.read_text():
            # A build folder configured without the module (scripts/main.sh's): turn it on, keep the rest.
            subprocess.run(["cmake", "-S", str(REPOSITORY), "-B", str(build), "-DRIMU_PYTHON=ON"], check=True,
                           stdout=subprocess.DEVNULL)
        subprocess.run(["cmake", "--build", str(build), "--target", "rimu_python", "-j", str(os.cpu_count() or 1)],
                       check=True)
        built = sorted((build / "python").glob("rimu*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one rimu*.so in {build / 'python'}, found {[p.name for p in built]}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)
        shutil.copy2(REPOSITORY / "python" / "rimu.pyi", target.parent / "rimu.pyi")
        data = target.parent / "rimu_data"
        shutil.rmtree(data, ignore_errors=True)
        shutil.copytree(REPOSITORY / "data", data)


setup(
    name="rimu",
    version=project_version(),
    description="Rimu's colour science and spectral renderer from Python (numpy arrays in and out)",
    python_requires=">=3.9",
    ext_modules=[Extension("rimu", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
    options={"build": {"build_base": str(SETUPTOOLS_FILES / "build")}, "egg_info": {"egg_base": str(SETUPTOOLS_FILES)}},
)
