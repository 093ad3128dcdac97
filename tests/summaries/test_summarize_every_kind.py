#!/usr/bin/env python3
"""summarize.py works for every kind and reduced model: on one committed table per kind (and per reduced model and
view) it exits 0 into a temporary folder, prints the paths it wrote, and those are the expected Markdown and figures,
each a non-empty file; the force-density view's table carries the permeability (cylinder lattice) and % errors.
Then it exits 0 on every committed table under results/, each alone (the Markdown), and 2 on a spec and on a
JSON file that is no table, saying which.
snapshot_closure has no committed table: a small one with that kind's row layout
(experiments/kinds/snapshot_closure.cpp) is written here.

Usage: python3 tests/summaries/test_summarize_every_kind.py   (from the repository root; exit 1 on a failure)
Figures are drawn and checked where matplotlib imports (Debian's python3-matplotlib under /usr/bin/python3);
elsewhere the Markdown alone is checked (--no-figures), and the test says so.
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SUMMARIZE = os.path.join(ROOT, "experiments", "summaries", "summarize.py")

# (tables, summarize.py options, expected files with figures, expected files without, text the Markdown must hold)
CASES = [
    (["results/stability/stability_square.json"], [], ["SUMMARY.md"], ["SUMMARY.md"], []),
    (["results/paper/appendix_c/appendix_c.json"], [], ["summary.md"], ["summary.md"], []),
    (["results/paper/appendix_b/appendix_b.json"], [], ["summary.md"], ["summary.md"], []),
    (["results/cellular/direct/direct.json"], [], ["summary.md"], ["summary.md"], []),
    (["results/cylinders/direct/direct.json"], [], ["summary.md"], ["summary.md"], ["k / k_ref - 1"]),
    (["results/two_phase/direct/two_phase_direct.json"], [], ["summary.md"], ["summary.md"], []),
    # reduced_model, the column: the paper's views, the front, the error budget, the profiles
    (["results/paper/fig2/fig2.json"], [], ["summary.md", "summary.png", "summary_sweep.png"], ["summary.md"], [" %"]),
    # a sweep of three keys, two of them categorical: the error against each
    (["results/sph_validation/sph_validation.json"], [], ["summary.md", "summary_sweep.png"], ["summary.md"], []),
    (["results/speed_vs_error/poiseuille_uniform/pareto_poiseuille_uniform.json"], [],
     ["summary.md", "summary.png"], ["summary.md"], []),
    (["results/error_budget/floor/error_budget_floor.json"], [], ["summary.md", "summary.png"], ["summary.md"], []),
    # reduced_model, the force-density model (kind reduced_model, model chosen by the scene)
    (["results/cellular/force_density/cellular_force_density.json"], [],
     ["summary.md", "summary_fields.png", "summary_sweep.png"], ["summary.md"], ["outside solid", " %"]),
    # a view asked for by name on a table it cannot draw: the Markdown, no crash
    (["results/cellular/force_density/cellular_force_density.json"], ["--view", "profiles"],
     ["profiles.md"], ["profiles.md"], []),
    # reduced_model_2d (the 2D mesh model of the cellular flow)
    (["results/cellular/reduced/reduced.json"], [], ["summary.md", "summary_fields.png"], ["summary.md"], []),
    # coarse_continuum_2d (the coarse continuum Navier-Stokes baseline): the Markdown, and the sweep over n and the force
    (["results/cellular/coarse_continuum/coarse_continuum.json"], [], ["summary.md", "summary_sweep.png"],
     ["summary.md"], ["vs averaged direct SPH", " %"]),
    # reduced_model_2d_force_density: the cylinder lattice (with its permeability), walls as one column, the
    # cylinder between walls
    (["results/cylinders/reduced/reduced.json"], [], ["summary.md", "summary_fields.png"], ["summary.md"],
     ["k reduced", "k red vs direct", "+0.113 %", "0.257 %", "(noisy)", "more than 10 %"]),
    (["results/walls_2d/reduced/walls_2d_reduced.json"], [], ["summary.md", "summary_fields.png"], ["summary.md"],
     ["The scene has no permeability"]),
    (["results/walls_2d/cylinder_channel/walls_2d_cylinder_channel.json"], [],
     ["summary.md", "summary_fields.png"], ["summary.md"], []),
]


def snapshot_closure_table(path):
    """A snapshot_closure table with the row layout snapshot_closure.cpp writes (values made up, not results)."""
    ys = [0.1 * k for k in range(1, 10)]
    norm = {"max_rel": 0.01, "l2_rel": 0.005, "count": 3}
    row = {"id": "0", "label": "landweber n=0", "status": "ok", "params": {"scene": {"name": "poiseuille-uniform"}},
           "snapshot": {"time": 1.0, "particles": 100, "pairs": 1000},
           "errors": {"stress_xy": {"channel": norm, "interior": norm, "wall_band": norm, "max_abs_exact": 1.0},
                      "particle_velocity_max_rel": 0.02},
           "profile": {"y": ys, "exact_xy": [0.5 - y for y in ys], "closure_xy": [0.49 - y for y in ys],
                       "y_data": ys, "averaged_vx": [y * (1 - y) for y in ys]},
           "cost": {"read_seconds": 0.01, "deconvolution_seconds": 0.02, "stress_seconds": 0.03}}
    table = {"experiment": "snapshot_test", "kind": "snapshot_closure", "description": "made up for the test",
             "complete": True, "spec": {}, "rows": [row],
             "provenance": {"git_commit": "0", "compiler": "-", "build_type": "-", "threads": 1, "date_utc": "-",
                            "command": "-"}}
    with open(path, "w") as f:
        json.dump(table, f)


def committed_tables():
    """Every results table under results/ (a JSON object with a "rows" list; a run's cells/ folders left out)."""
    found = []
    for folder, dirs, files in os.walk(os.path.join(ROOT, "results")):
        dirs[:] = sorted(d for d in dirs if d != "cells")
        for name in sorted(files):
            if not name.endswith(".json"):
                continue
            path = os.path.join(folder, name)
            try:
                with open(path) as f:
                    table = json.load(f)
            except (OSError, ValueError):
                continue
            if isinstance(table, dict) and isinstance(table.get("rows"), list):
                found.append(path)
    return found


def main():
    try:
        import matplotlib  # noqa: F401
        figures = True
    except ImportError:
        figures = False
        print(f"test_summarize_every_kind: matplotlib is not importable by {sys.executable}: the Markdown alone is "
              "checked (--no-figures)")
    failures, runs = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        synthetic = os.path.join(tmp, "snapshot_test.json")
        snapshot_closure_table(synthetic)
        cases = CASES + [([synthetic], [], ["summary.md", "summary.png"], ["summary.md"], ["1 %", "2 %"])]
        for k, (tables, options, with_fig, without_fig, texts) in enumerate(cases):
            out = os.path.join(tmp, f"out{k}")
            tables = [t if os.path.isabs(t) else os.path.join(ROOT, t) for t in tables]
            cmd = [sys.executable, SUMMARIZE] + ([] if figures else ["--no-figures"]) + options + tables + [out]
            r = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, env=dict(os.environ, MPLBACKEND="Agg"))
            runs += 1
            what = " ".join(options + [os.path.relpath(t, ROOT) if t.startswith(ROOT) else "snapshot_closure"
                                       for t in tables])
            if r.returncode != 0:
                failures.append(f"{what}: exit {r.returncode}: {r.stderr.strip()[-600:]}")
                continue
            printed = {line[len("summarize: wrote "):] for line in r.stdout.splitlines()
                       if line.startswith("summarize: wrote ")}
            for name in (with_fig if figures else without_fig):
                path = os.path.join(out, name)
                if not os.path.isfile(path) or os.path.getsize(path) == 0:
                    failures.append(f"{what}: {name} not written (or empty)")
                elif path not in printed:
                    failures.append(f"{what}: {name} written but its path not printed (stdout: {r.stdout.strip()})")
            md = os.path.join(out, (with_fig if figures else without_fig)[0])
            if os.path.isfile(md):
                text = open(md).read()
                for t in texts:
                    if t not in text:
                        failures.append(f"{what}: {os.path.basename(md)} does not hold '{t}'")
        # Then every committed table (the Markdown: figures are checked above, one table per view), each alone.
        for path in committed_tables():
            out = os.path.join(tmp, "all", os.path.relpath(path, ROOT).replace(os.sep, "_").removesuffix(".json"))
            r = subprocess.run([sys.executable, SUMMARIZE, "--no-figures", path, out], capture_output=True, text=True,
                               cwd=ROOT)
            runs += 1
            if r.returncode != 0 or "summarize: wrote " not in r.stdout:
                failures.append(f"{os.path.relpath(path, ROOT)}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
        # A spec and a JSON file that is no table (a benchmark's output) are refused with exit 2 and what they are.
        for path, said in (("experiments/cylinders/direct.json", "is a spec"),
                           ("results/paper/appendix_c/bench_quadrature.json", "is not a table")):
            r = subprocess.run([sys.executable, SUMMARIZE, "--no-figures", os.path.join(ROOT, path),
                                os.path.join(tmp, "refused")], capture_output=True, text=True, cwd=ROOT)
            runs += 1
            if r.returncode != 2 or said not in r.stderr:
                failures.append(f"{path}: expected exit 2 and '{said}', got exit {r.returncode}: {r.stderr.strip()}")
    for f in failures:
        print("test_summarize_every_kind: " + f, file=sys.stderr)
    print(f"test_summarize_every_kind: {runs} summaries, {len(failures)} failure(s)"
          f"{'' if figures else ' (figures not checked)'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
