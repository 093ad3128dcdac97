#!/usr/bin/env bash
# Installs the Debian packages closurelab needs (only those missing). Works as root or with sudo.
# Open MPI (libopenmpi-dev openmpi-bin) is optional for the build (CLOSURELAB_WITH_MPI) and installed for the
# mpirun test of the runner.
set -euo pipefail
packages=(cmake g++ make git libeigen3-dev libgsl-dev nlohmann-json3-dev libsuitesparse-dev libgtest-dev
          libbenchmark-dev libomp-dev libhdf5-dev python3 python3-h5py libopenmpi-dev openmpi-bin python3-pysph
          python3-pandas python3-matplotlib libsundials-dev)
# python3-h5py: the tests check that the reference store's H5Part files open in h5py, and read one it wrote.
# python3-pandas: the table reader python/closurelab/tables.py (and its test); python3-matplotlib: the summaries'
# figures (scripts/reproduce.sh, the test summaries_every_kind); both for Debian's /usr/bin/python3.
# python3-pysph: the peer test (ctest -L peer) runs an independent PySPH model of the channel against the engine
# (under /usr/bin/python3; without it that test reports SKIP).
# libsundials-dev: SUNDIALS ARKODE, the integrators arkode_erk and arkode_imex (core/reduced/integrator_arkode.cpp).
# (`--figures`, which added python3-matplotlib, is still accepted: it is now in the list.)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install_deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
