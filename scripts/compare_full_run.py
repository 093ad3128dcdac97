#!/usr/bin/env python3
"""Compares a from-scratch `scripts/reproduce.sh --full` in a clone (NEW_ROOT, its results/**/cells deleted before
the run, a fresh reference store) with the committed results (COMMITTED_ROOT), spec by spec in the order of
reproduce.sh's list:

  1. time: each spec's end-to-end seconds (from the previous spec's table write, or START_EPOCH, to its own table
     write), the sum of its new cells' cell_wall_seconds, and the sum of the committed cells' cell_wall_seconds;
  2. numbers: per cells folder, the largest relative difference over the cells' numeric leaves, leaving out run
     costs and timings (/cost/, *_seconds, rates), provenance and the reference store's records; counts (bond
     weights, pair forces, sample points, matvecs, steps, evaluations) are listed apart; every cell above 1e-9 is
     named with its label and where its largest difference is.

usage: scripts/compare_full_run.py NEW_ROOT COMMITTED_ROOT START_EPOCH
"""
import glob
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare_cells import leaves  # noqa: E402

SKIP = ("/cost/", "_seconds", "per_second", "active_particles", "last_relative_change", "/provenance/",
        "/reference_store/")
COUNTS = ("bond_weights", "pair_forces", "sample_points", "matvecs", "steps", "evaluations")


def full_list(committed_root):
    text = open(os.path.join(committed_root, "scripts/reproduce.sh")).read()
    return [line.split() for line in text.split("<<'LIST'\n")[1].split("\nLIST")[0].splitlines()]


def cell_seconds(folder, ids):
    total = 0.0
    for i in ids:
        path = os.path.join(folder, i + ".json")
        if os.path.exists(path):
            total += json.load(open(path)).get("cell_wall_seconds", 0.0)
    return total


def times(new_root, committed_root, start):
    print(f"{'spec':52s} {'end-to-end s':>12s} {'new cells s':>11s} {'committed cells s':>17s}")
    prev, tot = start, [0.0, 0.0, 0.0]
    for spec, folder in full_list(committed_root):
        name = json.load(open(os.path.join(committed_root, spec)))["name"]
        table = os.path.join(new_root, folder, name + ".json")
        written = os.path.getmtime(table)
        ids = [r["id"] for r in json.load(open(table)).get("rows", []) if isinstance(r, dict) and "id" in r]
        row = [written - prev, cell_seconds(os.path.join(new_root, folder, "cells"), ids),
               cell_seconds(os.path.join(committed_root, folder, "cells"), ids)]
        print(f"{spec:52s} {row[0]:12.0f} {row[1]:11.0f} {row[2]:17.0f}")
        tot = [a + b for a, b in zip(tot, row)]
        prev = written
    print(f"{'all':52s} {tot[0]:12.0f} {tot[1]:11.0f} {tot[2]:17.0f}")


def numbers(new_root, committed_root):
    for folder in sorted(glob.glob(os.path.join(new_root, "results/**/cells"), recursive=True)):
        rel = os.path.relpath(folder, new_root)
        worst, where, counts, above, compared, cells = 0.0, "", set(), [], 0, 0
        for path in sorted(glob.glob(os.path.join(folder, "*.json"))):
            old_path = os.path.join(committed_root, rel, os.path.basename(path))
            if not os.path.exists(old_path):
                continue
            cells += 1
            new = json.load(open(path))
            old = dict(leaves(json.load(open(old_path))))
            cell_worst, cell_where = 0.0, ""
            for key, v in leaves(new):
                if any(s in key for s in SKIP) or key not in old:
                    continue
                w = old[key]
                if isinstance(v, bool) or not isinstance(v, (int, float)) or not isinstance(w, (int, float)):
                    continue
                compared += 1
                if v == w:
                    continue
                if any(c in key.rsplit("/", 1)[-1] for c in COUNTS):
                    counts.add(key.rsplit("/", 1)[-1])
                    continue
                rel_diff = abs(v - w) / max(abs(w), 1e-300)
                if rel_diff > cell_worst:
                    cell_worst, cell_where = rel_diff, f"{key}: {w!r} -> {v!r}"
            if cell_worst > worst:
                worst, where = cell_worst, cell_where
            if cell_worst > 1e-9:
                above.append(f"    {os.path.basename(path)[:12]} {new.get('label', '')}: {cell_worst:.2g} ({cell_where})")
        print(f"{rel}: {cells} cells, {compared} numbers, largest relative difference {worst:.2g}"
              f"{' (' + where + ')' if where else ''}; counts that differ: {', '.join(sorted(counts)) or 'none'}")
        for line in above:
            print(line)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    times(sys.argv[1], sys.argv[2], float(sys.argv[3]))
    print()
    numbers(sys.argv[1], sys.argv[2])
