#!/usr/bin/env python3
"""Error budget by oracle substitution (a reduced_model table named error_budget_*): per cell, the max-norm
error against the averaged direct SPH, relative to the analytic peak, over every coarse node (wall-surface
nodes included), the interior, the wall band and the two wall-surface nodes; the paper's peak metric beside
it; the reduced model's cost. Then the budget: how much of the total each oracle removes alone and together.

Usage: python3 experiments/summaries/summarize_error_budget.py TABLE.json OUT_PREFIX
writes OUT_PREFIX.md and (where matplotlib is available) OUT_PREFIX.png (bars of the all-node error).
Every number is read from the table.
"""
import sys

from summary_util import fmt, get, load_table, pyplot_or_none


def pct(x):
    return "-" if x is None else f"{100 * x:.3g} %"


def err(row, subset):
    return get(row, "errors", "vs_averaged_direct_sph", subset, "max_rel")


def wall_surface_error(row):
    """The larger error of the two wall-surface nodes, on the tables' scale (the analytic peak, recovered as the
    all-node maximum of |v_reduced - v_direct| over its relative value)."""
    p = row.get("profile", {})
    red, ref, e_all = p.get("reduced"), p.get("direct_average"), err(row, "all_nodes")
    if not (red and ref and e_all):
        return None
    peak = max(abs(u - v) for u, v in zip(red, ref)) / e_all
    return max(abs(red[0] - ref[0]), abs(red[-1] - ref[-1])) / peak


def find(rows, predicate):
    for r in rows:
        if predicate(r):
            return r
    return None


def key(r):
    p = r.get("params", {})
    return (get(p, "quadrature", "name"), bool(get(p, "oracle", "closure")), get(p, "oracle", "boundary"),
            get(p, "solver", "balance"), get(p, "solver", "time_integration"), get(p, "solver", "wall_node_value"))


def main(path, prefix):
    table = load_table(path)
    prov = table["provenance"]
    rows = table["rows"]
    out = [f"# {table.get('experiment', '')}: error budget by oracle substitution", "",
           table.get("description", ""), "",
           f"Generated from `{path}` by `python3 experiments/summaries/summarize.py {path}`; commit "
           f"`{prov.get('git_commit', '?')}`, {prov.get('compiler', '?')}, {prov.get('build_type', '?')}, "
           f"{prov.get('threads', '?')} thread(s), {prov.get('date_utc', '?')}. Table complete: {table.get('complete')}.",
           "",
           "Errors: max over the subset's coarse nodes of |v_reduced - v_direct| / analytic peak, against the averaged "
           "direct SPH of the same strip at steady state; *all nodes* includes the two wall-surface nodes. Peak: the "
           "paper's metric (relative difference of the peak velocities). Cost: reduced-model setup + run wall time; "
           "speed-up against the direct SPH of the same strip (not the full domain).", "",
           "| cell | all nodes | interior | wall band | wall-surface nodes | peak metric | status | reduced s | speed-up |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        c = r.get("cost", {})
        secs = None if "wall_seconds" not in c else c["wall_seconds"] + c.get("setup_seconds", 0.0)
        out.append(f"| {r.get('label', '')} | {pct(err(r, 'all_nodes'))} | {pct(err(r, 'interior'))} | "
                   f"{pct(err(r, 'wall_band'))} | {pct(wall_surface_error(r))} | "
                   f"{pct(get(r, 'errors', 'vs_averaged_direct_sph', 'peak_relative_difference'))} | {r.get('status')} | "
                   f"{fmt(secs)} | {fmt(c.get('speed_up'))} |")
    # The budget: the paper's formulation and each oracle alone / together (coarse quadrature unless named).
    base = find(rows, lambda r: key(r)[:4] == ("coarse", False, "none", "stress_divergence") and key(r)[5] == "imposed")
    entries = [
        ("paper's formulation (closure, coarse quadrature (5.27), finite-difference divergence, (5.6) walls)", base),
        ("boundary oracle: wall-surface nodes at the averaged direct SPH",
         find(rows, lambda r: key(r)[:4] == ("coarse", False, "wall_nodes", "stress_divergence"))),
        ("closure oracle: reconstruction exact at the direct solution",
         find(rows, lambda r: key(r)[:4] == ("coarse", True, "none", "stress_divergence") and key(r)[5] == "imposed")),
        ("quadrature oracle: exact pair sum (2.13)",
         find(rows, lambda r: key(r)[:4] == ("exact", False, "none", "stress_divergence"))),
        ("closure oracle + boundary oracle (wall-surface nodes)",
         find(rows, lambda r: key(r)[:4] == ("coarse", True, "wall_nodes", "stress_divergence"))),
        ("closure + quadrature + boundary oracles (what remains: the finite-difference divergence)",
         find(rows, lambda r: key(r)[:4] == ("exact", True, "wall_nodes", "stress_divergence"))),
        ("closure + quadrature + boundary oracles, whole wall band held",
         find(rows, lambda r: key(r)[:4] == ("exact", True, "wall_band", "stress_divergence"))),
        ("force-density balance (exact divergence) + closure oracle: every ingredient exact",
         find(rows, lambda r: key(r)[1:4] == (True, "none", "force_density") and key(r)[4] == "explicit")),
    ]
    out += ["", "## The budget", "",
            "| formulation | all nodes | removed from the paper's formulation |", "|---|---|---|"]
    b = err(base, "all_nodes") if base else None
    for name, r in entries:
        e = err(r, "all_nodes") if r else None
        removed = None if (b is None or e is None) else b - e
        out.append(f"| {name} | {pct(e)} | {pct(removed)} |")
    with open(prefix + ".md", "w") as f:
        f.write("\n".join(out) + "\n")
    plt = pyplot_or_none()
    if plt is None:
        return
    labels = [r.get("label", "") for r in rows]
    values = [max(err(r, "all_nodes") or 0, 1e-5) * 100 for r in rows]
    fig, ax = plt.subplots(figsize=(10, 0.32 * len(rows) + 1.2))
    ax.barh(range(len(rows)), values, color=["tab:blue" if "force-density" in l else "tab:gray" for l in labels])
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels(labels, fontsize=6)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlabel("max error over all coarse nodes vs averaged direct SPH, % of peak")
    ax.set_title(table.get("experiment", ""))
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    main(sys.argv[1], sys.argv[2])
