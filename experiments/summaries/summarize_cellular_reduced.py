#!/usr/bin/env python3
"""Summary of a reduced_model_2d table (the two-dimensional reduced model on a cellular mode: the cellular flow or the
Taylor-Green vortex; or in the lid-driven cavity, which has no exact field).

Usage: python3 experiments/summaries/summarize_cellular_reduced.py TABLE.json OUT_PREFIX
A table named pareto_*: the speed-against-error front (summarize_pareto.py) in OUT_PREFIX.md / .png. Otherwise:
OUT_PREFIX.md, a row per cell (errors, the closure's amplitude against the Landweber prediction, the transient,
the cost and the speed-up; in the cavity the errors over all and the interior nodes at the final and the worst saved
time). Both draw, where matplotlib is available, OUT_PREFIX_fields.png: the velocity field of
the averaged direct SPH and of the reduced model side by side, and their difference, for the most accurate cell
at the finest resolution. Every number is read from the table.
"""
import os
import sys

from summary_util import fmt, get, load_table, pct, pyplot_or_none, spct

import summarize_pareto


def error(row, ref="vs_averaged_direct_sph"):
    return get(row, "errors", ref, "all_nodes", "max_rel")


def best_row(rows):
    ok = [r for r in rows if r.get("status") == "ok" and error(r) is not None and "fields" in r]
    if not ok:
        return None
    finest = max(r["params"]["scene"]["n"] for r in ok)
    return min((r for r in ok if r["params"]["scene"]["n"] == finest), key=error)


def fields_figure(row, path, title):
    plt = pyplot_or_none()
    if plt is None or row is None or "direct_average" not in row["fields"]:
        return False
    import numpy as np
    f = row["fields"]
    x, y = np.array(f["x"]), np.array(f["y"])
    shape = (len(y), len(x))  # flat j * nx + i: rows are y

    def grid(name, comp):
        return np.array(f[name][comp]).reshape(shape)

    dx, dy = grid("direct_average", "vx"), grid("direct_average", "vy")
    rx, ry = grid("reduced", "vx"), grid("reduced", "vy")
    speed_max = max(np.hypot(dx, dy).max(), np.hypot(rx, ry).max())
    diff = np.hypot(rx - dx, ry - dy)
    extent = [x[0] - 0.5 * (x[1] - x[0]), x[-1] + 0.5 * (x[1] - x[0]), y[0] - 0.5 * (y[1] - y[0]), y[-1] + 0.5 * (y[1] - y[0])]
    fig, axes = plt.subplots(1, 3, figsize=(12.0, 4.0))
    for ax, (u, v, name) in zip(axes[:2], [(dx, dy, "averaged direct SPH"), (rx, ry, "reduced model")]):
        im = ax.imshow(np.hypot(u, v), origin="lower", extent=extent, vmin=0.0, vmax=speed_max, cmap="viridis")
        ax.quiver(x, y, u, v, color="w", angles="xy", scale_units="xy", scale=speed_max / (0.9 * (x[1] - x[0])), width=0.005)
        ax.set_title(f"{name}: |v|", fontsize=9)
        fig.colorbar(im, ax=ax, fraction=0.046)
    im = axes[2].imshow(diff / speed_max, origin="lower", extent=extent, cmap="magma")
    axes[2].set_title("|v_reduced - v_direct| / max|v|", fontsize=9)
    fig.colorbar(im, ax=axes[2], fraction=0.046)
    for ax in axes:
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_aspect("equal")
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    return True


def cell_table(table, path):
    prov = table["provenance"]
    lines = [f"# {table['experiment']}: the two-dimensional reduced model on a cellular mode\n",
             f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: "
             f"{table['complete']}.\n",
             "Errors: max over all coarse nodes of |v_reduced - v_ref| (vector norm) in % of the scene's analytic peak A "
             "(the steady amplitude of the cellular flow, the initial U of the Taylor-Green vortex); *peak*: the "
             "paper's metric, the relative difference of the largest |v| against the same reference; *floor*: the "
             "averaged direct SPH against the averaged exact field (the reference's own error). *amplitude*: the "
             "reduced field's amplitude on the mode over A, with the Landweber prediction e/(1-(1-e)^(n+1)) where it "
             "applies (e: the kernel's symbol at the mode). *transient*: the error against the averaged direct SPH at "
             "the spec's saved times (transient.t_over_tau, in units of the decay time tau), in % of A; *own peak*: the "
             "largest of the same errors in % of the averaged direct field's own peak at each time (a decaying flow), "
             "where the table has it. *total s*: the reduced model's setup plus run; *speed-up*: the direct SPH's wall "
             "time over that.\n",
             "| cell | status | vs averaged direct SPH | peak | vs averaged exact | floor | amplitude | prediction | "
             "transient | own peak | total s | steps | bond weights | direct SPH s | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        c = r.get("cost", {})
        if r.get("status") != "ok":
            lines.append(f"| {r['label']} | {r.get('status')}: {(r.get('error') or '')[:80]} |" + " - |" * 13)
            continue
        transient = ", ".join(pct(get(s, "reduced_vs_averaged_direct_sph", "all_nodes", "max_rel"))
                              for s in r.get("transient", []))
        own = [get(s, "reduced_vs_averaged_direct_sph_at_its_peak", "all_nodes", "max_rel") for s in r.get("transient", [])]
        own = [x for x in own if x is not None]
        total = c["wall_seconds"] + c["setup_seconds"]
        lines.append(
            f"| {r['label']} | ok | {pct(error(r))} | "
            f"{spct(get(r, 'errors', 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
            f"{pct(error(r, 'vs_averaged_analytic'))} | {pct(error(r, 'direct_sph_vs_averaged_analytic'))} | "
            f"{fmt(get(r, 'errors', 'amplitude', 'ratio'), 5)} | "
            f"{fmt(get(r, 'errors', 'amplitude', 'landweber_prediction'), 5)} | {transient or '-'} | "
            f"{pct(max(own)) if own else '-'} | {fmt(total)} | "
            f"{fmt(c.get('steps'))} | {fmt(c.get('bond_weights'))} | {fmt(c.get('direct_sph_wall_seconds'))} | "
            f"{fmt(c.get('speed_up'))} |")
    return lines + transient_table(table["rows"])


def cavity_table(table, path):
    """The cavity's rows: no exact field, so the errors against the averaged direct SPH alone, over all nodes and the
    interior ones (>= 3 eta' from the walls), at the final time and the worst over the saved times."""
    prov = table["provenance"]
    lines = [f"# {table['experiment']}: the two-dimensional reduced model in the lid-driven cavity\n",
             f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: "
             f"{table['complete']}.\n",
             "Errors: max over the coarse nodes of |v_reduced - v_ref| (vector norm) in % of the lid speed U, against "
             "the averaged direct SPH, over all nodes and over the interior ones (>= 3 eta' from every wall); *final*: "
             "at the final time; *worst*: the largest over the saved times; *peak*: the paper's metric, the relative "
             "difference of the largest |v| at the final time. *total s*: the reduced model's setup plus run (the "
             "minimum over its repeats); *speed-up*: the direct SPH's wall time over that.\n",
             "| cell | status | all, final | interior, final | all, worst | interior, worst | peak | total s | steps | "
             "pair forces / step | direct SPH s | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        if r.get("status") != "ok":
            lines.append(f"| {r['label']} | {r.get('status')}: {(r.get('error') or '')[:80]} |" + " - |" * 10)
            continue
        c = r.get("cost", {})

        def worst(region):
            values = [get(s, "reduced_vs_averaged_direct_sph", region, "max_rel") for s in r.get("transient", [])]
            values = [x for x in values if x is not None]
            return pct(max(values)) if values else "-"

        lines.append(
            f"| {r['label']} | ok | {pct(error(r))} | "
            f"{pct(get(r, 'errors', 'vs_averaged_direct_sph', 'interior_nodes', 'max_rel'))} | {worst('all_nodes')} | "
            f"{worst('interior_nodes')} | {spct(get(r, 'errors', 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
            f"{fmt(c['wall_seconds'] + c['setup_seconds'])} | {fmt(c.get('steps'))} | "
            f"{fmt(c.get('pair_forces_per_step'))} | {fmt(c.get('direct_sph_wall_seconds'))} | {fmt(c.get('speed_up'))} |")
    rows = [r for r in table["rows"] if r.get("status") == "ok" and r.get("transient")]
    if rows:
        lines += ["\nOver the transient (% of U), at the saved times t (in L/U): all nodes / interior nodes.\n",
                  "| cell | t | all nodes | interior nodes |", "|---|---|---|---|"]
        for r in rows:
            times = ", ".join(fmt(s.get("time"), 3) for s in r["transient"])
            cols = [", ".join(pct(get(s, "reduced_vs_averaged_direct_sph", region, "max_rel")) for s in r["transient"])
                    for region in ("all_nodes", "interior_nodes")]
            lines.append(f"| {r['label']} | {times} | " + " | ".join(cols) + " |")
    return lines


def transient_table(rows):
    """Over the saved times, the reduced model against the averaged direct SPH and against the averaged exact
    field, beside the reference's own error (its floor) at the same times: where the floor is of the size of the
    first, the reference, not the model, sets the error against it."""
    rows = [r for r in rows if r.get("status") == "ok" and r.get("transient")]
    if not rows:
        return []
    lines = ["\nOver the transient, at the saved times (% of A): the reduced model against the averaged direct SPH "
             "and against the averaged exact field, and the *floor* (the averaged direct SPH against the averaged "
             "exact field) at the same times; *max*: the largest over the times.\n",
             "| cell | t / tau | vs averaged direct SPH | max | vs averaged exact | max | floor | max |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        times = ", ".join(fmt(s.get("t_over_tau"), 3) for s in r["transient"])
        cols = []
        for key in ("reduced_vs_averaged_direct_sph", "reduced_vs_averaged_analytic", "direct_sph_vs_averaged_analytic"):
            values = [get(s, key, "all_nodes", "max_rel") for s in r["transient"]]
            present = [x for x in values if x is not None]
            cols.append(", ".join(pct(x) for x in values) if present else "-")
            cols.append(pct(max(present)) if present else "-")
        lines.append(f"| {r['label']} | {times} | " + " | ".join(cols) + " |")
    return lines


def main(path, prefix):
    table = load_table(path)
    if table["experiment"].startswith("pareto_"):
        summarize_pareto.main(path, prefix)
        lines = open(prefix + ".md").read().rstrip("\n").split("\n")
    elif table["rows"] and get(table["rows"][0], "params", "scene", "name") == "lid-driven-cavity":
        lines = cavity_table(table, path)
    else:
        lines = cell_table(table, path)
    best = best_row(table["rows"])
    if best is not None:
        figure = prefix + "_fields.png"
        fields_figure(best, figure, f"{table['experiment']}: {best['label']}")
        # The text does not depend on whether matplotlib drew the figure (the summaries are checked byte for byte).
        lines.append(f"\nFields (`{os.path.basename(figure)}`, drawn where matplotlib is available): the velocity "
                     "of the averaged direct SPH and of the reduced model side by side, and their difference, for the "
                     f"most accurate cell at the finest resolution, {best['label']}, error {pct(error(best))} against "
                     "the averaged direct SPH.")
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(*sys.argv[1:3])
