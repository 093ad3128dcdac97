#!/usr/bin/env python3
"""Summary of a snapshot_closure table (the closure applied to a particle snapshot of another code or run).

Usage: python3 experiments/summaries/summarize_snapshot_closure.py TABLE.json OUT_PREFIX
Writes OUT_PREFIX.md: a row per cell with the closure's shear stress T_xy against the snapshot's exact pair sum
(max and RMS over the channel, the interior and the wall band, in % of the largest exact |T_xy|), the reconstructed
particle velocities' error, and the cost; and, where matplotlib is available, OUT_PREFIX.png: T_xy against y, exact
and closed, for up to six cells. Every number is read from the table.
"""
import sys

from summary_util import figure_label, fmt, get, load_table, pct, pyplot_or_none


def main(path, prefix):
    table = load_table(path)
    prov = table["provenance"]
    lines = [f"# {table.get('experiment', '')}\n", f"{table.get('description', '')}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['date_utc']}; complete: {table.get('complete')}.\n",
             "The closure's T_xy against the exact pair sum (2.13) of the snapshot's particles at the coarse nodes, in "
             "% of the largest exact |T_xy|: max and RMS over the channel, the interior (at least 3 eta' from the walls) "
             "and the wall band; *velocity*: the reconstructed particle velocities' max error in % of their peak.\n",
             "| cell | status | channel max | channel RMS | interior max | wall band max | velocity | particles | "
             "deconvolution s | stress s |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        s = get(r, "errors", "stress_xy") or {}
        c = r.get("cost", {})
        status = r.get("status", "?") + (f": {r['message']}" if r.get("message") else "")
        lines.append(f"| {r.get('label', '')} | {status} | {pct(get(s, 'channel', 'max_rel'))} | "
                     f"{pct(get(s, 'channel', 'l2_rel'))} | {pct(get(s, 'interior', 'max_rel'))} | "
                     f"{pct(get(s, 'wall_band', 'max_rel'))} | {pct(get(r, 'errors', 'particle_velocity_max_rel'))} | "
                     f"{fmt(get(r, 'snapshot', 'particles'))} | {fmt(c.get('deconvolution_seconds'))} | "
                     f"{fmt(c.get('stress_seconds'))} |")
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")
    plt = pyplot_or_none()
    rows = [r for r in table["rows"] if "profile" in r][:6]
    if plt is None or not rows:
        return
    fig, axes = plt.subplots(1, len(rows), figsize=(3.6 * len(rows), 3.6), squeeze=False)
    for ax, r in zip(axes[0], rows):
        p = r["profile"]
        ax.plot(p["y"], p["exact_xy"], "k-", label="exact pair sum")
        ax.plot(p["y"], p["closure_xy"], "rd--", ms=3, label="closure")
        ax.set_title(figure_label(r.get("label", ""), 40), fontsize=8)
        ax.set_xlabel("y")
    axes[0][0].set_ylabel("T_xy")
    axes[0][0].legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
