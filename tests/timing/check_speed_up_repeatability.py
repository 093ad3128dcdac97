#!/usr/bin/env python3
"""Two identical runs of a front give speed-ups within their stated spread (the timing acceptance).

Usage: python3 tests/timing/check_speed_up_repeatability.py CLOSURELAB SPEC.json WORK_DIR
           [--cells LABEL[|LABEL...]] [--tolerance range|spread|resolved] [--measure wall|cpu]
Runs SPEC (or, with --cells, the same spec with only the cells of those labels, unchanged) twice into
WORK_DIR/run1 and WORK_DIR/run2 with one reference store, WORK_DIR/store (so both divide the same direct SPH
time and the check is about the reduced model's repeated timing; the store is kept, so a second invocation
reuses the direct SPH), then, per cell, compares the two speed-ups (direct time over the fastest reduced run):
  --tolerance range   (default) they differ by no more than the larger of the two recorded ranges,
                      (max - min) / min of the repeated reduced runs;
  --tolerance spread  the second lies within the first's recorded spread, (median - min) / min:
                      |s2 - s1| / s1 <= spread1 (the acceptance's wording; tighter);
  --tolerance resolved  as spread, with the spread no smaller than the stopping rule's stability (the row's
                      params.timing.stability, 2 % by default): the rule calls the minimum stable once the last
                      runs lower it by no more than that, so a minimum is determined to it and no better.
--measure wall (default) compares the rows' speed_up (wall time); --measure cpu the same ratio in process CPU time
(reduced_timing.cpu: both runs divide the same direct run, so the speed-up ratio is the ratio of the reduced runs'
least CPU times, whether or not the direct record has a CPU time), which a loaded machine's preemption does not
inflate. Prints every cell's pair with both measures. ctest label `timing`: the result depends on the machine's load, so
scripts/test.sh and CI leave it out (`ctest -L timing` runs it); a failure says the recorded measure understates
the variation between two runs on that machine.
"""
import argparse
import json
import os
import subprocess
import sys


def stability(row):
    return row.get("params", {}).get("timing", {}).get("stability", 0.0)


def speed_ups(table, measure):
    out = {}
    for r in json.load(open(table))["rows"]:
        c = r.get("cost", {})
        t = c.get("reduced_timing") or {}
        if r.get("status") != "ok" or not c.get("speed_up") or t.get("repeats", 0) <= 1:
            continue
        if measure == "cpu":
            cpu = t["cpu"]
            # the direct run's time over the reduced runs' least CPU time (the same direct run in both runs)
            out[r["id"]] = (r["label"], c["direct_sph_wall_seconds"] / cpu["min_seconds"], cpu["range"], cpu["spread"],
                            t["repeats"], stability(r))
        else:
            out[r["id"]] = (r["label"], c["speed_up"], t["range"], t["spread"], t["repeats"], stability(r))
    return out


def selected_spec(spec_file, labels, work):
    """The spec itself, or a copy in WORK_DIR with only the cells whose labels are given (nothing else changed)."""
    if not labels:
        return spec_file
    spec = json.load(open(spec_file))
    cells = [c for c in spec.get("cells", []) if c.get("label") in labels]
    missing = set(labels) - {c["label"] for c in cells}
    if missing:
        sys.exit(f"check_speed_up_repeatability: no cell labelled {sorted(missing)} in {spec_file}")
    spec["cells"] = cells
    path = os.path.join(work, os.path.basename(spec_file))
    os.makedirs(work, exist_ok=True)
    json.dump(spec, open(path, "w"), indent=1)
    return path


def within(tolerance, s1, s2, p1, p2, q1, resolution):
    if tolerance == "spread":
        return abs(s2 - s1) / s1 <= q1
    if tolerance == "resolved":
        return abs(s2 - s1) / s1 <= max(q1, resolution)
    return abs(s1 - s2) / min(s1, s2) <= max(p1, p2)


def main(exe, spec_file, work, labels, tolerance, measure):
    spec = selected_spec(spec_file, labels, work)
    name = json.load(open(spec))["name"]
    store = os.path.join(work, "store")
    tables = []
    for k in (1, 2):
        out = os.path.join(work, f"run{k}")
        subprocess.run(["rm", "-rf", out], check=True)  # no cached cell: both runs compute every cell
        subprocess.run([exe, "run", spec, "--out", out, "--store", store], check=True, stdout=subprocess.DEVNULL)
        tables.append(speed_ups(os.path.join(out, name + ".json"), measure))
    failures, checked = 0, 0
    for cid, (label, s1, p1, q1, n1, res1) in sorted(tables[0].items()):
        if cid not in tables[1]:
            continue
        _, s2, p2, q2, n2, _ = tables[1][cid]
        checked += 1
        ok = within(tolerance, s1, s2, p1, p2, q1, res1)
        failures += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {label}: speed-ups {s1:.4g} and {s2:.4g} ({n1} and {n2} timed runs) differ "
              f"by {100 * abs(s2 - s1) / s1:.1f} % of the first; spreads {100 * q1:.1f} % and {100 * q2:.1f} %, "
              f"ranges {100 * p1:.1f} % and {100 * p2:.1f} % (tolerance: {tolerance}, {measure} time)")
    print(f"{checked - failures} passed, {failures} failed")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("closurelab")
    parser.add_argument("spec")
    parser.add_argument("work_dir")
    parser.add_argument("--cells", default="", help="LABEL[|LABEL...]: only these cells of SPEC")
    parser.add_argument("--tolerance", choices=("range", "spread", "resolved"), default="range")
    parser.add_argument("--measure", choices=("wall", "cpu"), default="wall")
    a = parser.parse_args()
    sys.exit(main(a.closurelab, a.spec, a.work_dir, [x for x in a.cells.split("|") if x], a.tolerance, a.measure))
