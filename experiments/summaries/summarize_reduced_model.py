#!/usr/bin/env python3
"""Markdown table (and, where matplotlib is available, a PNG of the profiles) for a reduced_model table.

Usage: python3 experiments/summaries/summarize_reduced_model.py TABLE.json OUT_PREFIX
writes OUT_PREFIX.md and OUT_PREFIX.png. Every number is read from the table.
"""
import json
import sys

from summary_util import fmt, get, load_table, pyplot_or_none


def main(path, prefix):
    table = load_table(path)
    prov = table["provenance"]
    lines = [f"# {table['experiment']}\n", f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: {table['complete']}.\n",
             "Errors at the coarse nodes, relative to the analytic peak; *interior*: nodes at least 3 eta' from the walls; "
             "*peak*: the paper's metric (max v_reduced - max v_ref) / max v_ref. *reduced s*: the reduced model's run; "
             "*setup s*: building its operators, factorizations and quadrature tables. Speed-up: direct SPH wall time / "
             "(setup + run) of the reduced model; the direct SPH's time is that of the run that computed it, which the "
             "reference store may have kept from an earlier run (each row records where its reference came from).\n",
             "| cell | status | vs analytic max | interior | peak | vs avg analytic max | vs avg direct SPH max | peak vs direct | steps | dt | reduced s | setup s | direct s | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        e, c = r.get("errors", {}), r.get("cost", {})
        lines.append(
            f"| {r['label']} | {r['status']} | {fmt(get(e, 'vs_analytic', 'all', 'max_rel'))} | "
            f"{fmt(get(e, 'vs_analytic', 'interior', 'max_rel'))} | {fmt(get(e, 'vs_analytic', 'peak_relative_difference'))} | "
            f"{fmt(get(e, 'vs_averaged_analytic', 'all', 'max_rel'))} | {fmt(get(e, 'vs_averaged_direct_sph', 'all', 'max_rel'))} | "
            f"{fmt(get(e, 'vs_averaged_direct_sph', 'peak_relative_difference'))} | {fmt(c.get('steps'))} | {fmt(c.get('dt'))} | "
            f"{fmt(c.get('wall_seconds'))} | {fmt(c.get('setup_seconds'))} | {fmt(c.get('direct_sph_wall_seconds'))} | {fmt(c.get('speed_up'))} |")
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")
    plt = pyplot_or_none()
    if plt is None:
        return
    rows = [r for r in table["rows"] if "profile" in r]
    ncols = min(4, max(1, len(rows)))
    nrows = (len(rows) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(3.4 * ncols, 3.0 * nrows), squeeze=False)
    for ax in axes.flat[len(rows):]:
        ax.axis("off")
    for ax, r in zip(axes.flat, rows):
        p = r["profile"]
        ax.plot(p["y"], p["analytic"], "k-", label="analytic")
        ax.plot(p["y"], p["analytic_average"], "k:", label="averaged analytic")
        if "direct_average" in p:
            ax.plot(p["y"], p["direct_average"], "bs", mfc="none", label="averaged direct SPH")
        ax.plot(p["y"], p["reduced"], "rd--", label="reduced model")
        ax.set_title(r["label"], fontsize=7)
        ax.set_xlabel("y")
    for row in axes:
        row[0].set_ylabel("v_x")
    axes[0][0].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
