#!/bin/sh
# Tutorial step 2: deconvolve a user system with every kind of closure the experiments use, and print one line
# per method (status, the parameter chosen, the relative error against the truth, matrix-vector products).
# Usage, from the repository root: docs/tutorials/step-2/run.sh [CLOSURELAB] [WORK_DIR]
set -e
exe=${1:-build/experiments/closurelab}
work=${2:-out/tutorials/step-2}
mkdir -p "$work"
delta=$(/usr/bin/python3 docs/tutorials/step-2/make_system.py "$work")
echo "noise level ||b - A x_true||_2 = $delta"
for method in "landweber --param order=0" "landweber --param order=2" "landweber --param rule=discrepancy" \
              "cgls --param rule=discrepancy" "tikhonov --param rule=discrepancy" "tikhonov --param rule=gcv" \
              "tikhonov --param rule=lcurve" "tsvd --param rule=gcv"; do
  # shellcheck disable=SC2086 # the method and its --param words are meant to split
  "$exe" deconvolve --matrix "$work/A.mtx" --rhs "$work/b.mtx" --x-true "$work/x_true.mtx" --method $method \
         --noise-level "$delta" --out "$work/x.mtx" > "$work/result.json"
  /usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); s = r["stats"]
print("%-38s %-10s %-20s relative error %.3g, %d matvecs" % (sys.argv[2], r["status"], "%s = %.3g" % (s["parameter_name"],
      s["chosen_parameter"]), r["relative_error"], r["cost"]["matvecs"]))' "$work/result.json" "$method"
done
