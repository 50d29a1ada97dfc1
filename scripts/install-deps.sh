#!/usr/bin/env bash
# moraine: install the Debian packages the build, the examples and the tests need.
# Safe to run again; does nothing when everything is present. Needs root (or sudo).
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  help2man                        # the man page, made from moraine --help at build time
  liblua5.4-dev lua5.4            # the embedded Lua 5.4 (C API) and a stock interpreter (the C module's test)
  libhdf5-dev hdf5-tools          # HDF5 (checkpoints, time series) and h5dump
  zlib1g-dev                      # CRC-32 of the checkpoint checksums
  libsuitesparse-dev              # UMFPACK sparse LU for the implicit integrator
  python3 python3-numpy python3-vtk9 python3-h5py   # the tests read outputs with the real VTK reader
  python3-xarray python3-h5netcdf  # the series read as xarray sees it (dimension scales)
  python3-matplotlib gnuplot-nox  # plots (scripts/moraine-plot uses matplotlib, else gnuplot)
  clang libclang-rt-14-dev        # the libFuzzer harnesses (-DMORAINE_FUZZ=ON, tests/fuzz/README.md)
  valgrind                        # the weekly memcheck target (scripts/memcheck.sh)
  libopenmpi-dev openmpi-bin      # distributed runs under mpirun (doc/parallel.md)
  python3-mpi4py                  # bench/mpi_pingpong.py: latency and bandwidth between processes
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
