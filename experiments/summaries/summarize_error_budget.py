#!/usr/bin/env python3
"""Error budget by oracle substitution (a reduced_model table named error_budget_*): per cell, the max-norm
error against the averaged direct SPH, relative to the analytic peak, over every coarse node (wall-surface
nodes included), the interior, the wall band and the two wall-surface nodes; the paper's peak metric beside
it; the reduced model's cost. Then the budget that adds up: the paper's formulation's error split node by node
along the oracle chain (error_budget_terms.py), each term's shift and shape, the order's effect, and the
attribution in words, every figure computed from the table.

Usage: python3 experiments/summaries/summarize_error_budget.py TABLE.json OUT_PREFIX
writes OUT_PREFIX.md and (where matplotlib is available) OUT_PREFIX.png (bars of the all-node error; the budget's
terms node by node, stacked, beside the total).
Every number is read from the table.
"""
import sys

from error_budget_terms import CHAIN, decompose, find_row, order_effects, recorded_max
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


def spct(x):
    """A signed share of the peak."""
    if x is None:
        return "-"
    return "0 %" if x == 0 else f"{100 * x:+.3g} %"


def node_name(d, i):
    where = "a wall-surface node" if i in d["wall_surface"] else "a fluid node"
    return f"y = {d['y'][i]:.4g} ({where})"


def budget_section(rows):
    """The budget that adds up (Markdown lines): the per-node telescoping decomposition along the oracle chain,
    its check, the order's effect, the attribution in words, and the force-density row outside the chain."""
    d = decompose(rows)
    if d is None:
        return ["", "## The budget, node by node", "",
                "The table lacks a row or profile of the oracle chain: no decomposition."]
    st, total, nf, nw = d["stats"], d["total"], len(d["fluid"]), len(d["wall_surface"])
    # The node of the largest |error|, and the fluid node of the largest where that one is a wall-surface node.
    nodes = [(d["argmax"], "the largest error")]
    if d["argmax_fluid"] != d["argmax"]:
        nodes.append((d["argmax_fluid"], "the largest at a fluid node"))
    chain = " -> ".join(name for name, _ in CHAIN)
    out = ["", "## The budget, node by node (the parts add up)", "",
           f"The paper's formulation's error e(n) = (v_paper(n) - v_direct(n)) / analytic peak at each coarse node n, "
           f"split along the oracle chain {chain} (each step adds one oracle to the ones before; every other setting "
           "the paper's): term k = (v_k(n) - v_(k+1)(n)) / peak is what the k-th oracle removes given the ones "
           "before it, and the remainder (v_last(n) - v_direct(n)) / peak what is left with all of them. The terms "
           "sum to e(n) at every node, so their values at the node of the largest |e| sum to the all-node error; "
           "their means over a node set (the *shift*, signed) sum to the total's. The *shape* is the max over the "
           "set of |term - shift|, the RMS the root mean square over every node; neither adds up (norms). *All "
           f"nodes*: the {nf + nw} coarse nodes as in the tables' all-node column; *fluid nodes*: the {nf} without "
           f"the {nw} wall-surface nodes. Signed: positive where the reduced velocity exceeds the direct SPH's.", "",
           "| term | " + " | ".join(f"at {node_name(d, i)}, {what}" for i, what in nodes) +
           " | max over nodes | RMS over nodes | shift, all nodes | shape, all nodes | shift, fluid nodes | "
           "shape, fluid nodes |", "|---|" + "---|" * (len(nodes) + 6)]

    def line(name, values, s):
        return (f"| {name} | " + " | ".join(spct(values[i]) for i, _ in nodes) + f" | {pct(s['all']['max'])} | "
                f"{pct(s['all']['rms'])} | {spct(s['all']['shift'])} | {pct(s['all']['shape'])} | "
                f"{spct(s['fluid']['shift'])} | {pct(s['fluid']['shape'])} |")

    for name, text, values in d["terms"]:
        out.append(line(f"{name}: {text}", values, st[name]))
    shifts = {k: sum(st[name][k]["shift"] for name, _, _ in d["terms"]) for k in ("all", "fluid")}
    out.append("| sum of the terms | " + " | ".join(spct(sum(v[i] for _, _, v in d["terms"])) for i, _ in nodes) +
               f" | - | - | {spct(shifts['all'])} | - | {spct(shifts['fluid'])} | - |")
    out.append(line("**total: paper's formulation - averaged direct SPH**", total, st["total"]))
    paper = find_row(rows, CHAIN[0][1])
    shift_gap = max(abs(shifts[k] - st["total"][k]["shift"]) for k in ("all", "fluid"))
    out += ["", f"Check: over every node the terms' sum differs from the total by at most {d['sum_error']:.1e} of "
                f"the peak, the shifts' sums from the total's by {shift_gap:.1e}; the total's max over nodes, "
                f"{100 * st['total']['all']['max']:.6g} %, is the table's recorded all-node error of the paper's "
                f"formulation, {100 * recorded_max(paper):.6g} % (the peak, {d['peak']:.6g}, recovered from the rows' "
                "recorded errors; every row gives the same)."]
    order = order_effects(rows, d["peak"])
    return out + order_section(d, order) + words_section(rows, d, order)


def order_section(d, order):
    """The chain's order: each of three oracles' term added first and added last, at the fluid node of the
    largest error."""
    if order is None:
        return []
    a = d["argmax_fluid"]
    out = ["", "### The order of the chain", "",
           "The terms depend on the order the oracles are added in (their effects interact). Each oracle's term "
           "added first (to the paper's formulation) and added last (to the other two, the wall-surface-node oracle "
           "standing for the boundary oracle):", "",
           f"| oracle | first: at {node_name(d, a)} | first: shift, all nodes | last: at the same node | "
           "last: shift, all nodes |", "|---|---|---|---|---|"]
    for name, (first, last) in order.items():
        out.append(f"| {name} | {spct(first[a])} | {spct(sum(first) / len(first))} | {spct(last[a])} | "
                   f"{spct(sum(last) / len(last))} |")
    return out


def words_section(rows, d, order):
    """The attribution in words, every figure from the decomposition."""
    st, a, af, total = d["stats"], d["argmax"], d["argmax_fluid"], d["total"]
    terms = {name: values for name, _, values in d["terms"]}
    fluid_shift, fluid_shape = st["total"]["fluid"]["shift"], st["total"]["fluid"]["shape"]
    wall = terms["wall-surface nodes"]
    wall_values = sorted({spct(wall[i]) for i in d["wall_surface"]})
    wall_values = f"{wall_values[0]} at both" if len(wall_values) == 1 else " and ".join(wall_values)
    wall_inside = max(abs(wall[i]) for i in d["fluid"])
    inside = "zero at every fluid node" if wall_inside == 0 else f"at most {pct(wall_inside)} at a fluid node"
    mostly = "mostly a shift" if abs(fluid_shift) > fluid_shape else "as much shape as shift"
    out = [f"The paper's formulation's all-node error, {pct(st['total']['all']['max'])}, is largest at "
           f"{node_name(d, a)}. Over the {len(d['fluid'])} fluid nodes it is a shift of {spct(fluid_shift)} with a "
           f"shape of {pct(fluid_shape)} ({mostly} across the channel); at the wall-surface nodes the imposed (5.6) "
           f"value stands {wall_values} off the averaged direct SPH, all of it the wall-surface term ({inside}), "
           f"which pulls the all-node shift to {spct(st['total']['all']['shift'])} and makes the all-node shape "
           f"{pct(st['total']['all']['shape'])}."]
    ranked = sorted([n for n in terms if n != "wall-surface nodes"], key=lambda n: -abs(st[n]["fluid"]["shift"]))
    out.append("Of the fluid shift, " + "; ".join(
        f"the {n}{'' if n == 'remainder' else ' term'} contributes {spct(st[n]['fluid']['shift'])} "
        f"(shape {pct(st[n]['fluid']['shape'])})" for n in ranked) +
        f", in that order of size; they add up to {spct(fluid_shift)}.")
    at = "; ".join(f"{n} {spct(v[af])}" for n, v in terms.items())
    largest = max(terms, key=lambda n: abs(terms[n][af]))
    if af == a:
        out.append(f"At the node of the largest error the terms are {at}: the wall-surface-node oracle alone "
                   f"changes nothing there, and the largest term is the {largest}.")
    else:
        out.append(f"The largest error is at a wall-surface node, all of it the wall-surface term; at the fluid node "
                   f"of the largest error, {node_name(d, af)} with {spct(total[af])}, the terms are {at}: the "
                   f"largest is the {largest}.")
    if order:
        out.append("The order matters: at that node the closure term is "
                   f"{spct(order['closure'][0][af])} added first and {spct(order['closure'][1][af])} added last, the "
                   f"quadrature term {spct(order['quadrature'][0][af])} and {spct(order['quadrature'][1][af])}.")
    fd = next((r for r in rows if get(r, "params", "solver", "balance") == "force_density" and
               get(r, "params", "oracle", "closure") and get(r, "params", "oracle", "boundary") == "none" and
               get(r, "params", "solver", "time_integration") == "explicit"), None)
    if fd is not None:
        out.append("Outside the chain, the force-density balance (exact divergence of (2.13)) with the closure oracle "
                   f"reads {pct(recorded_max(fd))} over all nodes: every ingredient exact (the all-oracle floor).")
    return ["", "### The attribution", "", " ".join(out)]


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
    out += budget_section(rows)
    with open(prefix + ".md", "w") as f:
        f.write("\n".join(out) + "\n")
    plt = pyplot_or_none()
    if plt is None:
        return
    labels = [r.get("label", "") for r in rows]
    values = [max(err(r, "all_nodes") or 0, 1e-5) * 100 for r in rows]
    d = decompose(rows)
    fig, axes = plt.subplots(1, 2 if d else 1, figsize=(16 if d else 10, 0.32 * len(rows) + 1.2),
                             gridspec_kw={"width_ratios": [3, 2]} if d else None, squeeze=False)
    ax = axes[0][0]
    ax.barh(range(len(rows)), values, color=["tab:blue" if "force-density" in l else "tab:gray" for l in labels])
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels(labels, fontsize=6)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlabel("max error over all coarse nodes vs averaged direct SPH, % of peak")
    ax.set_title(table.get("experiment", ""))
    if d:  # the budget node by node: the terms stacked (signed) and their sum, the total
        ax = axes[0][1]
        y = d["y"]
        width = 0.8 * min(b - a for a, b in zip(y, y[1:]))
        pos, neg = [0.0] * len(y), [0.0] * len(y)
        for name, _, values in d["terms"]:
            v = [100 * x for x in values]
            base = [p if x >= 0 else q for x, p, q in zip(v, pos, neg)]
            ax.bar(y, v, width, bottom=base, label=name)
            pos = [p + max(x, 0) for x, p in zip(v, pos)]
            neg = [q + min(x, 0) for x, q in zip(v, neg)]
        ax.plot(y, [100 * x for x in d["total"]], "k.-", label="total (paper's formulation)")
        ax.axhline(100 * d["stats"]["total"]["fluid"]["shift"], color="k", ls=":", lw=1, label="total's fluid shift")
        ax.axhline(0, color="gray", lw=0.5)
        ax.set_xlabel("y (coarse node)")
        ax.set_ylabel("(v_k - v_(k+1)) / analytic peak, %")
        ax.set_title("the budget node by node: the terms add up to the total", fontsize=9)
        ax.legend(fontsize=6, loc="lower center")
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=110)

if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    main(sys.argv[1], sys.argv[2])
