#!/usr/bin/env python3
"""Markdown summary of a direct_sph_validation table of the cellular scene (results/cellular/direct/direct.json).

Usage: python3 experiments/summaries/summarize_cellular.py TABLE.json > summary.md
Every number printed is read from the table. Orders: log(e_1 / e_2) / log(n_2 / n_1) between consecutive
resolutions of the same scene parameters, and the least-squares slope of log |e| against log n over all of them.
"""
import math
import sys

from summary_util import dirty_mark, fmt, load_table, pct, slope, spct


def main(path):
    table = load_table(path)
    prov = table["provenance"]
    print(f"# {table['experiment']}: direct SPH of the cellular flow\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}` by `python3 experiments/summaries/summarize_cellular.py {path}`; commit "
          f"`{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, {prov['threads']} thread(s), "
          f"{prov['date_utc']}, command `{prov['command']}`. Table complete: {table['complete']}.\n")
    print("*amplitude*: the least-squares amplitude of the particle velocities on the mode (sin kx cos ky, "
          "-cos kx sin ky), relative to the exact A(t) at the final time (its difference, in %); *particles max* / *L2*: "
          "max over particles of |v - v_exact| / A, and the relative L2 norm, in %; *avg max*: the same for the Gaussian averages on the mesh "
          "against the exact field times the window's factor (exp(-|k|^2 eta^2 / 4) for the Gaussian); "
          "*displacement*: the largest distance of a particle from its lattice site at the end, in lattice spacings.\n")
    print("| n | Re | status | amplitude | particles max | particles L2 | avg max | factor | displacement [eps'] | "
          "steps | dt | model time | SPH wall s | particle-steps/s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    groups = {}
    for r in table["rows"]:
        p = r["params"]["scene"]
        e, c = r.get("errors", {}), r.get("cost", {})
        a = e.get("amplitude", {})
        pa, av = e.get("particles_vs_analytic", {}), e.get("averaged_vs_averaged_analytic", {})
        print(f"| {p['n']}{dirty_mark(r)} | {p['re']} | {r['status']} | {spct(a.get('relative_difference'))} | "
              f"{pct(pa.get('max_rel'))} | {pct(pa.get('l2_rel'))} | {pct(av.get('max_rel'))} | "
              f"{fmt(e.get('averaging_factor'), 6)} | {fmt(e.get('max_displacement_dx'))} | {fmt(c.get('steps'))} | "
              f"{fmt(c.get('dt'))} | {fmt(c.get('model_time'))} | {fmt(c.get('wall_seconds'))} | "
              f"{fmt(c.get('particle_steps_per_second'))} |")
        if r["status"] == "ok" and a.get("relative_difference") is not None:
            key = tuple((k, str(v)) for k, v in sorted(p.items()) if k != "n")
            groups.setdefault(key, []).append((p["n"], abs(a["relative_difference"]), pa.get("max_rel")))
    for key, pts in groups.items():
        pts.sort()
        if len(pts) < 2:
            continue
        pairs = [f"{pts[i][0]} -> {pts[i + 1][0]}: amplitude "
                 f"{fmt(math.log(pts[i][1] / pts[i + 1][1]) / math.log(pts[i + 1][0] / pts[i][0]))}, particles max "
                 f"{fmt(math.log(pts[i][2] / pts[i + 1][2]) / math.log(pts[i + 1][0] / pts[i][0]))}"
                 for i in range(len(pts) - 1)]
        print(f"\nOrder of convergence in eps' (Re = {dict(key).get('re')}, m = {dict(key).get('m')}): "
              f"{'; '.join(pairs)}; least-squares slope over n = {', '.join(str(q[0]) for q in pts)}: amplitude "
              f"{fmt(-slope([(q[0], q[1]) for q in pts]))}, particles max {fmt(-slope([(q[0], q[2]) for q in pts]))}.")


if __name__ == "__main__":
    main(sys.argv[1])
