#!/usr/bin/env bash
# Installs the Debian packages mesocrack needs, and nothing when all are present (idempotent).
set -euo pipefail
# libopenblas0-pthread: the BLAS that CHOLMOD's supernodal factorisation runs on (the reference BLAS that
# libsuitesparse-dev pulls in is 4-5 times slower there: 57 ms against 10.4 ms on a 2 832-DOF prism, and the
# dynamic cantilever takes 11.5 s against 6.6 s; the solver keeps it on one thread).
# libopenmpi-dev, openmpi-bin: mpirun spreads realizations over processes and machines (studies/ranks.cpp).
# libhdf5-openmpi-dev: parallel HDF5 for benchmarks/mpi_io only (the build itself links the serial library, which
# CMake finds through h5cc whatever pkg-config's hdf5.pc points to).
pkgs=(build-essential cmake libeigen3-dev libnanoflann-dev libhdf5-dev hdf5-tools doctest-dev
      libtoml11-dev libcli11-dev libomp-dev libcgal-dev libsuitesparse-dev libopenblas0-pthread
      libopenmpi-dev openmpi-bin libhdf5-openmpi-dev python3 python3-numpy python3-h5py python3-matplotlib)
# --paraview: ParaView 5.11 with its Python (about 440 MB), which the test of the XDMF sidecars reads them with
# (tests/paraview_opens_outputs.py, skipped without it) and xvfb for pictures rendered without a screen.
if [ "${1:-}" = "--paraview" ]; then
  pkgs+=(paraview python3-paraview xvfb xauth)
fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "setup: installing ${missing[*]}" >&2
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
