#!/usr/bin/env python3
"""The reduced model on the cylinder lattice (experiments/cylinders/reduced.json) as a Markdown table and two figures.

Usage: /usr/bin/python3 experiments/cylinders/reduced_summary.py results/cylinders/reduced/reduced.json results/cylinders/reduced
       [--no-figures] [--row LABEL]

Writes OUT/table.md (every row: the error against the averaged direct SPH over all coarse nodes, the nodes outside
and inside the cylinder, the paper's peak metric; the Darcy permeability of the reduced model against the direct
SPH's and the reference; the cost: the fastest reduced run, its spread, the direct run, the speed-up) and, unless
--no-figures, OUT/field.png (the velocity magnitude of the averaged direct SPH and of the reduced model in one colour
range and their difference, the cylinder drawn: experiments/summaries/field_figure.py) for the cell labelled LABEL
(default "a=0.2L n=192" where the table has it, else the ok cell at the finest resolution with the smallest all-node
error), and OUT/front.png (error against reduced wall time of the cells at that cell's n and radius). Prints the
paths written.
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "summaries"))
import field_figure  # noqa: E402  (the summaries' helpers)
from summary_util import get, log_ticks  # noqa: E402


def pct(x):
    return "—" if x is None or (isinstance(x, float) and math.isnan(x)) else "%.3f %%" % (100.0 * x)


def row_line(r):
    e, c = r.get("errors", {}), r.get("cost", {})
    v = e.get("vs_averaged_direct_sph", {})
    p = e.get("permeability", {})
    t = c.get("reduced_timing", {})
    status = r.get("status", "?")
    msg = r.get("error") or get(r, "reduced_model", "message") or ""
    if status != "ok":
        return "| %s | %s: %s | | | | | | | | |" % (r["label"], status, msg[:90])
    return "| %s | %s | %s | %s | %s | %s | %s | %s | %.3g s (spread %.0f %%) | %.0f s | %.0f |" % (
        r["label"], pct(get(v, "all_nodes", "max_rel")), pct(get(v, "fluid_nodes", "max_rel")),
        pct(get(v, "solid_nodes", "max_rel")), pct(v.get("peak_relative_difference")),
        pct(p.get("reduced_vs_direct_sph")), pct(p.get("direct_sph_vs_reference")), pct(p.get("reduced_vs_reference")),
        t.get("min_seconds", float("nan")), 100.0 * t.get("spread", float("nan")),
        c.get("direct_sph_wall_seconds", float("nan")), c.get("speed_up", float("nan")))


def figure_row(rows, label):
    """The row drawn: the one labelled `label` (--row), else "a=0.2L n=192" where the table has it (the committed
    figure's), else the ok row at the finest resolution with the smallest all-node error (field_figure.figure_row)."""
    if label is not None:
        row = field_figure.figure_row(rows, label)
        if row is None:
            raise SystemExit("reduced_summary: no row labelled '%s' with fields; labels: %s"
                             % (label, ", ".join(r.get("label", "") for r in rows)))
        return row
    return field_figure.figure_row(rows, "a=0.2L n=192") or field_figure.figure_row(rows)


def figures(rows, out, label=None):
    """Writes OUT/field.png and OUT/front.png; returns the paths written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    base = figure_row(rows, label)
    if base is None:
        print("reduced_summary: no row has fields: no figure drawn", file=sys.stderr)
        return []
    scene = base["params"]["scene"]
    nx, ny = field_figure.node_count(base)
    written = [os.path.join(out, "field.png")]
    field_figure.draw(plt, base, written[0],
                      "%s, %s: coarse mesh %d x %d (commit %s)" % (scene["name"], base["label"], nx, ny,
                                                                   base["provenance"]["git_commit"][:7]))

    n, a = scene["n"], scene.get("radius_over_length")
    pts = [r for r in rows if r["params"]["scene"]["n"] == n and r.get("status") == "ok"
           and r["params"]["scene"].get("radius_over_length") == a and r.get("errors")
           and get(r, "cost", "reduced_timing", "min_seconds") is not None]
    if not pts:
        return written
    fig, ax = plt.subplots(figsize=(9, 4.5))
    # Each point at its fastest run, the bar to its slowest (the range of the repeats); points within 30 % in time
    # and 20 % in error share one label (they are not resolved from each other by the timing).
    clusters = []
    for k, r in enumerate(pts, 1):
        err = 100 * r["errors"]["vs_averaged_direct_sph"]["all_nodes"]["max_rel"]
        timing = r["cost"]["reduced_timing"]
        t, t_max = timing["min_seconds"], timing["max_seconds"]
        ax.errorbar([t], [err], xerr=[[0], [t_max - t]], fmt="o", color="C0", ecolor="0.6", elinewidth=1, capsize=2)
        for c in clusters:
            if abs(np.log(t / c["t"])) < np.log(1.3) and abs(np.log(err / c["err"])) < np.log(1.2):
                c["labels"].append(str(k))
                break
        else:
            clusters.append({"t": t, "err": err, "labels": [str(k)]})
    ax.set_xscale("log")
    ax.set_yscale("log")
    log_ticks(ax)
    for c in clusters:
        ax.annotate(", ".join(c["labels"]), (c["t"], c["err"]), textcoords="offset points", xytext=(4, 4), fontsize=8)
    direct = pts[0]["cost"]["direct_sph_wall_seconds"]
    ax.axvline(direct / 1e3, color="0.5", ls="--", lw=1)
    ax.text(direct / 1e3, ax.get_ylim()[1], " 1/1000 of the direct SPH", va="top", fontsize=8, color="0.4")
    ax.set_xlabel("reduced run, fastest of the repeats (s; bar: to the slowest)")
    ax.set_ylabel("max error over all coarse nodes (% of peak)")
    ax.set_title("a = %g L, n = %d: error against cost" % (a, n), fontsize=10)
    key = "\n".join("%d: %s" % (k, r["label"].replace(base["label"], "").strip() or "base (Tikhonov 1e-6)")
                    for k, r in enumerate(pts, 1))
    ax.text(1.02, 0.5, key, transform=ax.transAxes, va="center", fontsize=8)
    fig.tight_layout()
    written.append(os.path.join(out, "front.png"))
    fig.savefig(written[-1], dpi=110)
    plt.close(fig)
    return written


def main():
    argv, label = sys.argv[1:], None
    if "--row" in argv:
        k = argv.index("--row")
        if k + 1 >= len(argv):
            raise SystemExit("reduced_summary: --row needs a cell label")
        label = argv[k + 1]
        argv = argv[:k] + argv[k + 2:]
    args = [a for a in argv if not a.startswith("--")]
    table = json.load(open(args[0]))
    out = args[1]
    rows = table["rows"]
    commits = sorted({r["provenance"]["git_commit"][:12] + (" (dirty)" if r["provenance"].get("dirty") else "")
                      for r in rows})
    lines = ["# Reduced model on the cylinder lattice", "",
             "Generated by `experiments/cylinders/reduced_summary.py %s %s` from the rows of that table; rows "
             "computed at commit(s) %s." % (args[0], out, ", ".join(commits)), "",
             "Errors against the averaged direct SPH of the same box at steady state, max |v̄_red − v̄_direct| over "
             "the nodes / the peak |v̄_direct|; peak: the paper's metric (max|v̄_red| − max|v̄_direct|) / max|v̄_direct|. "
             "k: the Darcy permeability μ⟨u⟩/(ρg). Time: the fastest of the repeated reduced runs (setup + solve) "
             "with its spread (median − min)/min; speed-up: the direct SPH's wall time over that.", "",
             "| cell | all nodes | outside cylinder | inside | peak | k red/direct − 1 | k direct/ref − 1 | "
             "k red/ref − 1 | reduced run | direct SPH | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    lines += [row_line(r) for r in rows]
    os.makedirs(out, exist_ok=True)
    written = [os.path.join(out, "table.md")]
    open(written[0], "w").write("\n".join(lines) + "\n")
    if "--no-figures" not in argv:
        written += figures(rows, out, label)
    for path in written:
        print("reduced_summary: wrote %s" % path)


if __name__ == "__main__":
    main()
