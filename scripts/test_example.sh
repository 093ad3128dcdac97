#!/usr/bin/env bash
# The testbed as others extend it: installs the build (./build, made by scripts/build.sh) into a temporary
# prefix, builds examples/custom_deconvolver against the installed package (find_package(closurelab)), runs its
# conformance check on the user's Richardson iteration and its tiny spec (both closures ok, and Richardson with
# omega = 1 gives the built-in Landweber series of the same order). Exits non-zero on any
# failure; leaves nothing behind.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install build --prefix "$tmp/prefix" >/dev/null
echo "test_example: installed into a temporary prefix"
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S examples/custom_deconvolver -B "$tmp/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$tmp/prefix" \
      "${launcher[@]}" >/dev/null
cmake --build "$tmp/build" -j "$(nproc)"
ctest --test-dir "$tmp/build" --output-on-failure
"$tmp/build/test_richardson_conformance"
OMP_NUM_THREADS=1 "$tmp/build/custom_closurelab" run examples/custom_deconvolver/kolmogorov_richardson.json \
  --out "$tmp/out" --store "$tmp/store"
python3 - "$tmp/out/kolmogorov_richardson.json" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]
bad = [r for r in rows if r.get("status") == "error"]
assert len(rows) == 2 and not bad, f"{len(rows)} rows, failed: {bad}"
# Richardson with omega = 1 and 3 iterations is the Landweber series of order 2: the same closure.
a, b = (r["errors"]["kolmogorov"]["amplitude_ratio"] for r in rows)
assert abs(a - b) <= 1e-9 * abs(b), f"richardson {a} != landweber {b}"
print(f"test_example: the example's spec ran both cells; richardson = landweber n=2 (amplitude ratio {a:.6f})")
PY
echo "test_example: ok"
