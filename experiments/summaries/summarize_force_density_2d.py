#!/usr/bin/env python3
"""Summary of the 2D force-density reduced model with solids: a reduced_model table whose rows ran the model
force_density_2d (the default on the cylinder lattice and the cylinder channel; walled channels as one column), or an
older reduced_model_2d_force_density table.

Usage: python3 experiments/summaries/summarize_force_density_2d.py TABLE.json OUT_PREFIX
Writes OUT_PREFIX.md: a row per cell with the error against the averaged direct SPH (all coarse nodes, outside and
inside the solid, the paper's peak metric), the Darcy permeability where the scene has one (the reduced model's,
the direct SPH's, the reference's and their relative differences), the reduced run's time and spread, the direct
SPH's time and the speed-up; every error in % of the averaged direct SPH's peak speed. Where matplotlib is
available, OUT_PREFIX_fields.png: one cell's fields (field_figure.py; the cell named in the Markdown).
Every number is read from the table.
"""
import sys

import field_figure
from summary_util import fmt, get, load_table, noisy_note, pct, pyplot_or_none, speed_up_cell, spct


def row_line(r, with_k):
    e, c = r.get("errors", {}), r.get("cost", {})
    v = e.get("vs_averaged_direct_sph", {})
    t = c.get("reduced_timing") or {}
    status = r.get("status", "?")
    cells = [r.get("label", ""), status]
    if status == "error" or not r.get("errors"):
        msg = (r.get("error") or get(r, "reduced_model", "message") or r.get("message") or "").replace("|", "/")
        return "| " + " | ".join(cells + [msg[:120]]) + " |"
    cells += [pct(get(v, "all_nodes", "max_rel")), pct(get(v, "fluid_nodes", "max_rel")),
              pct(get(v, "solid_nodes", "max_rel")), spct(v.get("peak_relative_difference"))]
    if with_k:
        p = e.get("permeability", {})
        cells += [fmt(p.get("reduced"), 4), fmt(p.get("direct_sph"), 4), fmt(p.get("reference"), 4),
                  spct(p.get("reduced_vs_direct_sph")), spct(p.get("direct_sph_vs_reference")),
                  spct(p.get("reduced_vs_reference"))]
    t_min = t.get("min_seconds", c.get("wall_seconds"))
    cells += [f"{fmt(t_min)} s" if t_min is not None else "-", pct(t.get("spread")), fmt(t.get("repeats")),
              f"{fmt(c.get('direct_sph_wall_seconds'))} s" if c.get("direct_sph_wall_seconds") is not None else "-",
              speed_up_cell(c.get("speed_up"), t.get("spread"))]
    return "| " + " | ".join(cells) + " |"


def main(path, prefix):
    table = load_table(path)
    prov = table["provenance"]
    rows = table["rows"]
    with_k = any("permeability" in (r.get("errors") or {}) for r in rows)
    scenes = sorted({str(get(r, "params", "scene", "name")) for r in rows})
    lines = [f"# {table.get('experiment', '')}\n", f"{table.get('description', '')}\n",
             f"From `{path}` (the 2D force-density model; scene(s): {', '.join(scenes)}); commit `{prov['git_commit']}`, "
             f"{prov['compiler']}, {prov['build_type']}, {prov['threads']} thread(s), {prov['date_utc']}; "
             f"complete: {table.get('complete')}.\n",
             "Errors against the averaged direct SPH of the same box, max |v_reduced - v_direct| over the coarse nodes "
             "in % of the averaged direct SPH's peak speed: *all nodes* (the headline), *outside solid*, *in solid* "
             "(the nodes inside a solid, by the scene's geometry); *peak*: the paper's metric "
             "(max|v_reduced| - max|v_direct|) / max|v_direct|. "
             + ("*k*: the Darcy permeability mu<u>/(rho g) in units of L^2, of the reduced model, of the direct SPH and "
                "the scene's reference (a Stokes solve), with their relative differences in %. " if with_k else
                "The scene has no permeability. ")
             + "*reduced run*: the fastest of *runs* repeated reduced runs (setup and solve), *spread* "
               "(median - min) / min; speed-up: the direct SPH's wall time over the fastest reduced run.\n"]
    head = ["cell", "status", "all nodes", "outside solid", "in solid", "peak"]
    if with_k:
        head += ["k reduced", "k direct SPH", "k reference", "k red vs direct", "k direct vs ref", "k red vs ref"]
    head += ["reduced run", "spread", "runs", "direct SPH", "speed-up"]
    lines += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += [row_line(r, with_k) for r in rows]
    lines += noisy_note(lines)
    drawn = field_figure.figure_row(rows)
    figure = prefix + "_fields.png"
    if drawn is not None:
        nx, ny = field_figure.node_count(drawn)
        lines += ["", f"Figure `{figure.rsplit('/', 1)[-1]}`: the cell *{drawn['label']}* ({nx} x {ny} coarse nodes; "
                      "the ok cell at the finest resolution with the smallest all-node error): the averaged direct SPH "
                      "and the reduced model in one colour range, their difference in % of the peak, the solid drawn."]
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")
    plt = pyplot_or_none()
    if plt is None or drawn is None:
        return
    field_figure.draw(plt, drawn, figure, f"{table.get('experiment', '')}: {drawn['label']}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
