#!/usr/bin/env python3
"""Regenerates every committed summary (the lines of committed_summaries.txt) from the committed tables into a
temporary folder and compares each Markdown file byte for byte with the committed one (figures are not
compared: their bytes depend on the matplotlib version), and the index results/README.md with results_index.py's
output. Run from the repository root; exit 1 on a difference.

Usage: python3 experiments/summaries/check_summaries.py
"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    failures, checked = [], 0
    with tempfile.TemporaryDirectory() as tmp, open(os.path.join(HERE, "committed_summaries.txt")) as f:
        for line in f:
            args = line.split()
            if not args:
                continue
            tables = [a for a in args if a.endswith(".json")]
            out = next((a for a in args if not a.endswith(".json")), os.path.dirname(tables[0]))
            scratch = os.path.join(tmp, out)
            env = dict(os.environ, MPLBACKEND="Agg", CLOSURELAB_FIGURES="off")  # figures are not compared
            r = subprocess.run([sys.executable, os.path.join(HERE, "summarize.py"), *tables, scratch],
                               capture_output=True, text=True, env=env)
            if r.returncode != 0:
                failures.append(f"{line.strip()}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
                continue
            for name in sorted(os.listdir(scratch)):
                if not name.endswith(".md"):
                    continue
                checked += 1
                committed = os.path.join(out, name)
                new = open(os.path.join(scratch, name), "rb").read()
                if not os.path.exists(committed):
                    failures.append(f"{committed}: not committed")
                elif open(committed, "rb").read() != new:
                    failures.append(f"{committed}: differs from its regeneration")
    index = subprocess.run([sys.executable, os.path.join(HERE, "results_index.py")], capture_output=True)
    checked += 1
    if index.returncode != 0 or not os.path.exists("results/README.md") or \
            open("results/README.md", "rb").read() != index.stdout:
        failures.append("results/README.md: differs from results_index.py's output")
    for msg in failures:
        print("check_summaries: " + msg, file=sys.stderr)
    print(f"check_summaries: {checked} summaries compared, {len(failures)} problem(s)")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
