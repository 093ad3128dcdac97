#!/usr/bin/env python3
"""Runs one case of the bad-input corpus (cases.json): closurelab must exit with the expected code (< 128, so
no signal), say every expected phrase on stderr, and write nothing (the output folder stays absent and the
scratch folder, the working directory, holds only what this script put there).
usage: run_case.py CLOSURELAB CASE_NAME"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

corpus = os.path.dirname(os.path.abspath(__file__))


def main():
    closurelab, name = sys.argv[1], sys.argv[2]
    with open(os.path.join(corpus, "cases.json")) as f:
        case = next(c for c in json.load(f)["cases"] if c["name"] == name)
    tmp = tempfile.mkdtemp(prefix="closurelab_bad_input_")
    try:
        out = os.path.join(tmp, "out")
        if "deep_spec" in case:
            depth = case["deep_spec"]
            with open(os.path.join(tmp, "deep.json"), "w") as f:
                f.write('{"name": "deep", "kind": "direct_sph_validation", "base": ' + "[" * depth + "]" * depth + "}")
        before = sorted(os.listdir(tmp))
        args = [a.replace("{corpus}", corpus).replace("{out}", out).replace("{tmp}", tmp) for a in case["args"]]
        p = subprocess.run([closurelab] + args, cwd=tmp, capture_output=True, text=True, timeout=300)
        problems = []
        if p.returncode < 0 or p.returncode >= 128:
            problems.append(f"killed by a signal or crashed (exit {p.returncode})")
        if p.returncode != case["exit"]:
            problems.append(f"exit {p.returncode}, expected {case['exit']}")
        for phrase in case["message"]:
            if phrase not in p.stderr:
                problems.append(f"stderr lacks {phrase!r}")
        if os.path.exists(out):
            problems.append(f"{out} was created")
        after = sorted(os.listdir(tmp))
        if after != before:
            problems.append(f"files written to the working directory: {sorted(set(after) - set(before))}")
        if problems:
            print(f"case {name}: " + "; ".join(problems))
            print("stderr:\n" + p.stderr[-3000:])
            return 1
        print(f"case {name}: exit {p.returncode}, message ok, nothing written")
        return 0
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
