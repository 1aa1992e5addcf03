#!/usr/bin/env bash
# pip_install.sh PYTHON SOURCE_DIR BUILD_DIR WORKDIR: `pip install ./python` as docs/python.md gives it (a virtual
# environment that sees Debian's numpy, no network), then checks that the module imported is the installed one (from
# the environment's site-packages, not the build tree), that its type stubs are beside it, and that it reads the
# tables installed with it, from another folder, without RIMU_DATA or PYTHONPATH.
set -euo pipefail
python=$1 src=$2 build=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
"$python" -m venv --system-site-packages "$work/env"
# The documented command; RIMU_BUILD_DIR points setup.py at this test's build folder, so the module is not built a
# second time (cmake --build finds it up to date).
RIMU_BUILD_DIR="$build" "$work/env/bin/pip" install --no-build-isolation --no-index --no-deps --no-cache-dir \
  --quiet "$src/python"
cd "$work"
env -u RIMU_DATA -u PYTHONPATH "$work/env/bin/python" - <<'PY'
import pathlib
import sys

import rimu

module_folder = pathlib.Path(rimu.__file__).resolve().parent
assert module_folder.is_relative_to(pathlib.Path(sys.prefix).resolve()), (module_folder, sys.prefix)
assert (module_folder / "rimu.pyi").is_file(), "rimu.pyi not installed beside the module"
library = rimu.Library()
assert pathlib.Path(library.root).resolve() == module_folder / "rimu_data", library.root
x, y = rimu.xy(library.light_xyz(*library.illuminant("F2")))
assert abs(x - 0.3721) < 5e-4 and abs(y - 0.3751) < 5e-4, (x, y)  # CIE 15:2004 Table T.8.1, F2
print(f"pip install: rimu {rimu.__version__} in {module_folder}, data {library.root}, F2 xy = {x:.4f}, {y:.4f}")
PY
