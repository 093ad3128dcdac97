#!/usr/bin/python3
"""PySPH 1.0b1's Taylor-Green example (pysph/examples/taylor_green.py, TVFScheme) with the transport velocity equal
to the velocity at t = 0, as closurelab's engine starts it (core/sph/transport_velocity.hpp; the example leaves
uhat = 0 at its first evaluation), printing at each output the time, the largest particle speed, the exact one
U exp(-8 pi^2 t / Re) and their relative difference, then the particles against the exact field at the last output
(max |v - v_exact| / max|v_exact| and the relative L2 norm, as closurelab's particles_vs_exact).

    /usr/bin/python3 scripts/peer_taylor_green.py --nx 25 --tf 0.5 --pfreq 55 -d OUTDIR [--perturb 0.3 --hdx 1.5]

(pfreq 55 steps = 0.05 at nx = 25.) Every option is the example's own; --perturb draws numpy.random.seed(1) shifts,
which closurelab's scene option `perturbation` reproduces (core/base/numpy_uniform.hpp).

    /usr/bin/python3 scripts/peer_taylor_green.py --start-only FILE --nx 16 --perturb 0.3

writes the example's initial particles (x y u v per line, %.17g, PySPH's order) to FILE and runs nothing.
Needs Debian's python3-pysph.
"""
import sys

import numpy as np
from pysph.examples.taylor_green import TaylorGreen, exact_solution
from pysph.solver.utils import get_files, load


class TaylorGreenFromTransportEqualsVelocity(TaylorGreen):
    def create_particles(self):
        [fluid] = super().create_particles()
        fluid.uhat[:] = fluid.u
        fluid.vhat[:] = fluid.v
        return [fluid]


def exact_max_speed(app, t):
    return np.exp(-8.0 * np.pi**2 * t / app.options.re)


if __name__ == '__main__':
    start_only = None
    if '--start-only' in sys.argv:
        k = sys.argv.index('--start-only')
        start_only = sys.argv[k + 1]
        del sys.argv[k:k + 2]
        sys.argv += ['--disable-output']
    app = TaylorGreenFromTransportEqualsVelocity()
    if start_only is not None:
        app._parse_command_line(force=True)
        app.consume_user_options()
        fluid = app.create_fluid()
        np.savetxt(start_only, np.column_stack([fluid.x, fluid.y, fluid.u, fluid.v]), fmt='%.17g')
        sys.exit(0)
    app.run()
    b = -8.0 * np.pi**2 / app.options.re
    print("# t max|v| exact relative_error")
    last = None
    for f in get_files(app.output_dir):
        data = load(f)
        fl = data['arrays']['fluid']
        t = data['solver_data']['t']
        v, e = np.sqrt(fl.u**2 + fl.v**2).max(), exact_max_speed(app, t)
        print("%.6f %.16e %.16e %.6e" % (t, v, e, abs(v - e) / e))
        last = (t, fl)
    t, fl = last
    ue, ve, _ = exact_solution(U=1.0, b=b, t=t, x=fl.x, y=fl.y)
    d2 = (fl.u - ue)**2 + (fl.v - ve)**2
    scale = exact_max_speed(app, t)
    print("# particles vs exact at t = %.6f: max_rel %.6e l2_rel %.6e (%d particles)" % (
        t, np.sqrt(d2.max()) / scale, np.sqrt(d2.sum() / (ue**2 + ve**2).sum()), len(fl.x)))
