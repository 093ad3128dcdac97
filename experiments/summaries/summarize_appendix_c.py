#!/usr/bin/env python3
"""Markdown summary of the Appendix C table (results/paper/appendix_c/appendix_c.json).

Usage: python3 experiments/summaries/summarize_appendix_c.py TABLE.json > summary.md
Every number printed is read from the table. Errors: max |T_coarse - T_exact| of T_int,xy over the nodes of a
region, in % of max |T_exact,xy| in the channel. Observed order: least-squares slope of log(error) against
log(coarse spacing) over the x-integrated rows with stride_y >= 2 (stride 1 is the exact sum, round-off).
"""
import json
import math
import sys

from summary_util import dirty_mark, fmt, load_table, pct, slope


def main(path):
    table = load_table(path)
    prov = table["provenance"]
    print(f"# {table['experiment']}: coarse stress quadrature against the exact pair sum (Appendix C)\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
          f"{prov['threads']} thread(s), {prov['date_utc']}, command `{prov['command']}`. "
          f"Table complete: {table['complete']}.\n")
    print("Errors in % of max |T_exact,xy| in the channel; *interior*: nodes >= 3 eta' from the walls; *band*: "
          "channel nodes nearer; *walls*: nodes inside the walls. *dc/eta'*: R-grid spacing along y over eta'. "
          "*N/N_C paper*: s_x s_y (2D grid) or s_y^2 (x-integrated column, the square grid of the same y-spacing); "
          "*N/N_C strip*: particles of this strip per R-node (fine wall bands add R-rows). *wall band*: coarse = plain (5.27); "
          "fine = R-rows within one SPH support of a wall surface at lattice resolution. Times: one evaluate(), fastest of the repeats.\n")
    rows = sorted(table["rows"], key=lambda r: (r["params"]["evaluation"]["velocity"], r["params"]["quadrature"]["wall_band"],
                                                r["params"]["quadrature"]["stride_x"] > 0,
                                                r["params"]["quadrature"]["stride_y"], r["params"]["quadrature"]["stride_x"]))
    print("| velocity | wall band | R-grid | s_x x s_y | dc/eta' | N/N_C paper | N/N_C strip | channel max | interior max | band max | walls max | exact ms | coarse ms | speed-up |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    series = {}
    for r in rows:
        p, e, c, d = r["params"], r.get("errors", {}), r.get("cost", {}), r.get("derived", {})
        if r.get("status") != "ok":
            print(f"| {p['evaluation']['velocity']} | failed: {r.get('error', r.get('status'))} |||||||||||")
            continue
        sx, sy = p["quadrature"]["stride_x"], p["quadrature"]["stride_y"]
        grid = "x-integrated column" if sx == 0 else f"2D, n_x = {p['scene']['n_x']}"
        err = e["channel"]["max_rel"]
        wb = p["quadrature"]["wall_band"]
        print(f"| {p['evaluation']['velocity']}{dirty_mark(r)} | {wb} | {grid} | {'-' if sx == 0 else sx} x {sy} | {fmt(d.get('coarse_spacing_over_eta'))} | "
              f"{fmt(d.get('coarsening_paper_equivalent'))} | {fmt(d.get('coarsening_strip'))} | {pct(err)} | "
              f"{pct(e['interior']['max_rel'])} | {pct(e['wall_band']['max_rel'])} | {pct(e['inside_walls']['max_rel'])} | "
              f"{fmt(1e3 * c['exact_evaluate_seconds_min'])} | {fmt(1e3 * c['quadrature_evaluate_seconds_min'])} | "
              f"{fmt(c['evaluate_speedup'])} |")
        series.setdefault((p["evaluation"]["velocity"], wb, sx == 0), []).append((sy, d.get("coarse_spacing_over_eta"), e))
    print("\nObserved order of the error in the coarse spacing (x-integrated column, stride_y >= 2):\n")
    print("| velocity | wall band | region | fitted order | consecutive orders |")
    print("|---|---|---|---|---|")
    for (vel, wb, column), pts in sorted(series.items()):
        if not column:
            continue
        pts = sorted(p for p in pts if p[0] >= 2)
        for region in ("channel", "interior", "wall_band"):
            xy = [(dc, e[region]["max_rel"]) for _, dc, e in pts]
            cons = [math.log(e1 / e0) / math.log(x1 / x0) if e0 > 0 and e1 > 0 else float("nan")
                    for (x0, e0), (x1, e1) in zip(xy, xy[1:])]
            print(f"| {vel} | {wb} | {region} | {slope(xy):.2f} | {', '.join(f'{o:.2f}' for o in cons)} |")


if __name__ == "__main__":
    main(sys.argv[1])
