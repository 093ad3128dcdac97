#!/usr/bin/env python3
"""Compares the cells of a rerun experiment with the committed ones (same cell ids): for every cell, the largest
relative difference over its numeric leaves, leaving out run costs (/cost/, wall seconds, rates), the active
particle count (reported only by newer engines) and the steady-state test's last relative change (a difference
of velocities: its relative round-off is that of the velocities times ~1/change).

usage: scripts/compare_cells.py NEW_CELLS_DIR COMMITTED_CELLS_DIR
"""
import json
import os
import sys

SKIP = ("/cost/", "wall_seconds", "per_second", "active_particles", "last_relative_change")


def leaves(d, path=""):
    if isinstance(d, dict):
        for k, v in d.items():
            yield from leaves(v, path + "/" + k)
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield from leaves(v, path + "/" + str(i))
    else:
        yield path, d


def main(new_dir, old_dir):
    worst_all = 0.0
    for name in sorted(os.listdir(new_dir)):
        old_path = os.path.join(old_dir, name)
        if not os.path.exists(old_path):
            print(f"{name}: no committed cell")
            continue
        old = dict(leaves(json.load(open(old_path))))
        worst, where, count, other = 0.0, "", 0, []
        for path, v in leaves(json.load(open(os.path.join(new_dir, name)))):
            if any(s in path for s in SKIP) or path not in old:
                continue
            w = old[path]
            if isinstance(v, bool) or isinstance(w, bool) or not isinstance(v, (int, float)) or not isinstance(w, (int, float)):
                if v != w:
                    other.append(path)
                continue
            count += 1
            if v != w:
                rel = abs(v - w) / max(abs(w), 1e-300)
                if rel > worst:
                    worst, where = rel, path
        worst_all = max(worst_all, worst)
        print(f"{name}: {count} numbers, max relative difference {worst:.3g} ({where or '-'}); other differences: {other or 'none'}")
    print(f"largest: {worst_all:.3g}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
