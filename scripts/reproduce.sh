#!/usr/bin/env bash
# The main job. Installs what is missing (apt), builds the closurelab executable, then:
#
#   scripts/reproduce.sh          the quick run: computes from scratch (no cached cell reused) the headline
#                                 matrix of experiments/quick/ into out/quick/ (git-ignored): the direct SPH
#                                 reference of a channel (n_y = 96) and of the kolmogorov scene (n_y = 64), the
#                                 reduced model with the paper's closures on each (and, on the channel, the
#                                 force-density balance and the near-wall formulation), each reduced run repeated
#                                 until its fastest time is stable, the speed-against-error front and the profiles
#                                 as figures; prints one line per cell with the time left, and ends with the
#                                 headline (best closure's error beside the paper formulation's best, speed-ups
#                                 from the fastest runs with the median's, the reference's own error).
#                                 Measured: docs/results.md ("The quick run").
#   scripts/reproduce.sh --full   regenerates the committed paper set in results/ (hours from scratch; finished
#                                 cells are kept and skipped, so an interrupted run resumes; add --force to
#                                 recompute), then every summary and the index results/README.md.
#   scripts/reproduce.sh --summaries   only the summaries and the index, from the committed tables.
# Extra arguments after --full go to `closurelab run` (e.g. --jobs 2, --force).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=quick
case "${1:-}" in
  --full) mode=full; shift ;;
  --summaries) mode=summaries; shift ;;
  --help|-h) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  "") ;;
  *) echo "reproduce: unknown argument '$1'; valid: --full [closurelab run options], --summaries, --help" >&2; exit 2 ;;
esac
# Idle OpenMP threads sleep instead of spinning: on a loaded machine spinning threads made runs 10-20x slower.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-PASSIVE}"
PY=/usr/bin/python3; [ -x "$PY" ] || PY=python3   # Debian's python3 has python3-matplotlib for the figures
SUMMARIZE=("$PY" experiments/summaries/summarize.py)
if [ "$mode" != summaries ]; then
  scripts/install_deps.sh --figures
  launcher=()
  command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
  cmake --build build -j "$(nproc)" --target closurelab
fi
run() { build/experiments/closurelab run "$1" --out "$2" "${@:3}"; }

if [ "$mode" = quick ]; then
  out=out/quick
  rm -rf "$out"   # from scratch: no cached cell is reused
  start=$(date +%s)
  tables=()
  for spec in experiments/quick/*.json; do
    name=$(basename "$spec" .json)
    run "$spec" "$out/$name" --store "$out/store"   # a fresh reference store: no stored direct run reused
    tables+=("$out/$name/$name.json")
    "${SUMMARIZE[@]}" --view front "$out/$name/$name.json" "$out/$name"
    "${SUMMARIZE[@]}" --view profiles "$out/$name/$name.json" "$out/$name"
  done
  echo
  echo "reproduce: quick run done in $(( $(date +%s) - start )) s (computing and summaries; the build not counted)"
  echo "reproduce: summary $out/summary.md; per scene: $out/<scene>/front.md and profiles.md (figures .png"\
       "where python3-matplotlib is installed); tables $out/<scene>/<scene>.json"
  echo "reproduce: headline (errors relative to the analytic peak):"
  "${SUMMARIZE[@]}" --headline "$out" "${tables[@]}"
  exit 0
fi

if [ "$mode" = full ]; then
  # Each line: a spec and its output folder (results/<group>/<name>/).
  while read -r spec dir; do
    run "$spec" "$dir" "$@"
  done <<'LIST'
experiments/sph_validation.json results/sph_validation
experiments/stability/square.json results/stability
experiments/stability/coarse_fine.json results/stability
experiments/stability/rules.json results/stability
experiments/paper/appendix_c.json results/paper/appendix_c
experiments/paper/appendix_b.json results/paper/appendix_b
experiments/paper/fig2.json results/paper/fig2
experiments/paper/fig3.json results/paper/fig3
experiments/paper/fig4.json results/paper/fig4
experiments/paper/kolmogorov.json results/paper/kolmogorov
experiments/paper/speed_up.json results/paper/speed_up
experiments/speed_vs_error/poiseuille_uniform.json results/speed_vs_error/poiseuille_uniform
experiments/speed_vs_error/poiseuille_periodic.json results/speed_vs_error/poiseuille_periodic
experiments/speed_vs_error/kolmogorov.json results/speed_vs_error/kolmogorov
experiments/paper/two_phase_direct.json results/two_phase/direct
experiments/paper/two_phase.json results/two_phase/two_phase
experiments/paper/two_phase_eta.json results/two_phase/two_phase_eta
experiments/error_budget/poiseuille_uniform.json results/error_budget/poiseuille_uniform
experiments/error_budget/fig4.json results/error_budget/fig4
experiments/error_budget/two_phase_case3.json results/error_budget/two_phase_case3
experiments/near_wall/fig2.json results/near_wall/fig2
experiments/near_wall/two_phase.json results/near_wall/two_phase
experiments/cellular/direct.json results/cellular/direct
experiments/cellular/reduced.json results/cellular/reduced
experiments/speed_vs_error/cellular.json results/speed_vs_error/cellular
experiments/cellular/coarse_continuum.json results/cellular/coarse_continuum
experiments/taylor_green/tvf_re100_perturbed.json results/taylor_green/tvf_re100_perturbed
experiments/taylor_green/coarse_continuum_re100.json results/taylor_green/coarse_continuum_re100
experiments/taylor_green/reduced_2d_re100.json results/taylor_green/reduced_2d_re100
experiments/cavity/tvf_re100.json results/cavity/tvf_re100
experiments/cavity/coarse_continuum_re100.json results/cavity/coarse_continuum_re100
experiments/cavity/reduced_2d_re100.json results/cavity/reduced_2d_re100
experiments/cylinders/tvf_re1.json results/cylinders/tvf_re1
experiments/cylinders/tvf_re10.json results/cylinders/tvf_re10
experiments/cylinders/linearised_steady.json results/cylinders/linearised_steady
experiments/cylinders/reduced_steady_like_for_like.json results/cylinders/reduced_steady_like_for_like
experiments/cylinders/reduced_tvf.json results/cylinders/reduced_tvf
experiments/cylinders/reduced_tvf_diagnostics.json results/cylinders/reduced_tvf/diagnostics
experiments/cylinders/reduced_tvf_marched.json results/cylinders/reduced_tvf_marched
LIST
fi

# Every summary, one tool: each line is the tables of one summary (and its folder where it is not theirs).
while read -r -a args; do
  "${SUMMARIZE[@]}" "${args[@]}"
done < experiments/summaries/committed_summaries.txt
"$PY" experiments/summaries/results_index.py > results/README.md
echo "reproduce: results and summaries under results/; index results/README.md"
