#!/usr/bin/env python3
"""The Taylor-Green validation table (kind direct_sph_validation, scene taylor-green) beside PySPH's run of the same
vortex (the output of scripts/peer_taylor_green.py, one file per n): the largest particle speed against the exact decay
U exp(-8 pi^2 t / Re) at the engine's saved times, PySPH's at its output nearest each (its own exact value there), and
the particles against the exact field at the end. Markdown to stdout; every number is read from the two files.

usage: scripts/taylor_green_peer_table.py TABLE.json N=PEER_OUTPUT.txt [N=PEER_OUTPUT.txt ...]
"""
import json
import re
import sys


def peer(path):
    hist, field = [], None
    for line in open(path):
        m = re.match(r"# particles vs exact at t = (\S+): max_rel (\S+) l2_rel (\S+)", line)
        if m:
            field = (float(m.group(1)), float(m.group(2)), float(m.group(3)))
            continue
        parts = line.split()
        if len(parts) == 4 and not line.startswith("#"):
            try:
                hist.append(tuple(float(p) for p in parts))
            except ValueError:
                pass
    return hist, field


def main(table_path, peers):
    table = json.load(open(table_path))
    rows = {r["params"]["scene"]["n"]: r for r in table["rows"]}
    runs = {}
    for arg in peers:
        n, path = arg.split("=", 1)
        runs[int(n)] = peer(path)
    ns = sorted(n for n in runs if n in rows)
    print(f"Engine: `{table_path}` (commit `{', '.join(table['provenance'].get('commits', []))}`); PySPH: "
          + ", ".join(f"n = {n} `{peers[i].split('=', 1)[1]}`" for i, n in enumerate(sorted(runs))) + ".\n")
    print("max|v| against the exact decay, |max|v| - U e^{bt}| / U e^{bt} in %; PySPH at its output nearest the "
          "engine's time (t_PySPH):\n")
    print("| t | " + " | ".join(f"engine n = {n} | PySPH n = {n} (t_PySPH)" for n in ns) + " |")
    print("|---|" + "---|---|" * len(ns))
    times = rows[ns[0]]["errors"]["max_speed"]["times"]
    worst = {n: [0.0, 0.0, 0.0, 0.0] for n in ns}  # engine all, PySPH all (at those outputs), engine t>=0.5, PySPH t>=0.5
    for k, t in enumerate(times):
        cells = []
        for n in ns:
            e = rows[n]["errors"]["max_speed"]["relative_error"][k]
            tp, _, _, ep = min(runs[n][0], key=lambda h: abs(h[0] - t))
            cells.append(f"{100 * e:.3g} % | {100 * ep:.3g} % ({tp:.4g})")
            w = worst[n]
            w[0], w[1] = max(w[0], e), max(w[1], ep)
            if t >= 0.5 - 1e-12:
                w[2], w[3] = max(w[2], e), max(w[3], ep)
        print(f"| {t:.3g} | " + " | ".join(cells) + " |")
    print("| worst | " + " | ".join(f"{100 * worst[n][0]:.3g} % | {100 * worst[n][1]:.3g} %" for n in ns) + " |")
    print("| worst from t = 0.5 | " + " | ".join(f"{100 * worst[n][2]:.3g} % | {100 * worst[n][3]:.3g} %" for n in ns) + " |")
    print("\nEvery PySPH output (not only those nearest the engine's times), worst: "
          + "; ".join(f"n = {n}: {100 * max(h[3] for h in runs[n][0]):.3g} % overall, "
                      f"{100 * max(h[3] for h in runs[n][0] if h[0] >= 0.5 - 1e-12):.3g} % from t = 0.5" for n in ns) + ".\n")
    print("The particles against the exact field at the end (max |v - v_exact| / max|v_exact|; relative L2), in %:\n")
    print("| n | t | engine max | PySPH max | engine L2 | PySPH L2 |")
    print("|---|---|---|---|---|---|")
    for n in ns:
        pv = rows[n]["errors"]["particles_vs_exact"]
        tf, fmax, fl2 = runs[n][1]
        print(f"| {n} | {rows[n]['direct_sph']['time']:.4g} / {tf:.4g} | {100 * pv['max_rel']:.3g} % | {100 * fmax:.3g} % | "
              f"{100 * pv['l2_rel']:.3g} % | {100 * fl2:.3g} % |")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
