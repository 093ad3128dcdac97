#!/usr/bin/env python3
"""Summary of a coarse_continuum_2d table (the coarse continuum Navier-Stokes baseline on the 2D reduced model's
mesh, experiments/kinds/coarse_continuum.cpp).

Usage: python3 experiments/summaries/summarize_coarse_continuum.py TABLE.json OUT_PREFIX
Writes OUT_PREFIX.md: a row per cell with the baseline's errors against the averaged direct SPH, the averaged exact
field and the exact field, the reference's own error (floor), the baseline's amplitude on the mode, the transient,
the cost and the speed-up; for rows without an exact field (the cavity) a second table, the worst over the saved
times by region, the reference's floor and the centre lines against Ghia's, and OUT_PREFIX_fields.png, the finest
such row's fields (field_figure.py) and OUT_PREFIX_transient.png, their errors against the saved time. Every number
is read from the table.
"""
import sys

import field_figure
from summary_util import fmt, get, load_table, pct, pyplot_or_none, spct


def error(row, ref="vs_averaged_direct_sph"):
    return get(row, "errors", ref, "all_nodes", "max_rel")


def main(path, prefix):
    table = load_table(path)
    prov = table["provenance"]
    lines = [f"# {table['experiment']}: the coarse continuum Navier-Stokes baseline\n",
             f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: "
             f"{table['complete']}.\n",
             "The baseline: incompressible Navier-Stokes on the reduced model's coarse mesh (periodic: collocated central "
             "differences, AB2, exact FFT projection; with walls: staggered MAC, AB2, exact sparse projection; "
             "core/continuum/), no closure. Errors: "
             "max over all coarse nodes of |v_baseline - v_ref| (vector norm) in % of the scene's velocity scale; "
             "*peak*: the relative difference of the largest |v| against the averaged direct SPH; *floor*: the "
             "averaged direct SPH against the averaged exact field (the reference's own error). *amplitude*: the "
             "baseline's amplitude on the mode over the averaged exact one (over the exact one where the start and "
             "the force are sampled). *transient*: the error against the averaged direct SPH at the transient's "
             "times. *total s*: the baseline's setup plus run; *speed-up*: the direct SPH's wall time over that.\n",
             "| cell | status | start | force | vs averaged direct SPH | peak | vs averaged exact | vs exact | floor | "
             "amplitude | transient | total s | steps | direct SPH s | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        c = r.get("cost", {})
        if r.get("status") != "ok":
            lines.append(f"| {r['label']} | {r.get('status')}: {(r.get('message') or r.get('error') or '')[:80]} |"
                         + " - |" * 13)
            continue
        solver = get(r, "params", "solver") or {}
        sampled = solver.get("initial") == "sampled" and solver.get("force") == "sampled"
        amplitude = get(r, "errors", "amplitude", "ratio" if sampled else "ratio_to_averaged_analytic")
        transient = ", ".join(pct(get(s, "baseline_vs_averaged_direct_sph", "all_nodes", "max_rel"))
                              for s in r.get("transient", []))
        total = c["wall_seconds"] + c["setup_seconds"]
        lines.append(
            f"| {r['label']} | ok | {solver.get('initial', '-')} | {solver.get('force', '-')} | {pct(error(r))} | "
            f"{spct(get(r, 'errors', 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
            f"{pct(error(r, 'vs_averaged_analytic'))} | {pct(error(r, 'vs_analytic'))} | "
            f"{pct(error(r, 'direct_sph_vs_averaged_analytic'))} | {fmt(amplitude, 5)} | {transient or '-'} | "
            f"{fmt(total)} | {fmt(c.get('steps'))} | {fmt(c.get('direct_sph_wall_seconds'))} | "
            f"{fmt(c.get('speed_up'))} |")
    walled = [r for r in table["rows"] if get(r, "errors", "worst_over_saved_times") is not None]
    drawn = None
    if walled:
        lines += walls_section(walled)
        drawn = field_figure.figure_row(walled)
        if drawn is not None and "averaged_baseline" in drawn["fields"]:
            nx, ny = field_figure.node_count(drawn)
            lines += ["", f"Figure `{prefix.rsplit('/', 1)[-1]}_fields.png`: the cell *{drawn['label']}* ({nx} x {ny} "
                          "coarse nodes, the finest resolution) at the final time: the averaged direct SPH and the "
                          "baseline seen through the averaging in one colour range, their difference in % of the "
                          "direct field's peak."]
        else:
            drawn = None
    if walled:
        lines += ["", f"Figure `{prefix.rsplit('/', 1)[-1]}_transient.png`: the all-node error at each saved time, "
                      "per cell: the baseline's node values and the baseline seen through the averaging against the "
                      "averaged direct SPH, and the floor (the averaged direct SPH against the finer mesh's "
                      "solution seen through the averaging)."]
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")
    plt = pyplot_or_none() if walled else None
    if plt is not None:
        transient_figure(plt, walled, prefix + "_transient.png", table["experiment"])
    if plt is not None and drawn is not None:
        field_figure.draw(plt, drawn, prefix + "_fields.png", f"{table['experiment']}: {drawn['label']}",
                          model="averaged_baseline", model_name="baseline, averaged",
                          difference_name="v_baseline - v_direct")


def transient_figure(plt, rows, path, title):
    """The all-node error against the saved time for each walled row: node values, averaged view, floor."""
    styles = [("baseline_vs_averaged_direct_sph", "-", "baseline nodes"),
              ("averaged_baseline_vs_averaged_direct_sph", "--", "baseline averaged"),
              ("direct_sph_vs_averaged_fine_continuum", ":", "floor (direct vs finer mesh)")]
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    for k, r in enumerate(rows):
        colour = f"C{k}"
        snaps = [s for s in r.get("transient", []) if "time" in s]
        for key, ls, name in styles:
            pts = [(s["time"], get(s, key, "all_nodes", "max_rel")) for s in snaps]
            pts = [(t, 100.0 * e) for t, e in pts if e is not None]
            if pts:
                ax.plot([t for t, _ in pts], [e for _, e in pts], ls, color=colour, marker=".",
                        label=f"{r['label']}: {name}")
    ax.set_xlabel("t (in units of the scene's time scale)")
    ax.set_ylabel("max over all nodes, % of the velocity scale")
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title(title, fontsize=9)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)


def walls_section(rows):
    """The rows of a scene with walls and no exact field (the cavity): the worst over the saved times per region."""
    def worst(r, key, region):
        return pct(get(r, "errors", "worst_over_saved_times", key, region))

    out = ["", "## Without an exact field (the lid-driven cavity)\n",
           "Worst over the transient's saved times, in % of the lid speed, over *all* coarse nodes and over the "
           "*interior* ones (at least 3 eta' from every wall). *baseline*: the node values against the averaged "
           "direct SPH; *averaged*: the baseline seen through the same averaging (the scene's particles carrying its "
           "velocity, the walls theirs); *floor*: the averaged direct SPH against the same solver on a mesh 8x finer "
           "seen through the averaging (the stand-in for the averaged exact field: the reference's own error); "
           "*mesh*: the averaged baseline against that finer one at the final time; *Ghia*: the largest |difference| "
           "of the centre lines from Ghia, Ghia & Shin (1982) at the final time, baseline / finer mesh.\n",
           "| cell | nodes | baseline all | baseline interior | averaged all | averaged interior | floor all | "
           "floor interior | mesh all | mesh interior | Ghia | total s | direct SPH s | speed-up |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        c = r.get("cost", {})
        mesh = get(r, "errors", "averaged_baseline_vs_averaged_fine_continuum") or {}
        ghia = f"{pct(get(r, 'errors', 'centrelines', 'worst'))} / {pct(get(r, 'errors', 'fine_continuum_centrelines', 'worst'))}"
        out.append(
            f"| {r['label']} | {fmt(c.get('coarse_nodes'))} | "
            f"{worst(r, 'baseline_vs_averaged_direct_sph', 'all_nodes')} | "
            f"{worst(r, 'baseline_vs_averaged_direct_sph', 'interior_nodes')} | "
            f"{worst(r, 'averaged_baseline_vs_averaged_direct_sph', 'all_nodes')} | "
            f"{worst(r, 'averaged_baseline_vs_averaged_direct_sph', 'interior_nodes')} | "
            f"{worst(r, 'direct_sph_vs_averaged_fine_continuum', 'all_nodes')} | "
            f"{worst(r, 'direct_sph_vs_averaged_fine_continuum', 'interior_nodes')} | "
            f"{pct(get(mesh, 'all_nodes', 'max_rel'))} | {pct(get(mesh, 'interior_nodes', 'max_rel'))} | {ghia} | "
            f"{fmt(c['wall_seconds'] + c['setup_seconds'])} | {fmt(c.get('direct_sph_wall_seconds'))} | "
            f"{fmt(c.get('speed_up'))} |")
    return out


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
