"""The error budget that adds up: a per-node telescoping decomposition of the paper's formulation's error along
the oracle chain of an error_budget_* table (imported by summarize_error_budget.py and by
tests/summaries/test_error_budget_adds_up.py).

The chain holds the staggered scheme with the finite-difference divergence of the stress quadrature and the
imposed (5.6) wall value fixed, and adds one oracle at a time:
    v_0 paper's formulation -> v_1 + closure oracle -> v_2 + quadrature oracle -> v_3 + wall-surface nodes held
    -> v_4 + whole wall band held,
so that at every node n, relative to the analytic peak P,
    e(n) = (v_0(n) - v_direct(n)) / P = sum_k (v_k(n) - v_{k+1}(n)) / P + (v_4(n) - v_direct(n)) / P
exactly (up to round-off). Each term is the part of the error its oracle removes, given the oracles before it.
Shift of a term: its signed mean over a node set; shape: the max over that set of |term - shift|. The shifts add
up exactly as the terms do; the shapes (max norms) do not. Pure Python, no numpy.
"""
import math

from summary_util import get

# (name, (quadrature, closure oracle, boundary oracle)) along the chain; every other setting is the paper's.
CHAIN = [
    ("paper's formulation", ("coarse", False, "none")),
    ("closure oracle", ("coarse", True, "none")),
    ("quadrature oracle", ("exact", True, "none")),
    ("wall-surface nodes held", ("exact", True, "wall_nodes")),
    ("whole wall band held", ("exact", True, "wall_band")),
]
# The term each step removes (v_k - v_{k+1}), and what is left after the last step (v_last - v_direct).
TERMS = [
    ("closure", "the paper's closure ({closure}) against the reconstruction exact at the direct solution"),
    ("quadrature", "the coarse quadrature (5.27) against the exact pair sum (2.13)"),
    ("wall-surface nodes", "the imposed (5.6) wall-surface value against the averaged direct SPH there"),
    ("rest of the wall band", "the band's other nodes held: the error left there with the three oracles on (the "
                              "finite-difference divergence's), and its effect inside"),
    ("remainder", "what is left at the interior nodes (outside the wall band) with every oracle on: the "
                  "finite-difference divergence's error there"),
]
PAPER_SETTINGS = {"balance": "stress_divergence", "time_integration": "explicit", "wall_node_value": "imposed"}


def settings(row):
    """The row's (quadrature, closure oracle, boundary oracle) and whether its other settings are the paper's."""
    p = row.get("params", {})
    paper = all(get(p, "solver", k) == v for k, v in PAPER_SETTINGS.items())
    return (get(p, "quadrature", "name"), bool(get(p, "oracle", "closure")), get(p, "oracle", "boundary")), paper


def find_row(rows, combination):
    """The one row with the paper's settings and this (quadrature, closure oracle, boundary oracle); None if absent."""
    found = [r for r in rows if settings(r) == (combination, True)]
    if len(found) > 1:
        raise ValueError(f"error budget: {len(found)} rows match {combination}")
    return found[0] if found else None


def recorded_max(row, nodes="all_nodes"):
    return get(row, "errors", "vs_averaged_direct_sph", nodes, "max_rel")


def analytic_peak(rows):
    """The tables' scale (the scene's analytic peak; not stored in the rows): recovered from each row with a
    nonzero all-node error as max_n |v_reduced - v_direct| / max_rel; the rows must agree to 1e-12."""
    peaks = []
    for r in rows:
        p, e = r.get("profile", {}), recorded_max(r)
        if p.get("reduced") and p.get("direct_average") and e:
            peaks.append(max(abs(u - v) for u, v in zip(p["reduced"], p["direct_average"])) / e)
    if not peaks:
        return None
    if max(peaks) - min(peaks) > 1e-12 * max(peaks):
        raise ValueError(f"error budget: the rows' scales disagree ({min(peaks)!r} to {max(peaks)!r})")
    return peaks[0]


def stats(values, nodes):
    """Shift (signed mean), shape (max |value - shift|), max |value| and RMS over the node indices `nodes`."""
    sub = [values[n] for n in nodes]
    shift = sum(sub) / len(sub)
    return {"shift": shift, "shape": max(abs(v - shift) for v in sub), "max": max(abs(v) for v in sub),
            "rms": math.sqrt(sum(v * v for v in sub) / len(sub))}


def decompose(rows):
    """The decomposition of the paper's formulation's error, or None where a chain row or profile is missing.
    Returns {"peak", "y", "total", "terms": [(name, description, values)], "argmax" (the node of the largest
    |total|, the first of equals), "argmax_fluid" (the same over the fluid nodes), "fluid", "wall_surface",
    "sum_error" (max over nodes of |sum of the terms - total|), "stats": {name: {"all": ..., "fluid": ...}}};
    every value relative to the analytic peak."""
    chain = [find_row(rows, combination) for _, combination in CHAIN]
    if any(r is None or not r.get("profile", {}).get("reduced") for r in chain):
        return None
    peak = analytic_peak(rows)
    direct = chain[0]["profile"].get("direct_average")
    y = chain[0]["profile"].get("y")
    if not peak or not direct or any(r["profile"].get("direct_average") != direct for r in chain):
        return None
    v = [r["profile"]["reduced"] for r in chain] + [direct]
    n = len(direct)
    total = [(v[0][i] - direct[i]) / peak for i in range(n)]
    deconvolver = get(chain[0], "params", "closure", "deconvolver") or {}
    closure = " ".join(str(x) for x in (deconvolver.get("name"), deconvolver.get("order")) if x is not None)
    terms = [(name, text.format(closure=closure or "?"), [(v[k][i] - v[k + 1][i]) / peak for i in range(n)])
             for k, (name, text) in enumerate(TERMS)]
    summed = [sum(t[2][i] for t in terms) for i in range(n)]
    # The wall-surface nodes: where the wall-node oracle holds the averaged direct SPH (the two end nodes).
    wall_surface = [i for i in range(n) if chain[3]["profile"]["reduced"][i] == direct[i]]
    fluid = [i for i in range(n) if i not in wall_surface]
    counted = get(chain[0], "errors", "vs_averaged_direct_sph", "fluid_nodes", "count")
    if counted is not None and counted != len(fluid):
        raise ValueError(f"error budget: {len(fluid)} fluid nodes found, the rows count {counted}")
    every = list(range(n))
    argmax = max(every, key=lambda i: abs(total[i]))  # the first node of the largest |error|
    argmax_fluid = max(fluid, key=lambda i: abs(total[i]))
    out = {"peak": peak, "y": y, "total": total, "terms": terms, "argmax": argmax, "argmax_fluid": argmax_fluid,
           "fluid": fluid,
           "wall_surface": wall_surface, "sum_error": max(abs(summed[i] - total[i]) for i in every), "stats": {}}
    for name, values in [("total", total)] + [(t[0], t[2]) for t in terms]:
        out["stats"][name] = {"all": stats(values, every), "fluid": stats(values, fluid)}
    return out


def order_effects(rows, peak):
    """For the closure, quadrature and wall-surface-node oracles: the term each removes (relative to the peak) when
    added first, to the paper's formulation, and last, to the other two: {name: (first, last)}, per-node lists;
    None where a row is missing."""
    def combination(closure, quadrature, wall_nodes):
        return ("exact" if quadrature else "coarse", closure, "wall_nodes" if wall_nodes else "none")

    out = {}
    for which, name in enumerate(["closure", "quadrature", "wall-surface nodes"]):
        pair = []
        for others in (False, True):
            off, on = [others] * 3, [others] * 3
            off[which], on[which] = False, True
            r_off, r_on = find_row(rows, combination(*off)), find_row(rows, combination(*on))
            if r_off is None or r_on is None:
                return None
            pair.append([(a - b) / peak for a, b in zip(r_off["profile"]["reduced"], r_on["profile"]["reduced"])])
        out[name] = tuple(pair)
    return out
