#!/usr/bin/env bash
# Bounded fuzzing (CI): builds the four libFuzzer targets (spec validation, Matrix Market, CSV particle
# snapshots, HDF5 particle snapshots: H5Part and PySPH files written from a structure the bytes describe) with clang (the libraries instrumented with ASan + UBSan, in ./build-fuzz) and runs each for
# FUZZ_SECONDS (default 60) on a scratch copy of its checked-in seed corpus, so that new inputs are not added to
# the repository. A crash, a sanitizer report or a leak fails the script.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-60}"
missing=()
for p in clang libclang-rt-14-dev; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DCLOSURELAB_FUZZ=ON \
      -DCLOSURELAB_BUILD_TESTS=OFF -DCLOSURELAB_BUILD_BENCH=OFF -DCLOSURELAB_WITH_MPI=OFF "${launcher[@]}" >/dev/null
cmake --build build-fuzz -j "$(nproc)" --target fuzz_spec_validation fuzz_matrix_market fuzz_particle_csv \
      fuzz_hdf5_snapshot
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for t in matrix_market spec particle_csv hdf5_snapshot; do
  target=fuzz_${t}; [ "$t" = spec ] && target=fuzz_spec_validation
  cp -r "tests/fuzz/corpus/$t" "$scratch/$t"
  echo "fuzz: $target for ${seconds} s"
  (cd "$scratch" && "$OLDPWD/build-fuzz/tests/fuzz/$target" -max_total_time="$seconds" -rss_limit_mb=4096 \
       -print_final_stats=1 "$scratch/$t" 2>&1 | tail -n 12)
done
echo "fuzz: ok"
