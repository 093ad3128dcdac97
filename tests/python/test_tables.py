#!/usr/bin/env python3
"""python/closurelab/tables.py reads the committed tables: `load` gives one record per row and one dotted column per
leaf of params, errors and cost, with the JSON's values; `load_fields` gives a 2D row's fields as (ny, nx) arrays in
the documented order (node (i, j) at flat j * nx + i), a column row's profile as 1D arrays, and refuses a failed row.
With CLOSURELAB (the executable) given and built, the columns equal those of `closurelab export --csv`.

Usage: python3 tests/python/test_tables.py [CLOSURELAB]   (from the repository root; exit 1 on a failure, 77 when
pandas is not importable: Debian's python3-pandas, scripts/install_deps.sh)
"""
import csv
import io
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python"))
try:
    import numpy as np
    import pandas  # noqa: F401
except ImportError as e:
    print(f"test_tables: SKIP: {e} (under {sys.executable}; Debian: apt-get install python3-pandas)")
    sys.exit(77)
from closurelab.tables import load, load_fields  # noqa: E402

CYLINDERS = os.path.join(ROOT, "results", "cylinders", "reduced", "reduced.json")
CHANNEL = os.path.join(ROOT, "results", "paper", "fig2", "fig2.json")
WALLS = os.path.join(ROOT, "results", "walls_2d", "reduced", "walls_2d_reduced.json")
CELLULAR = os.path.join(ROOT, "results", "cellular", "reduced", "reduced.json")


def main(exe=None):
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    raw = json.load(open(CYLINDERS))
    df = load(CYLINDERS)
    check(len(df) == len(raw["rows"]), f"cylinders: {len(df)} records for {len(raw['rows'])} rows")
    check(list(df.columns[:3]) == ["id", "label", "status"], f"cylinders: first columns {list(df.columns[:3])}")
    check(df.attrs.get("kind") == raw["kind"], "cylinders: attrs kind")
    for col in ("params.scene.n", "params.scene.radius_over_length", "errors.vs_averaged_direct_sph.all_nodes.max_rel",
                "errors.permeability.reduced_vs_direct_sph", "cost.reduced_timing.min_seconds", "cost.speed_up"):
        check(col in df.columns, f"cylinders: no column {col}")
    check(not any(c.startswith(("fields", "profile")) for c in df.columns), "cylinders: fields flattened into columns")
    for k, row in enumerate(raw["rows"]):
        rec = df.iloc[k]
        check(rec["label"] == row["label"] and rec["status"] == row["status"], f"cylinders row {k}: label/status")
        want = row.get("errors", {}).get("permeability", {}).get("reduced_vs_direct_sph")
        got = rec["errors.permeability.reduced_vs_direct_sph"]
        check((want is None and got != got) or got == want, f"cylinders row {k}: permeability {got} != {want}")
        check(rec["params.scene.n"] == row["params"]["scene"]["n"], f"cylinders row {k}: params.scene.n")
    check(df["errors.vs_averaged_direct_sph.all_nodes.max_rel"].dtype.kind == "f", "cylinders: errors not float")
    failed = df[df.status == "error"]
    check(len(failed) == 1 and "square operator" in str(failed.iloc[0]["message"]), "cylinders: the failed row's message")

    # fields: a record of load() and the raw dict give the same arrays, in the documented order
    rec = df[df.label == "a=0.2L n=192"].iloc[0]
    row = next(r for r in raw["rows"] if r["label"] == "a=0.2L n=192")
    f, g = load_fields(rec), load_fields(row)
    nx, ny = len(row["fields"]["x"]), len(row["fields"]["y"])
    for name in ("reduced_vx", "reduced_vy", "direct_average_vx", "direct_average_vy", "reduced_density_deviation",
                 "outside_solid"):
        check(name in f and f[name].shape == (ny, nx), f"fields: {name} missing or not ({ny}, {nx})")
        check(name in g and np.array_equal(f[name], g[name]), f"fields: {name} differs between record and dict")
    check(f["outside_solid"].dtype == bool, "fields: outside_solid not boolean")
    i, j = 3, 11
    check(f["reduced_vx"][j, i] == row["fields"]["reduced"]["vx"][j * nx + i], "fields: not flat j * nx + i")
    check(f["x"][i] == row["fields"]["x"][i] and f["y"][j] == row["fields"]["y"][j], "fields: axes")
    # the node in the cylinder's centre is solid, a corner node is not
    c = np.argmin(np.abs(f["x"] - 0.5)), np.argmin(np.abs(f["y"] - 0.5))
    check(not f["outside_solid"][c[1], c[0]] and f["outside_solid"][0, 0], "fields: outside_solid at the centre/corner")
    try:
        load_fields(failed.iloc[0])
        check(False, "fields: a failed row gave fields")
    except ValueError:
        pass

    # a walled channel through the 2D model: one column
    w = load_fields(load(WALLS).iloc[0])
    check(w["reduced_vx"].shape[1] == 1, f"walls: {w['reduced_vx'].shape} is not one column")
    # the 2D mesh model: averaged_analytic too
    cel = load_fields(load(CELLULAR).iloc[0])
    check("averaged_analytic_vx" in cel, "cellular: no averaged_analytic")

    # a column table: profile arrays, the legacy node set read as fluid_nodes
    ch_raw = json.load(open(CHANNEL))
    ch = load(CHANNEL)
    check("errors.vs_averaged_direct_sph.all_nodes.max_rel" in ch.columns, "channel: no all_nodes column")
    check(not any(".all." in c for c in ch.columns), "channel: a legacy 'all' node set left as it was")
    p = load_fields(ch.iloc[0])
    check(set(p) >= {"y", "reduced", "analytic"} and p["y"].ndim == 1 and
          np.array_equal(p["reduced"], np.array(ch_raw["rows"][0]["profile"]["reduced"])), "channel: profile arrays")

    if exe and os.path.exists(exe):
        # (a table with the legacy node set "all" is renamed by load, not by export: compared on a current one)
        for path, frame in ((CYLINDERS, df), (WALLS, None)):
            r = subprocess.run([exe, "export", path, "--csv"], capture_output=True, text=True)
            if r.returncode != 0:
                failures.append(f"export {path}: exit {r.returncode}: {r.stderr.strip()[-300:]}")
                continue
            header = next(csv.reader(io.StringIO(r.stdout)))
            frame = frame if frame is not None else load(path)
            mine = [c for c in frame.columns if c != "table"]
            rows = list(csv.DictReader(io.StringIO(r.stdout)))
            check([row["message"] or None for row in rows] == [m if isinstance(m, str) and m else None for m in frame["message"]],
                  f"export {os.path.basename(path)}: the message column differs from load's")
            check(sorted(header) == sorted(mine),
                  f"export {os.path.basename(path)}: columns differ: only export {sorted(set(header) - set(mine))[:5]}, "
                  f"only load {sorted(set(mine) - set(header))[:5]}")
    else:
        print("test_tables: closurelab not given or not built: the comparison with `closurelab export` skipped")
    for msg in failures:
        print("test_tables: " + msg, file=sys.stderr)
    print(f"test_tables: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else None))
