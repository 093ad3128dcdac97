#!/usr/bin/env python3
"""python/closurelab/fields.py writes a cylinder row's coarse fields as XDMF + HDF5 that a reader opens: the XDMF
parses, every DataItem names a dataset of the .h5 (opened with h5py) of the declared dimensions, the topology's
dimensions are the geometry's node counts (ny nx), and the values are the row's (node (i, j) at flat j * nx + i;
difference = reduced - direct; outside_solid 1/0). A table without 2D fields is refused (exit 2, nothing written).

Usage: python3 tests/python/test_fields_xdmf.py   (from the repository root; exit 1 on a failure, 77 when h5py or
numpy is not importable: Debian's python3-h5py, scripts/install_deps.sh)
"""
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
try:
    import h5py
    import numpy as np
except ImportError as e:
    print(f"test_fields_xdmf: SKIP: {e} (under {sys.executable})")
    sys.exit(77)

SCRIPT = os.path.join(ROOT, "python", "closurelab", "fields.py")
TABLE = os.path.join(ROOT, "results", "cylinders", "reduced", "reduced.json")
LABEL = "a=0.2L n=192"


def main():
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    raw = json.load(open(TABLE))
    row = next(r for r in raw["rows"] if r["label"] == LABEL)
    f = row["fields"]
    nx, ny = len(f["x"]), len(f["y"])
    with tempfile.TemporaryDirectory() as tmp:
        r = subprocess.run([sys.executable, SCRIPT, TABLE, tmp, "--row", LABEL], capture_output=True, text=True)
        check(r.returncode == 0, f"fields.py exit {r.returncode}: {r.stderr.strip()[-400:]}")
        xdmfs = [p for p in os.listdir(tmp) if p.endswith(".xdmf")]
        check(len(xdmfs) == 1, f"one .xdmf expected, got {xdmfs}")
        check(all(f"fields: wrote {os.path.join(tmp, p)}" in r.stdout for p in xdmfs + ["reduced.h5"]),
              f"paths not printed: {r.stdout}")
        if not xdmfs:
            return report(failures)
        doc = ET.parse(os.path.join(tmp, xdmfs[0])).getroot()
        grid = doc.find("Domain/Grid")
        check(grid is not None and grid.get("Name") == LABEL, "the grid is not named by the row's label")
        topo = grid.find("Topology")
        check(topo.get("TopologyType") == "2DRectMesh" and topo.get("Dimensions") == f"{ny} {nx}",
              f"topology {topo.attrib}")
        geo = grid.find("Geometry")
        check(geo.get("GeometryType") == "VXVY", f"geometry {geo.attrib}")
        values = {}
        for item in grid.iter("DataItem"):
            h5file, _, path = item.text.strip().partition(":")
            with h5py.File(os.path.join(tmp, h5file), "r") as h5:
                if path not in h5:
                    failures.append(f"DataItem {item.text.strip()}: no such dataset")
                    continue
                data = h5[path][()]
            dims = tuple(int(d) for d in item.get("Dimensions").split())
            check(data.shape == dims, f"{path}: shape {data.shape}, declared {dims}")
            values[path.rsplit("/", 1)[-1]] = data
        gx, gy = [values.get(k) for k in ("x", "y")]
        check(gx is not None and np.array_equal(gx, f["x"]) and np.array_equal(gy, f["y"]), "geometry != fields x, y")
        names = {a.get("Name") for a in grid.findall("Attribute")}
        for name in ("reduced", "direct_average", "difference", "reduced_speed", "outside_solid",
                     "reduced_density_deviation"):
            check(name in names and name in values, f"attribute {name} missing")
        if failures:
            return report(failures)
        i, j = 5, 9
        k = j * nx + i
        check(values["reduced"][j, i, 0] == f["reduced"]["vx"][k] and values["reduced"][j, i, 1] == f["reduced"]["vy"][k]
              and values["reduced"][j, i, 2] == 0.0, "reduced at (i, j) is not the row's flat j * nx + i")
        check(np.allclose(values["difference"], values["reduced"] - values["direct_average"], rtol=0, atol=0),
              "difference != reduced - direct_average")
        check(np.array_equal(values["outside_solid"].ravel(), np.array(f["outside_solid"], dtype=np.int8)),
              "outside_solid differs")
        check(abs(values["reduced_speed"][j, i] - np.hypot(f["reduced"]["vx"][k], f["reduced"]["vy"][k])) < 1e-18,
              "reduced_speed")
        # a column model's table has no 2D fields: refused, nothing written
        empty = os.path.join(tmp, "none")
        r = subprocess.run([sys.executable, SCRIPT, os.path.join(ROOT, "results", "paper", "fig2", "fig2.json"), empty],
                           capture_output=True, text=True)
        check(r.returncode == 2 and not os.path.exists(empty), f"fig2: exit {r.returncode}, wrote {os.path.exists(empty)}")
    return report(failures)


def report(failures):
    for msg in failures:
        print("test_fields_xdmf: " + msg, file=sys.stderr)
    print(f"test_fields_xdmf: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
