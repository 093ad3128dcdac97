"""PySPH's own example of flow through a periodic square lattice of cylinders, pysph/examples/lattice_cylinders.py
(PySPH 1.0b1, Debian python3-pysph), run as it is written but at a chosen resolution, as a peer of closurelab's
cylinder-lattice permeability (results/cylinders/direct): an independent scheme, so the comparison is the Darcy
permeability against the Darcy permeability, not particle against particle.

  /usr/bin/python3 scripts/peer_lattice_cylinders.py --nx 48 [--tf 10000] [--fx-factor 1] [--sound-factor 1] [--window-over-tau 1.25]
        [--tol 1e-4] [--every 10] [--out FILE.json] [--save-particles FILE.npz] [-- PYSPH_OPTIONS ...]

The example (unchanged, imported; only its module constants that follow from the resolution are recomputed):
  - a square cell of side L = 0.1, periodic in x and y, one cylinder of radius a = 0.02 = 0.2 L at its centre
    (solid fraction c = pi a^2 / L^2 = 0.1257, as closurelab's cylinder-lattice at radius_over_length 0.2);
  - the transport-velocity formulation (Adami, Hu & Adams 2013, PySPH's TVFScheme): summation density,
    Tait-like state equation with background pressure p0 = c0^2 rho0, Adami's solid-wall pressure and no-slip
    conditions on the solid particles (lattice sites with r <= a; fluid r > a), quintic spline with h = dx,
    predictor-corrector integration at the fixed dt = min(0.25 h/(c0 + Umax), 0.125 h^2/nu, 0.25 sqrt(h/fx));
  - rho0 = 1000, nu = a Umax / Re = 1e-6 (Umax = 5e-5, Re = 1), c0 = 10 Umax, body force fx = 1.5e-7 on the fluid;
    the example's own resolution is nx = 100 and tf = 1000.
--nx sets the lattice (dx = L/nx, and the dt above with it); --fx-factor scales fx (Stokes flow is linear in fx:
at 0.1 the Reynolds and Mach numbers fall tenfold, the check that the example's Re ~ 1 leaves k unchanged);
--sound-factor scales the example's velocity scale Umax and with it c0 = 10 Umax, p0 = c0^2 rho0 and the CFL step,
nu kept (at --fx-factor 10 the flow is about eight times faster: --sound-factor 10 keeps the Mach number near the
example's, as closurelab's scene scales its sound speed with sqrt(g L)).

The permeability: k = nu <u> / fx with <u> the superficial velocity, sum_fluid m u / (rho0 L^2) (the particle mass
is rho0 dx^2, so this is closurelab's sum_fluid u dx^2 / L^2), taken every --every steps. Steady state by k itself:
k wobbles by a few 0.1 % with a period of a few hundred time units (the cell's sound time L/c0 is 200: c0 = 10 Umax
is slow), so the run stops when the mean of k over the last window differs from the mean over the window before by
less than --tol (relative), the window --window-over-tau relaxation times tau = k_ref / nu = 329 (k_ref the Stokes
permeability), or at --tf; the result is the mean over the last window, with its least and largest value. The
output (--out, JSON) holds the parameters, the history of k, the result, k / L^2 against the square array's Stokes
permeability (closurelab's boundary-collocation solve, core/scenes/square_array_stokes.cpp: k/L^2 = 0.032948 at
c = 0.1257; Sangani & Acrivos 1982) and the wall time.
--save-particles writes the final state's local particles (numpy .npz: fluid_x, fluid_y, fluid_u, fluid_v, fluid_m
and solid_x, ... alike; SI units of the example) for scripts/peer_lattice_cylinders_field.py.
Arguments after "--" go to PySPH's Application (e.g. --openmp); output files are disabled unless given there.
"""

import argparse
import json
import math
import os
import platform
import sys
import time

import pysph
import pysph.examples.lattice_cylinders as lc

# closurelab's Stokes solve of the square array at c = pi 0.2^2 (results/cylinders/direct/table.md).
K_REF_OVER_L2 = 0.032948


def configure(nx, fx_factor, tf, sound_factor=1.0):
    """The example's module constants at lattice nx: the same formulas as its module body."""
    if sound_factor != 1.0:  # nu = a Umax / Re stays the example's
        lc.Umax = 5e-5 * sound_factor
        lc.c0 = 10 * lc.Umax
        lc.p0 = lc.c0 * lc.c0 * lc.rho0
    lc.nx = nx
    lc.dx = lc.L / nx
    lc.ghost_extent = 5 * 1.5 * lc.dx
    lc.h0 = lc.hdx * lc.dx
    lc.fx = 1.5e-7 * fx_factor
    lc.dt_cfl = 0.25 * lc.h0 / (lc.c0 + lc.Umax)
    lc.dt_viscous = 0.125 * lc.h0 ** 2 / lc.nu
    lc.dt_force = 0.25 * math.sqrt(lc.h0 / abs(lc.fx))
    lc.tf = tf
    lc.dt = min(lc.dt_cfl, lc.dt_viscous, lc.dt_force)


class PermeabilityWatch(lc.LatticeCylinders):
    """The example, with k taken every `every` steps and the run stopped at steady state."""

    def setup_watch(self, every, window, tol):
        self.every, self.window, self.tol = every, window, tol
        self.history = []  # (t, k)
        self.steady_at = None

    def permeability(self):
        fluid = [pa for pa in self.particles if pa.name == "fluid"][0]
        local = fluid.tag == 0  # the arrays also hold the periodic images (tag 2)
        mean_u = float((fluid.m * fluid.u)[local].sum()) / (lc.rho0 * lc.L * lc.H)
        return lc.nu * mean_u / lc.fx

    def post_step(self, solver):
        count = solver.count + 1  # this step's number; solver.t is its start time
        if count % self.every:
            return
        t = solver.t + solver.dt
        k = self.permeability()
        self.history.append((t, k))
        # k wobbles (period a few hundred): compare the means over the last two windows.
        if t < 2 * self.window or self.steady_at is not None:
            return
        last = [kk for tt, kk in self.history if tt > t - self.window]
        before = [kk for tt, kk in self.history if t - 2 * self.window < tt <= t - self.window]
        m1, m0 = sum(last) / len(last), sum(before) / len(before)
        if m1 != 0.0 and abs(m1 - m0) <= self.tol * abs(m1):
            self.steady_at = t
            solver.max_steps = solver.count + 1  # the loop ends after this step


def main():
    argv = sys.argv[1:]
    rest = []
    if "--" in argv:
        rest = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--nx", type=int, default=48)
    ap.add_argument("--tf", type=float, default=10000.0, help="the longest model time (the example's: 1000)")
    ap.add_argument("--fx-factor", type=float, default=1.0)
    ap.add_argument("--sound-factor", type=float, default=1.0,
                    help="scales Umax, c0 = 10 Umax and p0 = c0^2 rho0 (nu kept)")
    ap.add_argument("--window-over-tau", type=float, default=1.25,
                    help="the steady test's window in tau = k_ref/nu (1.25: 412, two sound periods L/c0)")
    ap.add_argument("--tol", type=float, default=1e-4)
    ap.add_argument("--every", type=int, default=10)
    ap.add_argument("--out", default="")
    ap.add_argument("--save-particles", default="", help="the final local particles, .npz")
    a = ap.parse_args(argv)

    configure(a.nx, a.fx_factor, a.tf, a.sound_factor)
    tau = K_REF_OVER_L2 * lc.L ** 2 / lc.nu
    app = PermeabilityWatch(fname="lattice_cylinders_nx%d" % a.nx)
    app.setup_watch(a.every, a.window_over_tau * tau, a.tol)
    pysph_args = list(rest)
    if not any(o.startswith("--disable-output") or o.startswith("--pfreq") for o in pysph_args):
        pysph_args.append("--disable-output")
    if not any(o.startswith("-d") or o.startswith("--directory") for o in pysph_args):
        pysph_args += ["-d", os.path.join("/tmp", "peer_lattice_cylinders_nx%d" % a.nx)]
    t0 = time.time()
    app.run(pysph_args)
    seconds = time.time() - t0
    if not app.history or app.history[-1][0] < app.solver.t * (1 - 1e-12):  # the final state, between samples
        app.history.append((app.solver.t, app.permeability()))

    t_end, k = app.history[-1]
    window = [kk / lc.L ** 2 for tt, kk in app.history if tt > t_end - app.window]
    k_l2 = sum(window) / len(window)  # the mean over the last window
    fluid = [pa for pa in app.particles if pa.name == "fluid"][0]
    u_max = float(max(math.hypot(u, v) for u, v, tag in zip(fluid.u, fluid.v, fluid.tag) if tag == 0))
    result = {
        "script": "scripts/peer_lattice_cylinders.py",
        "pysph": getattr(pysph, "__version__", "?"),
        "host": platform.node(),
        "argv": sys.argv[1:],
        "nx": a.nx, "dx": lc.dx, "dt": lc.dt, "fx": lc.fx, "nu": lc.nu, "c0": lc.c0, "rho0": lc.rho0,
        "particles": {pa.name: int((pa.tag == 0).sum()) for pa in app.particles},  # local, no periodic images
        "tau": tau, "window": a.window_over_tau * tau, "tol": a.tol,
        "steps": int(app.solver.count), "t_end": t_end, "steady": app.steady_at is not None,
        "k_over_L2": k_l2, "k_vs_reference": k_l2 / K_REF_OVER_L2 - 1.0,
        "k_over_L2_last": k / lc.L ** 2, "k_over_L2_last_window_min_max": [min(window), max(window)],
        "reference_k_over_L2": K_REF_OVER_L2,
        "reynolds_a_mean": (k * lc.fx / lc.nu) * lc.a / lc.nu,
        "mach_max": u_max / lc.c0,
        "wall_seconds": seconds,
        "history": [[t, kk / lc.L ** 2] for t, kk in app.history],
    }
    print("peer_lattice_cylinders: nx = %d, %d steps to t = %.6g (%s), k/L^2 = %.6f over the last window "
          "(%+.2f %% vs %.6f; in [%.6f, %.6f]), Re = %.3g, Mach = %.3g, %.0f s"
          % (a.nx, result["steps"], t_end, "steady" if result["steady"] else "NOT steady: stopped at tf", k_l2,
             100 * result["k_vs_reference"], K_REF_OVER_L2, min(window), max(window), result["reynolds_a_mean"],
             result["mach_max"], seconds))
    if a.save_particles:
        import numpy as np
        arrays = {}
        for pa in app.particles:
            local = pa.tag == 0
            for prop in ("x", "y", "u", "v", "m"):
                arrays["%s_%s" % (pa.name, prop)] = np.asarray(getattr(pa, prop))[local].astype(np.float64)
        np.savez_compressed(a.save_particles, **arrays)
    if a.out:
        with open(a.out, "w") as f:
            json.dump(result, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
