#!/usr/bin/env bash
# Installs every Debian package physarum needs (idempotent, as root) and builds the `physarum`
# program in Release into ./build: what a first run needs, nothing more.
#   bash tools/setup.sh           the program only (the README's first command)
#   bash tools/setup.sh --tests   also the Python environment .venv (pinned versions: trimesh, numpy,
#                                 pillow for tests/read_exports.py; nanobind, scikit-build-core and
#                                 pytest for the Python module and its tests), the schedulers the sweep
#                                 tests use (Slurm, munge, GNU parallel; no daemon is started or
#                                 configured system-wide), Blender for tests/blender_exports.py, Mesa's
#                                 OpenCL (a second implementation the tests run on), and
#                                 every target: the test program, the benchmarks, the device check,
#                                 the Python module (the README's second command, CI)
# Safe to run again: packages already present are not reinstalled, a .venv that already holds the
# pinned versions is kept, and the build is incremental.
set -euo pipefail
cd "$(dirname "$0")/.."

with_tests=false
case "${1:-}" in
  "") ;;
  --tests) with_tests=true ;;
  *) echo "usage: bash tools/setup.sh [--tests]" >&2; exit 2 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers pocl-opencl-icd clinfo oclgrind
  libeigen3-dev libopenmesh-dev libopenimageio-dev libgtest-dev libbenchmark-dev
  librandom123-dev libspectra-dev nlohmann-json3-dev libcli11-dev fonts-dejavu-core libboost-math-dev
  libtinygltf-dev libsuitesparse-dev libopenblas0-pthread libxxhash-dev libmuparser-dev python3-venv
  python3-dev
)

# Only the tests use these: the schedulers the sweep tests submit to (a private Slurm the tests start
# and stop themselves, GNU parallel); Blender (headless, with the numpy its importers need) as the
# independent reader of result.glb; Mesa's
# OpenCL (rusticl on llvmpipe: a second implementation beside PoCL, which
# tests/test_other_opencl_implementations.cpp holds to the reference).
test_packages=(slurm-wlm munge parallel blender python3-numpy mesa-opencl-icd)
if $with_tests; then packages+=("${test_packages[@]}"); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ $(id -u) -ne 0 ]]; then
    echo "setup: missing packages (${missing[*]}); run this script as root to install them" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The tests' own Python (not the system's: Debian's pip refuses to install into it, and the versions
# must be the ones the tests were written against): the reader test's trimesh, numpy and pillow, and
# the Python module's nanobind (CMake builds the module when .venv has it), scikit-build-core (for
# `.venv/bin/pip install --no-build-isolation -C build-dir=build .`) and pytest (its tests).
python_packages=(trimesh==5.2.0 numpy==2.4.6 pillow==13.0.0 nanobind==2.9.2 scikit-build-core==0.11.6 pytest==8.4.2)
venv=.venv
venv_is_current() {
  [[ -x $venv/bin/python ]] && "$venv/bin/python" - "${python_packages[@]}" <<'PY'
import sys
from importlib.metadata import version, PackageNotFoundError
try:
    sys.exit(0 if all(version(n) == v for n, v in (p.split("==") for p in sys.argv[1:])) else 1)
except PackageNotFoundError:
    sys.exit(1)
PY
}
if $with_tests && ! venv_is_current; then
  echo "setup: creating $venv with ${python_packages[*]}"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${python_packages[@]}"
  venv_is_current || { echo "setup: $venv does not hold ${python_packages[*]} after installing" >&2; exit 1; }
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
if $with_tests; then
  cmake --build build -j "$(nproc)"
else
  cmake --build build -j "$(nproc)" --target physarum
fi
