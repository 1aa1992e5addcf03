#!/usr/bin/env bash
# Installs the Debian packages Rimu builds against, and only those that are missing.
#   scripts/install-deps.sh          what building and running the tools needs (scripts/main.sh)
#   scripts/install-deps.sh --test   that, plus what the tests, benchmarks, fuzzers, the Python module and the
#                                    render-farm test need (scripts/test.sh)
# Idempotent: when everything is present it does nothing (no apt-get update, no network).
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libembree-dev          # Embree 3: BVH and ray queries
  libopenexr-dev         # OpenEXR 3: film output
  libopencolorio-dev     # OpenColorIO 2: display transforms
  libopenimageio-dev     # OpenImageIO 2: TIFF, HDR and other textures, PNG output
  libstb-dev             # stb_image: PNG, JPEG, TGA, BMP textures in-process
  libfreeimage-dev       # FreeImage: PFM images (environment maps) without loading OpenImageIO
  libpng-dev             # libpng: display PNGs written without loading OpenImageIO
  libtbb-dev             # oneTBB: parallel tiles
  nlohmann-json3-dev     # scene files, --json output
  libcli11-dev           # command-line parsing
  libtinyobjloader-dev   # OBJ meshes
  zlib1g-dev             # .ply.gz meshes, ZIP-compressed .nvdb volumes
  libnanovdb-dev         # NanoVDB: sparse .nvdb volumes (header-only; brings libblosc-dev for BLOSC files)
  gnuplot-nox            # the tools' --plot/--graphic figures
)
test_packages=(
  doctest-dev            # unit tests
  libbenchmark-dev       # Google Benchmark (benchmarks)
  pybind11-dev python3-dev python3-pybind11  # the rimu Python module
  python3-numpy          # spectra as numpy arrays in the Python module and its tests
  python3-jsonschema     # docs/scene.schema.json checked against the shipped scenes
  python3-venv python3-pip python3-setuptools python3-wheel  # the test of `pip install ./python` (offline)
  clang                  # fuzz targets (scripts/fuzz.sh): clang++ 14
  libclang-rt-14-dev     # libFuzzer and the sanitizer runtimes for clang 14
  slurm-wlm slurmctld slurmd slurm-client munge  # render-farm tests: a single-node Slurm (scripts/slurm-local.sh)
)
case "${1:-}" in
  "") ;;
  --test) packages+=("${test_packages[@]}") ;;
  *) echo "install-deps: unknown option '$1' (expected nothing or --test)" >&2; exit 1 ;;
esac

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
