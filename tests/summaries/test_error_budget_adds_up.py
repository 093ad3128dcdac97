#!/usr/bin/env python3
"""The error budget adds up: on the committed uniform-channel budget table, the per-node terms that
experiments/summaries/error_budget_terms.py computes along the oracle chain sum to the paper's formulation's
error at every node, and their shifts to its shift, to round-off; independently of that code, the total is the
engine's recorded error (its max over nodes over the analytic peak read from the profile, and its l2 norm
relative to the direct SPH's), so the decomposition's normalisation is the engine's.

Usage: python3 tests/summaries/test_error_budget_adds_up.py   (from the repository root; exit 1 on a failure)
"""
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "experiments", "summaries"))
import error_budget_terms as budget  # noqa: E402
from summary_util import load_table  # noqa: E402

TABLE = os.path.join(ROOT, "results", "error_budget", "poiseuille_uniform", "error_budget_poiseuille_uniform.json")
TOL = 1e-12  # of the analytic peak


def main():
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    rows = load_table(TABLE)["rows"]  # as the summary reads it (older rows' fluid set renamed fluid_nodes)
    d = budget.decompose(rows)
    check(d is not None, "no decomposition: a chain row is missing")
    if d is None:
        return report(failures)
    total, terms, n = d["total"], [t[2] for t in d["terms"]], len(d["total"])
    check(len(terms) == len(budget.CHAIN), f"{len(terms)} terms for a chain of {len(budget.CHAIN)} rows")
    # The parts sum to the total at every node, the shifts to the total's shift.
    for i in range(n):
        s = sum(t[i] for t in terms)
        check(abs(s - total[i]) <= TOL, f"node {i}: the terms sum to {s!r}, the total is {total[i]!r}")
    a = d["argmax"]
    check(abs(sum(t[a] for t in terms) - total[a]) <= TOL, "the terms at the node of the largest error")
    for nodes in ("all", "fluid"):
        s = sum(d["stats"][name][nodes]["shift"] for name, _, _ in d["terms"])
        check(abs(s - d["stats"]["total"][nodes]["shift"]) <= TOL, f"{nodes} nodes: the shifts sum to {s!r}")
    # Independent of the module: the chain's first row is the paper's formulation and the last step's row the
    # whole wall band held; the total is their stored profiles' difference over the analytic peak, which on this
    # scene is the analytic profile's centre-line node (the node set is symmetric about the centre line).
    paper = next(r for r in rows if r["label"] == "coarse quadrature, closure oracle off, boundary oracle none")
    band = next(r for r in rows if r["label"] == "exact quadrature, closure oracle on, boundary oracle wall_band")
    prof = paper["profile"]
    peak = max(prof["analytic"])
    check(abs(d["peak"] - peak) <= 1e-12 * peak, f"peak {d['peak']!r}, the analytic profile's {peak!r}")
    direct, reduced = prof["direct_average"], prof["reduced"]
    recorded = paper["errors"]["vs_averaged_direct_sph"]["all_nodes"]
    mine = max(abs(u - v) for u, v in zip(reduced, direct)) / peak
    check(abs(d["stats"]["total"]["all"]["max"] - recorded["max_rel"]) <= 1e-12,
          f"the total's max {d['stats']['total']['all']['max']!r}, recorded {recorded['max_rel']!r}")
    check(abs(mine - recorded["max_rel"]) <= 1e-12, f"max |v - v_direct| / analytic peak {mine!r}, recorded "
                                                    f"{recorded['max_rel']!r}")
    l2 = math.sqrt(sum((t * d["peak"]) ** 2 for t in total)) / math.sqrt(sum(v * v for v in direct))
    check(abs(l2 - recorded["l2_rel"]) <= 1e-12, f"l2 of the total {l2!r}, recorded {recorded['l2_rel']!r}")
    for i in range(n):
        check(abs(total[i] - (reduced[i] - direct[i]) / peak) <= TOL, f"node {i}: the total")
        remainder = (band["profile"]["reduced"][i] - direct[i]) / peak
        check(abs(terms[-1][i] - remainder) <= TOL, f"node {i}: the remainder")
    # The wall-surface nodes are the two end nodes, and the rows count the rest as fluid.
    check(d["wall_surface"] == [0, n - 1], f"wall-surface nodes {d['wall_surface']}")
    check(len(d["fluid"]) == paper["errors"]["vs_averaged_direct_sph"]["fluid_nodes"]["count"], "fluid count")
    return report(failures)


def report(failures):
    for msg in failures:
        print("test_error_budget_adds_up: " + msg, file=sys.stderr)
    print(f"test_error_budget_adds_up: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
