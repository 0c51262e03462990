#!/usr/bin/env bash
# Install the Debian packages piezocontact needs (only those missing), then
# configure and build it in build/ and install it under /usr/local. Safe to
# run again: it does only what is left to do. Debian 12 (bookworm, dolfinx
# 0.5.2), Debian 13 (trixie, dolfinx 0.9.0) and unstable (sid, dolfinx
# 0.11.0); scripts/debian.sh runs a command in a root of the other two.
# --packages-only: install the packages and stop.
set -euo pipefail
cd "$(dirname "$0")/.."

# The one difference in what to install: the bindings' library (dolfinx's
# Python layer is pybind11 in 0.5, nanobind from 0.9; ours must match it)
release=$(. /etc/os-release && echo "${VERSION_CODENAME:-unknown}")
case "$release" in
  bookworm) BINDINGS=(pybind11-dev) ;;
  # sid says the codename of the testing release it leads to
  trixie | forky | sid) BINDINGS=(nanobind-dev python3-nanobind) ;;
  *) echo "setup: Debian 12 (bookworm), 13 (trixie) or unstable (sid) expected, found '$release'" >&2
     exit 2 ;;
esac

PACKAGES=(
  # FEniCSx 0.5 stack: dolfinx C++ and Python, ffcx, UFL, basix, PETSc
  libdolfinx-dev python3-dolfinx python3-ffcx python3-ufl python3-basix
  python3-petsc4py python3-mpi4py python3-numpy
  # the reference engine's floating electrodes (multi-point constraints)
  python3-dolfinx-mpc
  # meshes: gmsh and its Python API (example 2)
  python3-gmsh
  # build: compilers, CMake, pkg-config (PETSc), JSON for the C++ config
  cmake g++ make pkg-config nlohmann-json3-dev libgtest-dev
  # expressions of x, y, z, t in prescribed data
  libmuparser-dev
  # eigenvalues of modal analyses: SLEPc (C for the core, slepc4py for the
  # reference engine)
  libslepc-real-dev python3-slepc4py
  # Python bindings of the C++ core
  "${BINDINGS[@]}" python3-dev
  # MPI launcher; OpenBLAS makes MUMPS' LU ~3x faster than reference BLAS
  openmpi-bin libopenblas0
  # tests and pictures
  python3-pytest python3-matplotlib
  # tests derive the loads of exact solutions as expressions
  python3-sympy
  # tests read the XDMF steps back; the forms-edit test copies the tracked tree
  # (git ls-files)
  python3-h5py git
  # benchmarks: /usr/bin/time for peak memory
  time
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" \
    || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends \
    "${missing[@]}"
fi
[ "${1:-}" != --packages-only ] || exit 0

# Debian's packages live in /usr/bin/python3, not in a pyenv python3 on PATH
cmake -B build -S . -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build build -j"$(nproc)"
# Install the library, headers, CMake package, `piezo-contact` and the Python
# package (with its forms/) under /usr/local: `import piezocontact` from any folder
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
$SUDO cmake --install build >/dev/null
