"""The peer test (ctest label `peer`): closurelab's direct SPH of the `poiseuille-uniform` scene against an
independent PySPH model of the same scene (tests/peer/poiseuille_pysph.py), particle by particle.

  test_pysph_equivalence.py CLOSURELAB [--ny 48] [--tf 0.6] [--wall-model zero_velocity|ghost_velocity]
                            [--scene poiseuille-uniform|layered-two-phase|cylinder-lattice] [--case caseK]
                            [--radius-over-length 0.2] [--work DIR] [--pysph-args "..."]

Exit 0: the two agree to round-off; 1: they differ (a physics change) or a run failed; 77: PySPH (or h5py)
cannot be imported under this interpreter (ctest reports SKIP; the test never passes without PySPH).

closurelab runs the scene as a user would (`closurelab run` of a direct_sph_validation cell in target_time mode);
its final particles are read from the reference store's H5Part payload (for cylinder-lattice, whose
direct_sph_validation reports the permeability without storing particles, the direct reference of a
reduced_model_2d_force_density cell, timed once: the same engine run through the same store). PySPH runs the peer script, whose
final particles are read from PySPH's own HDF5 output. Particles are paired by their lattice index.

The tolerances, from round-off (not from the measured differences). The two codes evaluate the same sums in a
different order and in algebraically equal but not bitwise equal forms (kernel polynomial, periodic images,
F = q.grad w / |q|^2 against w'(r)/r), so each acceleration differs by a few ulps of the largest terms it sums.
At n_y = 48 (the lattice sums, P = c^2 rho = 0.238, n = 2304, 24 neighbours within the support): the pressure
terms |(P_i/n_i^2 + P_j/n_j^2) grad w| / m add up to 37 per particle (cancelling on the lattice), the viscous ones
to 6.3e3 |v_ij| <~ 20 next to the walls; with a few ulps (2.2e-16) of ~60 per sum, |delta a| <~ 7e-14 per
evaluation and |delta v| = dt |delta a| <~ 8e-18 per step (dt = 0.25 eps'^2 = 1.1e-4). The viscous dynamics
contracts (the slowest channel mode decays in tau = W^2/(pi^2 nu) = 0.040 = 365 steps), so velocity differences
do not grow: added coherently over tau they stay below 3e-15, 6e-14 of the peak 0.052 (randomly, ~3e-15 of it).
Positions integrate the velocity difference without decay (the flow is x-invariant): t |delta v| <~ 2e-15, plus
one ulp (<= 1.1e-16) of a coordinate wherever a rounding flips: ~sqrt(N) ulps randomly, N = 5530 steps at
t = 0.6 (4e-15), N ulps only if every step flipped the same way (3e-13, not credible). Asserted: velocities
within VEL_TOL = 1e-13 of the peak (above the coherent bound), positions within POS_TOL = 1e-13 L_y (5e-12 eps',
25x above the random-walk bound); anything systematic fails: a physics change moves the particles by many
orders of magnitude more (mu_i + mu_j replaced by their mean in the engine's one-phase force pass, planted
and not committed: 0.50 of the peak, 1.2 eps' in position at t = 0.6; exit 1).
The same argument holds for the other two cases (c = 10 x the peak in each, so pressure and viscous terms keep
their proportions; ghost walls multiply the fluid-wall viscous coupling by up to 7 and divide dt by 7; the
layered scene relaxes in L^2/(pi^2 nu) = 1250 of its steps), and their measured differences are as small.
Measured (n_y = 48): poiseuille-uniform, t = 0.6, zero-velocity walls: 2.7e-16 of the peak and 5.6e-17 L_y;
ghost-velocity walls, t = 0.1 (6452 steps): 4.7e-16 and 2.8e-17 L_y; layered-two-phase case1 (van der Waals,
mu 200/100, unlike-pair excess), t = 0.002 (3687 steps): 6.0e-16 of the peak, positions equal.

cylinder-lattice (--scene cylinder-lattice, --ny = n; doubly periodic cell, one cylinder of radius a = 0.2 L,
frozen solid particles with their solid-solid density part, g = 0.01, c = 10, P_b = 0.002 rho c^2 = 0.2): a Stokes
flow, so the peak velocity (4.5e-4 at t = 0.05) is small against the pressure terms and the tolerance relative to
the peak is wider. At n = 32 (h = 1/32, dt = 0.25 eps'^2 = 2.44e-4, 24 neighbours): the pressure terms
|(P_i/n_i^2 + P_j/n_j^2) grad w| / m add up to S = 21 per particle, the viscous ones to 2.8e3 |v_ij| <= 1.3. Besides
a few ulps of S from the order of the sums (2e-14), the pair vectors differ by an ulp of a coordinate across the
periodic boundaries (PySPH's images at x +- L against closurelab's wrapped differences: 2.2e-16 in r >= eps',
7e-15 relative, a few times that in grad w), so |delta a| <~ 2e-14 S = 4e-13 per evaluation and
|delta v| <~ dt |delta a| = 1e-16 per step: 2e-14 = 4.6e-11 of the peak if all 205 steps to t = 0.05 added
coherently, ~sqrt(205) x 1e-16 = 1.4e-15 = 3e-12 of it randomly. Asserted: velocities within
VEL_TOL_CYLINDERS = 1e-10 of the peak (2x above the coherent bound), positions within POS_TOL (t |delta v| <~ 1e-15
plus coordinate ulps). Measured: n = 32, t = 0.05 (205 steps): 3.2e-12 of the peak (1.4e-15 absolute), 1.6e-16 L
in position; the absolute difference stays at 1.1-1.4e-15 from t = 0.0125 to 0.2 (52-820 steps: it does not
accumulate); n = 48, t = 0.05 (461 steps): 3.5e-12 of the peak, 1.6e-16 L.
"""

import argparse
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

VEL_TOL = 1e-13
VEL_TOL_CYLINDERS = 1e-10
POS_TOL = 1e-13
SKIP = 77

here = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("closurelab")
    ap.add_argument("--ny", type=int, default=48)
    ap.add_argument("--nx", type=int, default=12)
    ap.add_argument("--tf", type=float, default=0.6)
    ap.add_argument("--wall-model", default="zero_velocity", choices=["zero_velocity", "ghost_velocity"])
    ap.add_argument("--scene", default="poiseuille-uniform",
                    choices=["poiseuille-uniform", "layered-two-phase", "cylinder-lattice"],
                    help="layered-two-phase: --ny fluid rows, case --case, zero-velocity walls; cylinder-lattice: "
                         "--ny is n (the n x n cell), --nx ignored, radius --radius-over-length")
    ap.add_argument("--case", default="case1", choices=["case1", "case2", "case3"])
    ap.add_argument("--radius-over-length", type=float, default=0.2)
    ap.add_argument("--work", help="keep the runs in this folder (default: a temporary one, removed)")
    ap.add_argument("--pysph-args", default="", help="extra arguments for the PySPH application")
    a = ap.parse_args()

    try:
        import numpy as np
        import h5py  # noqa: F401
        import pysph  # noqa: F401
    except ImportError as e:
        print("SKIP: cannot import PySPH under %s (%s); Debian: apt-get install python3-pysph, and run it with "
              "/usr/bin/python3" % (sys.executable, e))
        return SKIP

    work = a.work or tempfile.mkdtemp(prefix="closurelab_peer_")
    os.makedirs(work, exist_ok=True)
    try:
        return compare(a, work, np)
    finally:
        if not a.work:
            shutil.rmtree(work, ignore_errors=True)


def run(cmd, **kw):
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        print("FAILED (%d): %s\n%s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-4000:], p.stderr[-4000:]))
        raise SystemExit(1)
    return time.time() - t0


def closurelab_run(a, work):
    solver = {"mode": "target_time", "target_time": a.tf, "max_time": a.tf, "kappa": 0.25}
    if a.scene == "cylinder-lattice":
        # direct_sph_validation of a porous scene reports the permeability and stores no particles; the
        # force-density reduced model's direct reference goes through the reference store like the channel's.
        spec = {"name": "peer", "kind": "reduced_model_2d_force_density",
                "base": {"scene": {"name": a.scene, "n": a.ny, "radius_over_length": a.radius_over_length},
                         "kernel": {"name": "gaussian"},
                         "reference": {"solver": solver},
                         "timing": {"min_repeats": 1, "max_repeats": 1}}}
    else:
        spec = {"name": "peer", "kind": "direct_sph_validation",
                "base": {"scene": {"name": a.scene, "n_y": a.ny, "n_x": a.nx, "wall_model": a.wall_model},
                         "kernel": {"name": "gaussian"}, "solver": solver}}
    if a.scene == "layered-two-phase":
        spec["base"]["scene"]["case"] = a.case
    spec_file = os.path.join(work, "peer_spec.json")
    with open(spec_file, "w") as f:
        json.dump(spec, f, indent=1)
    store = os.path.join(work, "store")
    seconds = run([a.closurelab, "run", spec_file, "--out", os.path.join(work, "closurelab"), "--store", store,
                   "--force"])
    payload = glob.glob(os.path.join(store, "*", "particles.h5part"))
    if len(payload) != 1:
        print("FAILED: expected one reference-store entry in %s, found %d" % (store, len(payload)))
        raise SystemExit(1)
    with open(os.path.join(work, "closurelab", "peer.json")) as f:
        row = json.load(f)["rows"][0]
    return payload[0], row, seconds


def read_closurelab(np, payload):
    import h5py
    with h5py.File(payload, "r") as f:
        last = "Step#%d" % (len([k for k in f.keys() if k.startswith("Step#")]) - 1)
        g = f[last]
        out = {k: np.array(g[k]) for k in ("x", "y", "vx", "vy", "mass", "fixed")}
        out["time"] = float(g.attrs["TimeValue"])
    return out


def read_pysph(np, folder):
    """PySPH's last output file, fluid and solid together, ordered by lattice index."""
    import h5py
    files = sorted(glob.glob(os.path.join(folder, "*.hdf5")), key=lambda s: int(s.rsplit("_", 1)[1].split(".")[0]))
    with h5py.File(files[-1], "r") as f:
        parts = {}
        for name in ("fluid", "solid"):
            g = f["particles"][name]["arrays"]
            parts[name] = {k: np.array(g[k]) for k in ("x", "y", "u", "v", "m", "lattice", "tag")}
        solver = dict(f["solver_data"].attrs)
    cat = {k: np.concatenate([parts["fluid"][k], parts["solid"][k]]) for k in parts["fluid"]}
    cat["fixed"] = np.concatenate([np.zeros(len(parts["fluid"]["x"])), np.ones(len(parts["solid"]["x"]))])
    order = np.argsort(cat["lattice"])
    out = {k: v[order] for k, v in cat.items()}
    out["time"] = float(solver["t"])
    out["count"] = int(solver["count"])
    out["file"] = files[-1]
    return out


def compare(a, work, np):
    cl_payload, row, cl_seconds = closurelab_run(a, work)
    cl = read_closurelab(np, cl_payload)
    pysph_out = os.path.join(work, "pysph")
    py_seconds = run([sys.executable, os.path.join(here, "poiseuille_pysph.py"), "--ny", str(a.ny), "--nx", str(a.nx),
                      "--wall-model", a.wall_model, "--scene", a.scene, "--case", a.case, "--tf", repr(a.tf),
                      "--radius-over-length", repr(a.radius_over_length),
                      "-d", pysph_out] + a.pysph_args.split(),
                     cwd=work)
    py = read_pysph(np, pysph_out)

    n = len(cl["x"])
    failures = []
    if len(py["x"]) != n or not np.array_equal(py["lattice"], np.arange(n)):
        failures.append("particle sets differ: closurelab %d, PySPH %d (lattice indices 0..n-1 expected)"
                        % (n, len(py["x"])))
        print("\n".join(failures))
        return 1
    if np.any(py["tag"] != 0):
        failures.append("PySPH's output holds non-local particles")
    if not np.array_equal(cl["fixed"].astype(bool), py["fixed"].astype(bool)):
        failures.append("wall particles differ")
    mass_rel = float(np.max(np.abs(cl["mass"] - py["m"]) / cl["mass"]))
    cylinders = a.scene == "cylinder-lattice"
    lx = 1.0 if cylinders else a.nx * (1.0 / a.ny)  # eps' = L_y / n_y (channel) or L / n_y (layered, cylinders)
    dx_pos = cl["x"] - py["x"]
    dx_pos -= lx * np.round(dx_pos / lx)  # minimum image (periodic in x)
    dy_pos = cl["y"] - py["y"]
    if cylinders:
        dy_pos -= 1.0 * np.round(dy_pos / 1.0)  # and in y (the cell L = 1)
    dpos = np.hypot(dx_pos, dy_pos)
    dvel = np.hypot(cl["vx"] - py["u"], cl["vy"] - py["v"])
    fluid = cl["fixed"] == 0
    peak = float(np.max(np.hypot(cl["vx"], cl["vy"])[fluid]))
    vel_rel = float(np.max(dvel) / peak)
    pos_abs = float(np.max(dpos))
    worst_v = int(np.argmax(dvel))
    vel_tol = VEL_TOL_CYLINDERS if cylinders else VEL_TOL
    cl_steps = int(row["direct_sph"]["steps"] if cylinders else row["cost"]["steps"])
    if cylinders:
        print("peer: cylinder-lattice n = %d, a/L = %g, t = %r (closurelab %r after %d steps, PySPH %r after %d)"
              % (a.ny, a.radius_over_length, a.tf, cl["time"], cl_steps, py["time"], py["count"]))
    else:
        print("peer: %s%s n_y = %d, n_x = %d, %s walls, t = %r (closurelab %r after %d steps, PySPH %r after %d)"
              % (a.scene, " " + a.case if a.scene == "layered-two-phase" else "", a.ny, a.nx, a.wall_model, a.tf,
                 cl["time"], cl_steps, py["time"], py["count"]))
    print("peer: %d particles (%d fluid); peak |v| %.6g; particle mass relative difference %.3g"
          % (n, int(np.sum(fluid)), peak, mass_rel))
    print("peer: max |v_closurelab - v_pysph| / peak = %.3e (particle %d, y = %.6f); tolerance %.0e"
          % (vel_rel, worst_v, cl["y"][worst_v], vel_tol))
    print("peer: max |q_closurelab - q_pysph| = %.3e L_y = %.3e eps'; tolerance %.0e L_y"
          % (pos_abs, pos_abs * a.ny, POS_TOL))
    print("peer: seconds: closurelab %.2f (run command, whole cell), PySPH %.2f (with its compile when not cached)"
          % (cl_seconds, py_seconds))
    if cl_steps != py["count"]:
        failures.append("step counts differ: closurelab %d, PySPH %d" % (cl_steps, py["count"]))
    if abs(cl["time"] - py["time"]) > 1e-12 * a.tf:
        failures.append("final times differ: %r vs %r" % (cl["time"], py["time"]))
    if mass_rel > 1e-14:
        failures.append("particle masses differ by %.3g (relative)" % mass_rel)
    if not vel_rel <= vel_tol:
        failures.append("velocities differ by %.3e of the peak (> %.0e)" % (vel_rel, vel_tol))
    if not pos_abs <= POS_TOL:
        failures.append("positions differ by %.3e L_y (> %.0e)" % (pos_abs, POS_TOL))
    if not peak > 1e-8:
        failures.append("no flow (peak %.3g): nothing was compared" % peak)
    for msg in failures:
        print("FAIL: " + msg)
    if not failures:
        print("peer: PASS")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
