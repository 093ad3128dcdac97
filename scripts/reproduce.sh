#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the paper reproduction as far as it exists:
#   results/sph_validation/   the direct SPH reference (issue 2), ~25 min on one core
#   results/stability/        the deconvolution hard-case suite (issue 3), seconds
#   results/paper/            the reduced model: Figs. 2-4, the kolmogorov diagnostic (issue 4), App. C, ~20 min
# Finished cells are kept and skipped on a re-run (an interrupted run resumes); pass --force to recompute.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh --figures
scripts/build.sh
run() { build/experiments/closurelab run "$1" --out "$2" "${@:3}"; }
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3   # Debian's python3 has python3-matplotlib for the figures

run experiments/sph_validation.json results/sph_validation "$@"
python3 experiments/summarize_validation.py results/sph_validation/sph_validation.json > results/sph_validation/summary.md

for s in square coarse_fine rules; do run "experiments/stability/$s.json" results/stability "$@"; done
python3 results/stability/summarize.py results/stability/stability_{square,coarse_fine,rules}.json > results/stability/SUMMARY.md

run experiments/paper/appendix_c.json results/paper/appendix_c "$@"
python3 experiments/summarize_appendix_c.py results/paper/appendix_c/appendix_c.json > results/paper/appendix_c/summary.md
for f in fig2 fig3 fig4 kolmogorov; do
  run "experiments/paper/$f.json" "results/paper/$f" "$@"
  "$PY" experiments/summarize_reduced_model.py "results/paper/$f/$f.json" "results/paper/$f/summary"
done
echo "reproduce: results written under results/"
