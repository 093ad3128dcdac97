#!/usr/bin/env python3
"""Stands in for an external SPH code: writes one particle snapshot of a closurelab scene's lattice,
(i + 1/2) dx, (j + 1/2) dx with dx = 1/n_y on the unit-height box, with a chosen velocity profile v_x(y).

  write_lattice_snapshot.py OUT.csv|OUT.h5part --n-y N --n-x M --profile poiseuille|sine [--eta-over-ly E]

poiseuille: v_x = (y - l1)(l2 - y)/2 between the walls l1 = 3 eta', l2 = 1 - 3 eta' (rho = mu = g = 1), 0 in
the walls; sine: v_x = sin(2 pi y). Mass 1/n_y^2 (the lattice's, not closurelab's SPH-normalized one), phase 0.
CSV has the header x,y,vx,vy,mass,phase; .h5part is written with h5py in the H5Part layout (Step#0)."""
import argparse
import math

ap = argparse.ArgumentParser()
ap.add_argument("out")
ap.add_argument("--n-y", type=int, required=True)
ap.add_argument("--n-x", type=int, required=True)
ap.add_argument("--profile", choices=["poiseuille", "sine"], required=True)
ap.add_argument("--eta-over-ly", type=float, default=1.0 / 16.0)
a = ap.parse_args()
dx = 1.0 / a.n_y
l1, l2 = 3 * a.eta_over_ly, 1 - 3 * a.eta_over_ly


def vx(y):
    if a.profile == "sine":
        return math.sin(2 * math.pi * y)
    return 0.5 * (y - l1) * (l2 - y) if l1 < y < l2 else 0.0


rows = [((i + 0.5) * dx, (j + 0.5) * dx) for j in range(a.n_y) for i in range(a.n_x)]
if a.out.endswith(".csv"):
    with open(a.out, "w") as f:
        f.write("x,y,vx,vy,mass,phase\n")
        for x, y in rows:
            f.write(f"{x!r},{y!r},{vx(y)!r},0.0,{dx * dx!r},0\n")
else:
    import h5py
    import numpy as np
    with h5py.File(a.out, "w") as f:
        g = f.create_group("Step#0")
        g.attrs["TimeValue"] = 0.0
        g["x"] = np.array([p[0] for p in rows])
        g["y"] = np.array([p[1] for p in rows])
        g["z"] = np.zeros(len(rows))
        g["vx"] = np.array([vx(p[1]) for p in rows], dtype=np.float32)  # another code's single precision
        g["vy"] = np.zeros(len(rows))
        g["mass"] = np.full(len(rows), dx * dx)
