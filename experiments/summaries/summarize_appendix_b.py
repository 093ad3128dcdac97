#!/usr/bin/env python3
"""Markdown summary of the Appendix B eta-sweep (results/paper/appendix_b/appendix_b.json).

Usage: python3 experiments/summaries/summarize_appendix_b.py TABLE.json > summary.md
Every number printed is read from the table. For each eta' the table holds the interior maximum of |T_c,xx| of the
averaged direct SPH steady state, the same maximum of the App. B formula, and their max difference. Because the
walls sit at 3 eta', the channel (and its shear) changes with eta', so the interior maximum is no clean power of
eta'. App. B gives -T_c,xx / rho = eta'^2 V'(y)^2 / 2 + O(eta'^4) (V' = (rho g / mu)((l1 + l2)/2 - y), the shear of
(5.15)); the scaled stress s = -T_c,xx / (rho V'^2 / 2), taken as the median over the interior profile nodes away
from the centre (|y - (l1 + l2)/2| > (l2 - l1)/8, where V' is not small), must then grow like eta'^2: its fitted
exponent is the App. B test.
"""
import json
import sys

from summary_util import slope, load_table, dirty_mark


def _eta(row):
    """The row's eta'/L_y: eta_over_l, or eta_over_ly in rows stored before every scene named it eta_over_l."""
    scene = row["params"]["scene"]
    return scene["eta_over_l"] if "eta_over_l" in scene else scene["eta_over_ly"]


def main(path):
    table = load_table(path)
    prov = table["provenance"]
    print(f"# {table['experiment']}: the convective stress shrinks like eta'^2 (Appendix B)\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
          f"{prov['threads']} thread(s), {prov['date_utc']}, command `{prov['command']}`. Table complete: {table['complete']}.\n")
    rows = sorted((r for r in table["rows"] if r.get("status") == "ok"), key=lambda r: _eta(r))
    print("| eta'/L_y | steps | interior nodes used | max \\|T_c,xx\\| SPH (interior) | max \\|T_c,xx\\| App. B | max \\|SPH - App. B\\| | scaled s / eta'^2 |")
    print("|---|---|---|---|---|---|---|")
    scaled = []
    for r in rows:
        eta = _eta(r)
        e, c, d, p = r["errors"], r["cost"], r["scene_derived"], r["params"]["scene"]
        l1, l2, rho, g, mu = d["l1"], d["l2"], p["rho"], p["g"], p["mu"]
        centre, width = 0.5 * (l1 + l2), l2 - l1
        vals = []
        for y, t in zip(r["profile"]["y"], r["profile"]["convective_xx"]):
            if y < l1 + 3 * eta or y > l2 - 3 * eta or abs(y - centre) <= width / 8:
                continue
            shear = rho * g / mu * (centre - y)
            vals.append(-t / (rho * shear ** 2 / 2))
        if not vals:
            print(f"| {eta:.4g}{dirty_mark(r)} | {c['steps']} | 0 (no interior node off the centre: the channel is {width:.3g} wide) ||||")
            continue
        vals.sort()
        s = vals[len(vals) // 2]
        scaled.append((eta, s))
        print(f"| {eta:.4g}{dirty_mark(r)} | {c['steps']} | {len(vals)} | {e['convective_xx_interior_max']:.4g} | "
              f"{e['convective_xx_appendix_b_interior_max']:.4g} | {e['convective_xx_vs_appendix_b_max_abs']:.3g} | {s / eta ** 2:.4f} |")
    for r in table["rows"]:
        if r.get("status") != "ok":
            print(f"| {_eta(r):.4g} | {r.get('status')}: {r.get('error', '')} |||||")
    if len(scaled) >= 2:
        print(f"\nFitted exponent p in s ~ eta'^p over {len(scaled)} eta' values: **{slope(scaled):.3f}** (App. B: 2; "
              "s / eta'^2 = 1 + O(eta'^2)).")


if __name__ == "__main__":
    main(sys.argv[1])
