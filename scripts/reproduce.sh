#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the paper reproduction as far as it exists:
#   results/sph_validation/   the direct SPH reference (issue 2), ~25 min on one core
#   results/stability/        the deconvolution hard-case suite (issue 3), seconds
#   results/paper/            the reduced model: Figs. 2-4, the kolmogorov diagnostic, App. B and C, the
#                             speed-up against the full 192 x 192 direct SPH (issue 4), ~40 min
#   results/speed_vs_error/   every deconvolution strategy as the closure, per scene (issue 4), ~5 min
#   results/two_phase/        the layered two-phase flow: direct SPH, reduced model, eta' sweep (issue 5), ~40 min
# Finished cells are kept and skipped on a re-run (an interrupted run resumes); pass --force to recompute.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh --figures
scripts/build.sh
run() { build/experiments/closurelab run "$1" --out "$2" "${@:3}"; }
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3   # Debian's python3 has python3-matplotlib for the figures

run experiments/sph_validation.json results/sph_validation "$@"
python3 experiments/summaries/summarize_validation.py results/sph_validation/sph_validation.json > results/sph_validation/summary.md

for s in square coarse_fine rules; do run "experiments/stability/$s.json" results/stability "$@"; done
python3 experiments/summaries/summarize_stability.py results/stability/stability_{square,coarse_fine,rules}.json > results/stability/SUMMARY.md

run experiments/paper/appendix_c.json results/paper/appendix_c "$@"
python3 experiments/summaries/summarize_appendix_c.py results/paper/appendix_c/appendix_c.json > results/paper/appendix_c/summary.md
run experiments/paper/appendix_b.json results/paper/appendix_b "$@"
python3 experiments/summaries/summarize_appendix_b.py results/paper/appendix_b/appendix_b.json > results/paper/appendix_b/summary.md
for f in fig2 fig3 fig4 kolmogorov speed_up; do
  run "experiments/paper/$f.json" "results/paper/$f" "$@"
  "$PY" experiments/summaries/summarize_reduced_model.py "results/paper/$f/$f.json" "results/paper/$f/summary"
done

for s in poiseuille_uniform poiseuille_periodic kolmogorov; do
  run "experiments/speed_vs_error/$s.json" "results/speed_vs_error/$s" "$@"
  "$PY" experiments/summaries/summarize_pareto.py "results/speed_vs_error/$s/pareto_$s.json" "results/speed_vs_error/$s/summary"
done

run experiments/paper/two_phase_direct.json results/two_phase/direct "$@"
python3 experiments/summaries/summarize_two_phase.py results/two_phase/direct/two_phase_direct.json > results/two_phase/direct/summary.md
run experiments/paper/two_phase.json results/two_phase/two_phase "$@"
run experiments/paper/two_phase_eta.json results/two_phase/two_phase_eta "$@"
"$PY" experiments/summaries/summarize_two_phase_reduced.py results/two_phase/two_phase/two_phase.json \
  results/two_phase/two_phase_eta/two_phase_eta.json results/two_phase/reduced
echo "reproduce: results written under results/"
