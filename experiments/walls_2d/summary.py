#!/usr/bin/env python3
"""The walled channels through the 2D force-density model (experiments/walls_2d/reduced.json) as a Markdown table,
beside the 1D near-wall model's rows of the error budgets on the same scenes and references.

Usage: python3 experiments/walls_2d/summary.py results/walls_2d/reduced/walls_2d_reduced.json > results/walls_2d/reduced/table.md
       python3 experiments/walls_2d/summary.py results/walls_2d/cylinder_channel/walls_2d_cylinder_channel.json \
           > results/walls_2d/cylinder_channel/table.md

Every row: the error against the averaged direct SPH over every coarse node (the wall-surface nodes included), the
paper's peak metric, the fastest reduced run with its spread, the direct run's time and the speed-up; then, for each
scene, the 1D model's near-wall rows (force-density balance, backward Euler, coarse-fine Tikhonov alpha = 1e-6 with
C = I and with the viscosity-weighted first difference) from results/error_budget/*/, for the channels' table.
"""
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
BUDGETS = {  # the scene label of reduced.json -> the error budget of the same scene and reference
    "uniform": "results/error_budget/poiseuille_uniform/error_budget_poiseuille_uniform.json",
    "fig4": "results/error_budget/fig4/error_budget_fig4.json",
    "two-phase case 3": "results/error_budget/two_phase_case3/error_budget_two_phase_case3.json",
}
ONE_D = {  # the 1D rows compared, by their labels in the error budgets
    "C = I": "force-density balance, backward Euler, tikhonov alpha=1e-6 (C = I), cf",
    "C = viscosity-weighted first difference": "force-density balance, backward Euler, tikhonov alpha=1e-6 "
                                               "(C = viscosity-weighted first difference with the wall links), cf",
}


def pct(x):
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else "%.4g %%" % (100.0 * x)


def errors(r):
    v = r.get("errors", {}).get("vs_averaged_direct_sph", {})
    return v.get("all_nodes", {}).get("max_rel"), v.get("peak_relative_difference")


def main():
    table = json.load(open(sys.argv[1]))
    rows = table["rows"]
    prov = table.get("provenance", {})
    print("# Walled channels through the 2D force-density model")
    print()
    print("Table: `%s` (commit %s). Errors against the averaged direct SPH of the same strip, max over every coarse "
          "node (the wall-surface nodes included), with the paper's peak metric; the reduced run's time is the fastest "
          "of its repeats (setup and solve), with the spread (median − min) / min." % (
              os.path.relpath(sys.argv[1], ROOT) if os.path.isabs(sys.argv[1]) else sys.argv[1],
              ", ".join(prov.get("commits", ["?"]))))
    print()
    print("| cell | all nodes | peak metric | reduced (fastest, spread) | direct SPH | speed-up |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        if r.get("status") != "ok":
            print("| %s | %s: %s | | | | |" % (r["label"], r.get("status"), (r.get("error") or r.get("message") or "")[:90]))
            continue
        c = r.get("cost", {})
        t = c.get("reduced_timing", {})
        e_all, e_peak = errors(r)
        print("| %s | %s | %s | %.3g s (%.0f %%) | %.0f s | %.3g |" % (
            r["label"], pct(e_all), pct(e_peak), t.get("min_seconds", float("nan")),
            100.0 * t.get("spread", float("nan")), c.get("direct_sph_wall_seconds", float("nan")),
            c.get("speed_up", float("nan"))))
    if not any(r["label"].startswith(tuple(BUDGETS)) for r in rows):
        return
    print()
    print("The 1D model's near-wall rows on the same scenes and references (results/error_budget):")
    print()
    print("| scene | 1D row | all nodes | peak metric | commit |")
    print("|---|---|---|---|---|")
    for scene, path in BUDGETS.items():
        full = os.path.join(ROOT, path)
        if not os.path.exists(full):
            continue
        budget = json.load(open(full))
        for short, label in ONE_D.items():
            row = next((r for r in budget["rows"] if r.get("label") == label), None)
            if row is None:
                continue
            e_all, e_peak = errors(row)
            print("| %s | %s | %s | %s | %s |" % (scene, short, pct(e_all), pct(e_peak),
                                                   ", ".join(budget.get("provenance", {}).get("commits", ["?"]))))


if __name__ == "__main__":
    main()
