#!/usr/bin/env python3
"""The velocity field of PySPH's lattice_cylinders.py against closurelab's direct SPH, both averaged onto the same
coarse mesh: a peer check of the field, not only of the permeability (scripts/peer_lattice_cylinders.py).

Usage: /usr/bin/python3 scripts/peer_lattice_cylinders_field.py RUN.npz ... [--cells DIR] [--out FILE.json]

Each NPZ is the final state written by `peer_lattice_cylinders.py --save-particles`, with its JSON output beside
it (same name, .json). closurelab's side is the averaged direct SPH that the committed reduced-model cells hold
(results/cylinders/reduced/cells, rows labelled "a=0.2L n=N": `fields.direct_average`, computed at commit 99d8407
by the engine's average_particles: v = sum m v psi / sum m psi over every particle, the solid's at rest, on the
16 x 16 nodes (i + 1/2) L/16, Gaussian window psi = exp(-|x|^2/eta^2)/(pi eta^2), eta = L/16, periodic images).
The PySPH particles (fluid and solid, the solid at u = v = 0, all of mass rho0 dx^2) are averaged here the same way
(numpy, image sums over |q| <= 2 periods, the window below 1e-15 of its peak beyond 6 eta < L).

Both fields made dimensionless by the scale g L^2 / nu of each run (closurelab: g = 0.01, nu = mu/rho = 1, L = 1;
PySPH: fx, nu = 1e-6, L = 0.1): v* = v nu / (g L^2), so that k/L^2 = <v*>. Compared on the nodes outside the
solid (`fields.outside_solid`): max |v*_PySPH - v*_closurelab| over the peak |v*_closurelab|, and the relative
L2 norm; and the same after dividing each field by its own superficial velocity (the shape, with the permeability
difference taken out). Each PySPH file against closurelab at the same n where the cells have it, and against
closurelab's finest (n = 192); and, for scale, closurelab's n = 48 and 96 against its n = 192. The check of the averaging: <rho v_x> over the mesh, sum rho_bar v_bar dA/(rho0 L^2),
gives back the superficial velocity the peer script measured (printed as its k/L^2).
"""
import argparse
import glob
import json
import math
import os

import numpy as np


def window_1d(nodes, q, eta, period):
    """phi(node - q) summed over periodic images: (len(nodes), len(q))."""
    d = nodes[:, None] - q[None, :]
    d -= period * np.round(d / period)
    out = np.zeros_like(d)
    for img in range(-2, 3):
        t = d + img * period
        out += np.exp(-(t / eta) ** 2) / (math.sqrt(math.pi) * eta)
    return out


def average(npz, L, nodes_x, nodes_y, eta):
    z = np.load(npz)
    x = np.concatenate([z["fluid_x"], z["solid_x"]])
    y = np.concatenate([z["fluid_y"], z["solid_y"]])
    u = np.concatenate([z["fluid_u"], z["solid_u"]])
    v = np.concatenate([z["fluid_v"], z["solid_v"]])
    m = np.concatenate([z["fluid_m"], z["solid_m"]])
    px = window_1d(nodes_x, x, eta, L)  # (nx, N)
    py = window_1d(nodes_y, y, eta, L)  # (ny, N)
    rho = (py * m) @ px.T  # (ny, nx): row j = y node, column i = x node (closurelab's index i + nx j)
    mu_ = (py * (m * u)) @ px.T
    mv_ = (py * (m * v)) @ px.T
    return rho.ravel(), (mu_ / rho).ravel(), (mv_ / rho).ravel()


def compare(a_vx, a_vy, b_vx, b_vy, mask):
    """a against b (b the scale) on the nodes of mask: max and L2 of |a - b| over the peak |b|."""
    d = np.hypot(a_vx - b_vx, a_vy - b_vy)[mask]
    sb = np.hypot(b_vx, b_vy)[mask]
    return {"max_rel": float(d.max() / sb.max()), "l2_rel": float(np.sqrt((d ** 2).sum() / (sb ** 2).sum()))}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("npz", nargs="+")
    ap.add_argument("--cells", default="results/cylinders/reduced/cells")
    ap.add_argument("--out", default="")
    a = ap.parse_args()

    cl = {}
    for f in sorted(glob.glob(os.path.join(a.cells, "*.json"))):
        c = json.load(open(f))
        lab = c.get("label", "")
        if lab.startswith("a=0.2L n=") and " " not in lab[len("a=0.2L "):] and "direct_average" in c.get("fields", {}):
            sc = c["params"]["scene"]
            fld = c["fields"]
            scale = sc["g"] * sc["l"] ** 2 / (sc["mu"] / sc["rho"])
            cl[sc["n"]] = {"file": f, "x": np.array(fld["x"]), "y": np.array(fld["y"]), "l": sc["l"],
                           "eta": c["params"]["kernel"]["eta"], "kernel": c["params"]["kernel"]["name"],
                           "vx": np.array(fld["direct_average"]["vx"]) / scale,
                           "vy": np.array(fld["direct_average"]["vy"]) / scale,
                           "outside": np.array(fld["outside_solid"], dtype=bool),
                           "k_over_l2": c["errors"]["permeability"]["direct_sph"] / sc["l"] ** 2,
                           "commit": c["provenance"]["git_commit"]}
    finest = max(cl)
    results = []
    for path in a.npz:
        run = json.load(open(os.path.splitext(path)[0] + ".json"))
        L = 0.1
        ref = cl[finest]
        assert all(c["kernel"] == "gaussian" for c in cl.values())
        rho, vx, vy = average(path, L, ref["x"] * L / ref["l"], ref["y"] * L / ref["l"], ref["eta"] * L / ref["l"])
        scale = run["fx"] * L ** 2 / run["nu"]
        vx, vy = vx / scale, vy / scale
        dA = (L / len(ref["x"])) * (L / len(ref["y"]))
        k_mesh = float((rho * vx).sum() * dA / (run["rho0"] * L ** 2))  # <rho v*> over the mesh / rho0 = k/L^2
        r = {"npz": path, "nx": run["nx"], "fx": run["fx"], "k_over_L2_script": run["k_over_L2_last"],
             "k_over_L2_from_mesh": k_mesh, "vs": {}}
        for n in sorted({run["nx"], finest} & set(cl)):
            c = cl[n]
            s_p = run["k_over_L2_last"]
            s_c = c["k_over_l2"]
            r["vs"]["closurelab_n%d" % n] = {
                "cell": c["file"], "cell_commit": c["commit"], "closurelab_k_over_L2": s_c,
                "dimensionless": compare(vx, vy, c["vx"], c["vy"], c["outside"]),
                "shape": compare(vx / s_p, vy / s_p, c["vx"] / s_c, c["vy"] / s_c, c["outside"]),
                "peak_closurelab": float(np.hypot(c["vx"], c["vy"])[c["outside"]].max()),
                "peak_pysph": float(np.hypot(vx, vy)[c["outside"]].max()),
            }
        results.append(r)
        for key, v in r["vs"].items():
            print("field: %s (nx %d, fx %.3g) vs %s: v* max %.2f %% / L2 %.2f %% of closurelab's peak; shape (each / its "
                  "<u>) max %.2f %% / L2 %.2f %%; peaks %.5f vs %.5f; k/L^2 from the mesh %.6f (script %.6f)" % (
                      path, r["nx"], r["fx"], key, 100 * v["dimensionless"]["max_rel"],
                      100 * v["dimensionless"]["l2_rel"], 100 * v["shape"]["max_rel"], 100 * v["shape"]["l2_rel"],
                      v["peak_pysph"], v["peak_closurelab"], k_mesh, r["k_over_L2_script"]))
    # For scale: closurelab's own coarser fields against its finest, the same measures.
    own = {}
    for n in sorted(set(cl) - {finest}):
        c, f = cl[n], cl[finest]
        own["closurelab_n%d_vs_n%d" % (n, finest)] = {
            "dimensionless": compare(c["vx"], c["vy"], f["vx"], f["vy"], f["outside"]),
            "shape": compare(c["vx"] / c["k_over_l2"], c["vy"] / c["k_over_l2"], f["vx"] / f["k_over_l2"],
                             f["vy"] / f["k_over_l2"], f["outside"])}
        v = own["closurelab_n%d_vs_n%d" % (n, finest)]
        print("field: closurelab n %d vs n %d: v* max %.2f %% / L2 %.2f %%; shape max %.2f %% / L2 %.2f %%" % (
            n, finest, 100 * v["dimensionless"]["max_rel"], 100 * v["dimensionless"]["l2_rel"],
            100 * v["shape"]["max_rel"], 100 * v["shape"]["l2_rel"]))
    if a.out:
        with open(a.out, "w") as f:
            json.dump({"script": "scripts/peer_lattice_cylinders_field.py", "mesh": "16 x 16, gaussian eta = L/16",
                       "results": results, "closurelab_against_its_finest": own}, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
