#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the paper reproduction as far as it exists
# (today: the direct SPH validation, experiments/sph_validation.json, into results/sph_validation/).
# Finished cells are kept and skipped on a re-run; pass --force to recompute them.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh
build/experiments/closurelab run experiments/sph_validation.json --out results/sph_validation "$@"
python3 experiments/summarize_validation.py results/sph_validation/sph_validation.json > results/sph_validation/summary.md
echo "wrote results/sph_validation/sph_validation.json and summary.md"
