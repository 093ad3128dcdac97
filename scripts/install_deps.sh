#!/usr/bin/env bash
# Installs the Debian packages closurelab needs (only those missing). Works as root or with sudo.
# Open MPI (libopenmpi-dev openmpi-bin) is optional for the build (CLOSURELAB_WITH_MPI) and installed for the
# mpirun test of the runner.
set -euo pipefail
packages=(cmake g++ make git libeigen3-dev libgsl-dev nlohmann-json3-dev libsuitesparse-dev libgtest-dev
          libbenchmark-dev libomp-dev libhdf5-dev python3 python3-h5py libopenmpi-dev openmpi-bin python3-pysph)
# python3-h5py: the tests check that the reference store's H5Part files open in h5py, and read one it wrote.
# python3-pysph: the peer test (ctest -L peer) runs an independent PySPH model of the channel against the engine
# (under /usr/bin/python3; without it that test reports SKIP).
# The figures of scripts/reproduce.sh also need python3-matplotlib: `scripts/install_deps.sh --figures`.
[ "${1:-}" = "--figures" ] && packages+=(python3-matplotlib)
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
