#!/usr/bin/env python3
"""The reduced model on the cylinder lattice (experiments/cylinders/reduced.json) as a Markdown table and two figures.

Usage: /usr/bin/python3 experiments/cylinders/reduced_summary.py results/cylinders/reduced/reduced.json results/cylinders/reduced
       [--no-figures]

Writes OUT/table.md (every row: the error against the averaged direct SPH over all coarse nodes, the nodes outside
and inside the cylinder, the paper's peak metric; the Darcy permeability of the reduced model against the direct
SPH's and the reference; the cost: the fastest reduced run, its spread, the direct run, the speed-up) and, unless
--no-figures, OUT/field.png (the velocity magnitude of the averaged direct SPH and of the reduced model and their
difference at a = 0.2 L, n = 192, the cylinder drawn) and OUT/front.png (error against reduced wall time at n = 192).
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "summaries"))
from summary_util import get  # noqa: E402  (the summaries' helpers)


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


def figures(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    base = next(r for r in rows if r["label"] == "a=0.2L n=192" and "fields" in r)
    f = base["fields"]
    x, y = np.array(f["x"]), np.array(f["y"])
    nx, ny = len(x), len(y)
    red = np.hypot(np.array(f["reduced"]["vx"]), np.array(f["reduced"]["vy"])).reshape(ny, nx)
    dvx = np.array(f["reduced"]["vx"]) - np.array(f["direct_average"]["vx"])
    dvy = np.array(f["reduced"]["vy"]) - np.array(f["direct_average"]["vy"])
    dirc = np.hypot(np.array(f["direct_average"]["vx"]), np.array(f["direct_average"]["vy"])).reshape(ny, nx)
    scale = dirc.max()
    diff = np.hypot(dvx, dvy).reshape(ny, nx) / scale
    a = base["params"]["scene"]["radius_over_length"] * base["params"]["scene"].get("l", 1.0)
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    panels = [(dirc / scale, "averaged direct SPH |v̄| / peak"), (red / scale, "reduced model |v̄| / peak"),
              (diff, "|v̄_red − v̄_direct| / peak")]
    for ax, (field, title) in zip(axes, panels):
        m = ax.pcolormesh(x, y, field, shading="nearest", cmap="viridis")
        fig.colorbar(m, ax=ax, format="%.1e" if field is diff else "%.2f")
        ax.add_patch(plt.Circle((0.5, 0.5), a, fill=False, color="w", lw=1.5))
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("x / L")
    axes[0].set_ylabel("y / L")
    fig.suptitle("Stokes flow through a square lattice of cylinders, a = 0.2 L, n = 192, coarse mesh 16 x 16 "
                 "(commit %s)" % base["provenance"]["git_commit"][:7], fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "field.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(9, 4.5))
    pts = [r for r in rows if r["params"]["scene"]["n"] == 192 and r.get("status") == "ok"
           and r["params"]["scene"]["radius_over_length"] == 0.2]
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
    for c in clusters:
        ax.annotate(", ".join(c["labels"]), (c["t"], c["err"]), textcoords="offset points", xytext=(4, 4), fontsize=8)
    direct = pts[0]["cost"]["direct_sph_wall_seconds"]
    ax.axvline(direct / 1e3, color="0.5", ls="--", lw=1)
    ax.text(direct / 1e3, ax.get_ylim()[1], " 1/1000 of the direct SPH", va="top", fontsize=8, color="0.4")
    ax.set_xlabel("reduced run, fastest of the repeats (s; bar: to the slowest)")
    ax.set_ylabel("max error over all coarse nodes (% of peak)")
    ax.set_title("a = 0.2 L, n = 192: error against cost", fontsize=10)
    key = "\n".join("%d: %s" % (k, r["label"].replace("a=0.2L n=192", "").strip() or "base (Tikhonov 1e-6)")
                    for k, r in enumerate(pts, 1))
    ax.text(1.02, 0.5, key, transform=ax.transAxes, va="center", fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "front.png"), dpi=110)
    plt.close(fig)


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
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
    open(os.path.join(out, "table.md"), "w").write("\n".join(lines) + "\n")
    if "--no-figures" not in sys.argv:
        figures(rows, out)


if __name__ == "__main__":
    main()
