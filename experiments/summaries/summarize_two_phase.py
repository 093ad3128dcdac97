#!/usr/bin/env python3
"""Markdown summary of a direct_sph_validation table of the layered two-phase scene
(results/two_phase/direct/two_phase_direct.json).

Usage: python3 experiments/summaries/summarize_two_phase.py TABLE.json > summary.md
Every number printed is read from the table.
"""
import json
import sys

from summary_util import dirty_mark, fmt, load_table, pct, spct


def main(path):
    table = load_table(path)
    prov = table["provenance"]
    print(f"# {table['experiment']}: direct SPH of the layered two-phase channel (par. 7)\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}` by `python3 experiments/summaries/summarize_two_phase.py {path}`; commit "
          f"`{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, {prov['threads']} thread(s), "
          f"{prov['date_utc']}, command `{prov['command']}`. Table complete: {table['complete']}.\n")
    print("Errors in % of the analytic peak velocity. *max* / *L2*: every fluid particle against the "
          "piecewise-parabolic solution; *interior* / *wall band*: particles at least 3 eta' from a wall / nearer; "
          "*near if* / *away*: particles within one SPH support (3 eps') of a phase interface / farther; "
          "*avg int*: averaged SPH velocity against the Gaussian average of the analytic solution at mesh nodes at least "
          "3 eta' from the walls; *peak*: the paper's metric (max v - max V)/max V; *shift*: the largest "
          "y-displacement of a fluid particle from its lattice row, in eps'; *out*: fluid particles whose phase no "
          "longer matches the phase of their height; *drho*: min/max (m n - rho0)/rho0 of fluid particles within "
          "3 eps' of an interface.\n")
    print("| case | mean | status | max | L2 | interior max | wall band max | near if max | away max | avg int max | "
          "peak | shift [eps'] | out | drho near if | steps | dt | model time | SPH wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    vdw = None
    for r in table["rows"]:
        p = r["params"]["scene"]
        e, c, i = r.get("errors", {}), r.get("cost", {}), r.get("interfaces", {})
        pa = e.get("particles_vs_analytic", {})
        g = lambda k, f="max_rel": pa.get(k, {}).get(f)
        ai = e.get("averaged_vs_averaged_analytic", {}).get("interior", {}).get("max_rel")
        d = i.get("density_deviation_near_interfaces", {})
        drho = f"{fmt(d.get('min'))} / {fmt(d.get('max'))}" if d else "-"
        vdw = vdw or i.get("van_der_waals")
        print(f"| {p['case']}{dirty_mark(r)} | {p['pair_viscosity_mean']} | {r['status']} | {pct(g('all'))} | {pct(g('all', 'l2_rel'))} | "
              f"{pct(g('interior'))} | {pct(g('wall_band'))} | {pct(g('near_interfaces'))} | "
              f"{pct(g('away_from_interfaces'))} | {pct(ai)} | {spct(e.get('peak_relative_difference'))} | "
              f"{fmt(i.get('max_y_displacement_dx'))} | {fmt(i.get('particles_outside_phase_region'))} | {drho} | "
              f"{fmt(c.get('steps'))} | {fmt(c.get('dt'))} | {fmt(c.get('model_time'))} | {fmt(c.get('wall_seconds'))} |")
    if vdw:
        sd = table["rows"][0].get("scene_derived", {})
        sp = table["rows"][0]["params"]["scene"]
        print(f"\nVan der Waals EOS (7.1) of the first row: phi = c_1 n0 = {sp['vdw_phi']}, a = c_2 n0 / k_BT = {sp['vdw_a']}, "
              f"k* = {sp['k_star']}; n0 = {fmt(vdw['n0'], 6)}, k_BT = {fmt(vdw['kT'], 6)}, c_1 = {fmt(vdw['c1'], 6)}, "
              f"c_2 = {fmt(vdw['c2'], 6)}; P(n0) = {fmt(vdw['rest_pressure'], 6)}; sound speed at n0 "
              f"{fmt(vdw['sound_speed_at_n0'], 6)} (scene: {fmt(sd.get('sound_speed'), 6)} = "
              f"{sp['sound_speed_factor']} x analytic peak {fmt(sd.get('analytic_peak'), 6)}); interface pressure jump "
              f"(1 - k*) c_2 n0^2 = {fmt(vdw['interface_pressure_jump'], 6)} = "
              f"{fmt(vdw['interface_pressure_jump_over_rho_c2'], 4)} rho c^2. The analytic peak and hence c differ by case.")


if __name__ == "__main__":
    main(sys.argv[1])
