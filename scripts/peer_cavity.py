#!/usr/bin/python3
"""PySPH 1.0b1's lid-driven cavity (pysph/examples/cavity.py: TVFScheme with the generalized wall condition of
Adami, Hu & Adams 2012, solid walls 5 layers deep, the lid's solid particles moving at Umax = 1, c0 = 10, Re = 100)
run as written, its final fluid particles written as `x y u v` per line (%.17g, PySPH's order, PySPH's coordinates:
the fluid fills [0, L]^2) to FILE; with --centreline, also u(y) at x = L/2 and v(x) at y = L/2 at Ghia's points,
interpolated as cavity.py's post-processing does (pysph.tools.interpolator.Interpolator, Shepard) from the last
output only.

    /usr/bin/python3 scripts/peer_cavity.py FILE --nx 20 --tf 0.5 -d OUTDIR [--re 100] [--centreline CSV]

closurelab's scene `lid-driven-cavity` is the same flow with its walls at x, y < w and > w + L (w the walls'
thickness); tests/peer/test_cavity_peer.cpp compares the two engines' particles. Needs Debian's python3-pysph.
"""
import sys

import numpy as np
from pysph.examples.cavity import LidDrivenCavity
from pysph.solver.utils import get_files, load

if __name__ == '__main__':
    out = sys.argv[1]
    del sys.argv[1]
    centreline = None
    if '--centreline' in sys.argv:
        k = sys.argv.index('--centreline')
        centreline = sys.argv[k + 1]
        del sys.argv[k:k + 2]
    app = LidDrivenCavity()
    app.run()
    last = get_files(app.output_dir)[-1]
    data = load(last)
    fl = data['arrays']['fluid']
    np.savetxt(out, np.column_stack([fl.x, fl.y, fl.u, fl.v]), fmt='%.17g',
               header='PySPH 1.0b1 cavity.py %s, t = %.17g' % (' '.join(sys.argv[1:]), data['solver_data']['t']))
    if centreline is not None:
        from pysph.tools.interpolator import Interpolator
        from pysph.examples.ghia_cavity_data import get_u_vs_y, get_v_vs_x
        y, _ = get_u_vs_y()
        x, _ = get_v_vs_x()
        arrays = list(data['arrays'].values())
        iu = Interpolator(arrays, x=0.5 * np.ones_like(y), y=np.asarray(y, dtype=float))
        iv = Interpolator(arrays, x=np.asarray(x, dtype=float), y=0.5 * np.ones_like(x))
        with open(centreline, 'w') as f:
            f.write('# line coordinate value\n')
            for c, v in zip(y, iu.interpolate('u')):
                f.write('u_vs_y %.17g %.17g\n' % (c, v))
            for c, v in zip(x, iv.interpolate('v')):
                f.write('v_vs_x %.17g %.17g\n' % (c, v))
