#!/usr/bin/python3
"""PySPH 1.0b1's Taylor-Green example (pysph/examples/taylor_green.py, TVFScheme) with the transport velocity equal
to the velocity at t = 0, as closurelab's engine starts it (core/sph/transport_velocity.hpp; the example leaves
uhat = 0 at its first evaluation), printing the largest particle speed at each output.

    /usr/bin/python3 scripts/peer_taylor_green.py --nx 25 --tf 0.5 --pfreq 55 -d OUTDIR

prints "t max|v|" per output file (pfreq 55 steps = 0.05 at nx = 25). Needs Debian's python3-pysph.
"""
import sys

import numpy as np
from pysph.examples.taylor_green import TaylorGreen
from pysph.solver.utils import get_files, load


class TaylorGreenFromTransportEqualsVelocity(TaylorGreen):
    def create_particles(self):
        [fluid] = super().create_particles()
        fluid.uhat[:] = fluid.u
        fluid.vhat[:] = fluid.v
        return [fluid]


if __name__ == '__main__':
    app = TaylorGreenFromTransportEqualsVelocity()
    app.run()
    for f in get_files(app.output_dir):
        data = load(f)
        fl = data['arrays']['fluid']
        print("%.4f %.16e" % (data['solver_data']['t'], np.sqrt(fl.u**2 + fl.v**2).max()))
