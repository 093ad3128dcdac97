#!/usr/bin/env python3
"""Markdown summary of a direct_sph_validation table (results/sph_validation/sph_validation.json).

Usage: python3 experiments/summaries/summarize_validation.py TABLE.json > summary.md
Every number printed is read from the table; orders are log2 of consecutive error ratios over n_y.
"""
import json
import math
import sys

from summary_util import dirty_mark, fmt, load_table, pct, spct


def main(path):
    table = load_table(path)
    prov = table["provenance"]
    print(f"# {table['experiment']}: direct SPH validation\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
          f"{prov['threads']} thread(s), {prov['date_utc']}, command `{prov['command']}`. "
          f"Table complete: {table['complete']}.\n")
    print("Errors in % of the analytic peak velocity. *particles*: every fluid particle against (5.15)/(D.3); "
          "*avg interior* / *avg band*: the averaged SPH velocity against the Gaussian average of the analytic "
          "solution, at nodes at least 3 eta' from the walls / nearer. *shift*: effective wall position from a "
          "parabola fitted to the particle velocities, in lattice spacings beyond the nominal wall (uniform force "
          "only); *centre*: fitted peak overprediction, beside 2 eps'/W.\n")
    print("| scene | n_y | walls | status | steps | dt | SPH wall s | particle-steps/s | particles max | avg interior max | avg band max | shift [eps'] | centre | 2eps'/W |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    groups = {}
    for r in table["rows"]:
        p = r["params"]["scene"]
        e, c = r.get("errors", {}), r.get("cost", {})
        wo = e.get("wall_offset", {})
        pa = e.get("particles_vs_analytic", {}).get("all", {}).get("max_rel")
        ai = e.get("averaged_vs_averaged_analytic", {}).get("interior", {}).get("max_rel")
        ab = e.get("averaged_vs_averaged_analytic", {}).get("wall_band", {}).get("max_rel")
        print(f"| {p['name']}{dirty_mark(r)} | {p['n_y']} | {p['wall_model']} | {r['status']} | {fmt(c.get('steps'))} | {fmt(c.get('dt'))} | "
              f"{fmt(c.get('wall_seconds'))} | {fmt(c.get('particle_steps_per_second'))} | {pct(pa)} | {pct(ai)} | {pct(ab)} | "
              f"{fmt(wo.get('shift_in_spacings'))} | {spct(wo.get('centre_overprediction'))} | {pct(wo.get('expected_2dx_over_w'))} |")
        if pa is not None:
            groups.setdefault((p["name"], p["wall_model"]), []).append((p["n_y"], pa))
    print("\nObserved order of the particle max error between consecutive resolutions:\n")
    print("| scene | walls | n_y pair | order |")
    print("|---|---|---|---|")
    for (name, walls), pts in sorted(groups.items()):
        pts.sort()
        for (n0, e0), (n1, e1) in zip(pts, pts[1:]):
            order = math.log(e0 / e1) / math.log(n1 / n0) if e0 > 0 and e1 > 0 and n1 != n0 else float("nan")
            print(f"| {name} | {walls} | {n0} -> {n1} | {order:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1])
