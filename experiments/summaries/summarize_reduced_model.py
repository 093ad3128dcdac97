#!/usr/bin/env python3
"""Markdown table (and, where matplotlib is available, a PNG of the profiles) for a reduced_model table.

Usage: python3 experiments/summaries/summarize_reduced_model.py TABLE.json OUT_PREFIX
writes OUT_PREFIX.md and OUT_PREFIX.png. Every number is read from the table.
"""
import json
import sys

from summary_util import figure_label, fmt, get, load_table, log_ticks, noisy_note, pct, pyplot_or_none, speed_up_cell, spct


def main(path, prefix):
    table = load_table(path)
    prov = table["provenance"]
    lines = [f"# {table['experiment']}\n", f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: {table['complete']}.\n",
             "Max errors over the coarse nodes, in % of the analytic peak: *all nodes* (every node the model reports, "
             "wall-surface nodes included: the headline), *fluid nodes* (without the wall-surface nodes), *interior* "
             "(nodes at least 3 eta' from the walls); *peak*: the paper's metric (max v_reduced - max v_ref) / max v_ref. "
             "*reduced s*: the reduced model's run; *setup s*: building its operators, factorizations and quadrature "
             "tables (the fastest of *runs* repeated runs where the row records them; *spread*: (median - min) / min of "
             "setup + run). Speed-up: direct SPH wall time / the fastest (setup + run) of the reduced model; the direct "
             "SPH's time is that of the run that computed it, which the reference store may have kept from an earlier "
             "run (each row records where its reference came from).\n",
             "| cell | status | vs analytic, all nodes | fluid nodes | interior | peak | vs avg analytic, all nodes | vs avg direct SPH, all nodes | fluid nodes | peak vs direct | steps | dt | reduced s | setup s | runs | spread | direct s | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        e, c = r.get("errors", {}), r.get("cost", {})
        timing = c.get("reduced_timing") or {}
        lines.append(
            f"| {r['label']} | {r['status']} | {pct(get(e, 'vs_analytic', 'all_nodes', 'max_rel'))} | "
            f"{pct(get(e, 'vs_analytic', 'fluid_nodes', 'max_rel'))} | "
            f"{pct(get(e, 'vs_analytic', 'interior', 'max_rel'))} | {spct(get(e, 'vs_analytic', 'peak_relative_difference'))} | "
            f"{pct(get(e, 'vs_averaged_analytic', 'all_nodes', 'max_rel'))} | {pct(get(e, 'vs_averaged_direct_sph', 'all_nodes', 'max_rel'))} | "
            f"{pct(get(e, 'vs_averaged_direct_sph', 'fluid_nodes', 'max_rel'))} | "
            f"{spct(get(e, 'vs_averaged_direct_sph', 'peak_relative_difference'))} | {fmt(c.get('steps'))} | {fmt(c.get('dt'))} | "
            f"{fmt(c.get('wall_seconds'))} | {fmt(c.get('setup_seconds'))} | {fmt(timing.get('repeats', 1))} | "
            f"{pct(timing.get('spread'))} | {fmt(c.get('direct_sph_wall_seconds'))} | "
            f"{speed_up_cell(c.get('speed_up'), timing.get('spread'))} |")
    lines += noisy_note(lines)
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")
    plt = pyplot_or_none()
    if plt is None:
        return
    rows = [r for r in table["rows"] if "profile" in r]
    if not rows:  # every row failed, or the rows are a 2D model's (summarize.py routes those to their own views)
        print(f"summary: no row of {path} has a profile: no figure drawn", file=sys.stderr)
        return
    ncols = min(4, max(1, len(rows)))
    nrows = (len(rows) + ncols - 1) // ncols
    # Each cell: its profiles above, |v_reduced - v_ref| / peak against y (log scale) below.
    fig, axes = plt.subplots(2 * nrows, ncols, figsize=(3.4 * ncols, 4.6 * nrows), squeeze=False,
                             gridspec_kw={"height_ratios": [2, 1] * nrows})
    for k in range(len(rows), nrows * ncols):
        axes[2 * (k // ncols)][k % ncols].axis("off")
        axes[2 * (k // ncols) + 1][k % ncols].axis("off")
    for k, r in enumerate(rows):
        ax, ex = axes[2 * (k // ncols)][k % ncols], axes[2 * (k // ncols) + 1][k % ncols]
        p = r["profile"]
        smooth = parabola_through(p["y"], p["analytic"])
        if smooth is not None:  # the nodes lie on one parabola ((5.15)): drawn smooth between them
            ax.plot(smooth[0], smooth[1], "k-", lw=0.9, label="analytic")
        else:  # known at the nodes only (periodic force, layers): not interpolated
            ax.plot(p["y"], p["analytic"], "k.", ms=3, label="analytic (at the nodes)")
        smooth = parabola_through(p["y"], p["analytic_average"])
        if smooth is not None:
            ax.plot(smooth[0], smooth[1], "k:", label="averaged analytic")
        else:
            ax.plot(p["y"], p["analytic_average"], "k+", ms=4, label="averaged analytic (at the nodes)")
        if "direct_average" in p:
            ax.plot(p["y"], p["direct_average"], "bs", mfc="none", label="averaged direct SPH")
        ax.plot(p["y"], p["reduced"], "rd--", label="reduced model")
        ax.set_title(figure_label(r["label"], 45), fontsize=7)
        ax.set_ylabel("v_x" if k % ncols == 0 else "")
        scale = max(abs(v) for v in p["analytic"]) or 1.0
        ref = p.get("direct_average", p["analytic_average"])
        diff = [max(abs(a - b) / scale, 1e-12) for a, b in zip(p["reduced"], ref)]
        ex.semilogy(p["y"], [100.0 * d for d in diff], "r.-", lw=0.8)
        log_ticks(ex, "y")
        ex.set_xlabel("y")
        ex.set_ylabel(("|v_red - v_direct| / peak (%)" if "direct_average" in p
                       else "|v_red - v_avg. analytic| / peak (%)") if k % ncols == 0 else "", fontsize=6)
    # One legend for every panel, below them (off the data).
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.tight_layout(rect=(0, 0.06 / nrows, 1, 1))
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=7, frameon=False)
    fig.savefig(prefix + ".png", dpi=110)


def parabola_through(y, v):
    """(ys, vs) on a fine grid when the points (y, v) lie on one parabola to 1e-9 of their peak (the uniform-force
    channel's (5.15)), else None."""
    import numpy as np
    y, v = np.asarray(y, dtype=float), np.asarray(v, dtype=float)
    if len(y) < 4:
        return None
    c = np.polyfit(y, v, 2)
    scale = np.abs(v).max() or 1.0
    if np.abs(np.polyval(c, y) - v).max() > 1e-9 * scale:
        return None
    ys = np.linspace(y.min(), y.max(), 400)
    return ys, np.polyval(c, ys)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
