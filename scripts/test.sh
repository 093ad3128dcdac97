#!/usr/bin/env bash
# The test command: installs what is missing, builds, and runs the whole test suite with ctest.
# Extra arguments go to ctest, e.g. `scripts/test.sh -L unit` for the quick subset.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh
cd build
# ctest runs one test process per core; each uses one OpenMP thread so that they do not oversubscribe.
# The label `timing` (speed-up repeatability, load-dependent) runs only when asked: `ctest -L timing`.
if [ $# -eq 0 ]; then set -- -LE timing; fi
OMP_NUM_THREADS=1 ctest --output-on-failure -j "$(nproc)" --timeout 1500 "$@"
