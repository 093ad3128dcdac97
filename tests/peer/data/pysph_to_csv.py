"""Writes a PySPH output file as closurelab's particle CSV (x,y,vx,vy,mass,phase,fixed), read with PySPH's own
loader (pysph.solver.utils.load), arrays in name order, `solid` held fixed: the same particles that
core/io/pysph_output.cpp reads from the .hdf5, for the test that both give the same closure.

  /usr/bin/python3 tests/peer/data/pysph_to_csv.py IN.hdf5 OUT.csv
"""
import sys

from pysph.solver.utils import load

data = load(sys.argv[1])
with open(sys.argv[2], "w") as out:
    out.write("# from %s (PySPH output, t = %r)\n" % (sys.argv[1].rsplit("/", 1)[-1], float(data["solver_data"]["t"])))
    out.write("x,y,vx,vy,mass,phase,fixed\n")
    for name in sorted(data["arrays"]):
        pa = data["arrays"][name]
        fixed = 1 if name == "solid" else 0
        for k in range(pa.get_number_of_particles()):
            out.write("%r,%r,%r,%r,%r,0,%d\n" % (float(pa.x[k]), float(pa.y[k]), float(pa.u[k]), float(pa.v[k]),
                                                 float(pa.m[k]), fixed))
