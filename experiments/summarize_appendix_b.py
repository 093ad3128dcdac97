#!/usr/bin/env python3
"""Markdown summary of the Appendix B eta-sweep (results/paper/appendix_b/appendix_b.json).

Usage: python3 experiments/summarize_appendix_b.py TABLE.json > summary.md
Every number printed is read from the table. For each eta' the table holds the interior maximum of |T_c,xx| of the
averaged direct SPH steady state, the same maximum of the App. B formula, and their max difference. The exponent is
the least-squares slope of log(max |T_c,xx|) against log(eta'), for the measured and for the formula values.
"""
import json
import math
import sys


def slope(points):
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sum((p[0] - mx) ** 2 for p in pts)


def main(path):
    table = json.load(open(path))
    prov = table["provenance"]
    print(f"# {table['experiment']}: the convective stress shrinks like eta'^2 (Appendix B)\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
          f"{prov['threads']} thread(s), {prov['date_utc']}, command `{prov['command']}`. Table complete: {table['complete']}.\n")
    rows = sorted((r for r in table["rows"] if r.get("status") == "ok"), key=lambda r: r["params"]["scene"]["eta_over_ly"])
    print("| eta'/L_y | steps | max \\|T_c,xx\\| SPH (interior) | max \\|T_c,xx\\| App. B | max \\|SPH - App. B\\| | SPH / App. B |")
    print("|---|---|---|---|---|---|")
    measured, formula = [], []
    for r in rows:
        eta = r["params"]["scene"]["eta_over_ly"]
        e, c = r["errors"], r["cost"]
        m, b = e["convective_xx_interior_max"], e["convective_xx_appendix_b_interior_max"]
        measured.append((eta, m))
        formula.append((eta, b))
        print(f"| {eta:.4g} | {c['steps']} | {m:.4g} | {b:.4g} | {e['convective_xx_vs_appendix_b_max_abs']:.3g} | {m / b:.4f} |")
    for r in table["rows"]:
        if r.get("status") != "ok":
            print(f"| {r['params']['scene']['eta_over_ly']:.4g} | {r.get('status')}: {r.get('error', '')} |||||")
    if len(measured) >= 2:
        print(f"\nFitted exponent p in max |T_c,xx| ~ eta'^p: direct SPH **{slope(measured):.3f}**, App. B formula "
              f"{slope(formula):.3f}. The walls sit at 3 eta', so the channel narrows as eta' grows and the interior maximum "
              "is not a pure eta'^2 law: the formula's slope, not 2, is the one to compare with.")


if __name__ == "__main__":
    main(sys.argv[1])
