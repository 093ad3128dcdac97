#!/usr/bin/env python3
"""Speed-vs-error table and figure for a reduced_model table whose cells are closure strategies on one scene.

Usage: python3 experiments/summaries/summarize_pareto.py TABLE.json OUT_PREFIX [ERROR_KEY]
writes OUT_PREFIX.md and (where matplotlib is available) OUT_PREFIX.png. ERROR_KEY picks the error measure,
"reference/subset" with reference in vs_averaged_direct_sph, vs_averaged_analytic, vs_analytic and subset in
all_nodes, fluid_nodes, interior, wall_band (default: vs_averaged_direct_sph/all_nodes when present, else
vs_averaged_analytic/all_nodes: the headline metric, every coarse node the model reports, wall-surface nodes
included); the measure is the max-norm error relative to the analytic peak. A cell is on the Pareto front unless
another cell is no slower (reduced-model setup + run wall time; the minimum over the repeated runs where the row
records them) and no less accurate, and strictly better in one of the two. Where rows record the timing spread
(median over minimum), front points whose times lie within each other's spread are named: their order in time is
not resolved. Every number is read from the table; ratios are meaningful within one table only.
"""
import json
import math
import sys

from summary_util import figure_label, fmt, load_table, log_ticks, noisy_note, pct, pyplot_or_none, speed_up_cell, spct


def error_of(row, ref, subset):
    try:
        return row["errors"][ref][subset]["max_rel"]
    except (KeyError, TypeError):
        return None


def total_seconds(row):
    """The reduced run's setup + loop: the fastest of the repeated runs where the row records them."""
    c = row.get("cost", {})
    if isinstance(c.get("reduced_timing"), dict):
        return c["reduced_timing"].get("min_seconds")
    return None if "wall_seconds" not in c else c["wall_seconds"] + c.get("setup_seconds", 0.0)


def timing_spread(row):
    """(median - min) / min of the repeated runs, or None for a row timed once."""
    t = row.get("cost", {}).get("reduced_timing")
    return t.get("spread") if isinstance(t, dict) and t.get("repeats", 1) > 1 else None


def unresolved_pairs(points):
    """Adjacent (in time) front points whose times differ by less than the larger of their spreads."""
    pairs = []
    pts = sorted(points, key=lambda p: p[0])
    for (t1, _, r1), (t2, _, r2) in zip(pts, pts[1:]):
        s1, s2 = timing_spread(r1), timing_spread(r2)
        if s1 is None or s2 is None:
            continue
        if t2 <= t1 * (1.0 + max(s1, s2)):
            pairs.append((r1["label"], r2["label"]))
    return pairs


def main(path, prefix, key=None):
    table = load_table(path)
    prov = table["provenance"]
    rows = table["rows"]
    if key is None:
        key = "vs_averaged_direct_sph/all_nodes" if any("vs_averaged_direct_sph" in r.get("errors", {}) for r in rows) \
            else "vs_averaged_analytic/all_nodes"
    ref, subset = key.split("/")
    if subset == "all":
        sys.exit("summarize_pareto: the node set 'all' is now named 'fluid_nodes' (or use 'all_nodes')")
    pts = []
    for r in rows:
        e = error_of(r, ref, subset)
        t = total_seconds(r)
        if r.get("status") == "ok" and e is not None and t is not None:
            pts.append((t, e, r))
    front = set()
    for t, e, r in pts:
        if not any((t2 <= t and e2 <= e) and (t2 < t or e2 < e) for t2, e2, _ in pts):
            front.add(r["id"])
    subset_words = {"all_nodes": "all nodes, wall-surface nodes included", "fluid_nodes": "fluid nodes",
                    "interior": "interior nodes", "wall_band": "wall-band nodes"}.get(subset, subset)
    lines = [f"# {table['experiment']}: speed against error\n", f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: {table['complete']}.\n",
             f"Error: max over the coarse nodes ({subset_words}) of |v_reduced - v_ref| in % of the analytic peak, reference `{ref}`; "
             "*peak*: the paper's metric against the same reference. *total s*: the reduced model's setup plus its run to "
             "steady state (or the target time), the fastest of *runs* repeated runs, *spread* (median - min) / min, "
             "of which *deconv s* in the deconvolution. **Bold**: on the Pareto front.\n",
             "| strategy | status | error | peak | vs analytic | total s | runs | spread | deconv s | steps | speed-up vs direct SPH |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    order = sorted(rows, key=lambda r: (r.get("status") != "ok",
                                        1e300 if error_of(r, ref, subset) is None else error_of(r, ref, subset)))
    for r in order:
        e, c = (r.get("errors", {}) if r.get("status") == "ok" else {}), r.get("cost", {})
        label = f"**{r['label']}**" if r["id"] in front else r["label"]
        message = r.get("error") or r.get("reduced_model", {}).get("message") or ""
        status = r.get("status", "") if r.get("status") == "ok" else f"{r.get('status')}: {message[:80]}"
        lines.append(f"| {label} | {status} | {pct(error_of({'errors': e}, ref, subset))} | {spct(e.get(ref, {}).get('peak_relative_difference'))} | "
                     f"{pct(error_of({'errors': e}, 'vs_analytic', subset))} | {fmt(total_seconds(r))} | "
                     f"{fmt((c.get('reduced_timing') or {}).get('repeats', 1))} | {pct(timing_spread(r))} | "
                     f"{fmt(c.get('deconvolution_seconds'))} | {fmt(c.get('steps'))} | {speed_up_cell(c.get('speed_up'), timing_spread(r))} |")
    if pts:
        best = min(pts, key=lambda p: p[1])
        fastest = min(pts, key=lambda p: p[0])
        lines.append(f"\nMost accurate: {best[2]['label']} (error {pct(best[1])}, {fmt(best[0])} s). "
                     f"Fastest: {fastest[2]['label']} ({fmt(fastest[0])} s, error {pct(fastest[1])}).")
        on_front = [p for p in pts if p[2]["id"] in front]
        if any(timing_spread(p[2]) is None for p in on_front):
            lines.append("Some front points were timed once: their order in time is not established by this table.")
        for a, b in unresolved_pairs(on_front):
            lines.append(f"Within the timing spread of each other (order in time not resolved): {a}; {b}.")
    lines += noisy_note(lines)
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")
    plt = pyplot_or_none()
    if plt is None:
        return
    # Points numbered by error (most accurate first), the key beside the axes: labels never overlap.
    fig, (ax, key) = plt.subplots(1, 2, figsize=(10.0, 4.8), gridspec_kw={"width_ratios": [3, 2]})
    key.axis("off")
    numbered = sorted(pts, key=lambda p: p[1])
    # Points within 8 % of each other in time and error share one label ("4, 5, 14"): they are not resolved.
    clusters = []
    for k, (t, e, r) in enumerate(numbered, 1):
        on = r["id"] in front
        ax.plot(t, 100.0 * e, "o" if on else "x", color="C3" if on else "0.4")
        for c in clusters:
            if abs(math.log(t / c["t"])) < math.log(1.08) and abs(math.log(e / c["e"])) < math.log(1.08):
                c["k"].append(str(k))
                break
        else:
            clusters.append({"t": t, "e": e, "k": [str(k)]})
    # Neighbouring labels (within 30 % in time and error) alternate above and below their points.
    placed = []
    for c in sorted(clusters, key=lambda c: c["t"]):
        near = [p for p in placed if abs(math.log(c["t"] / p[0]["t"])) < math.log(1.3)
                and abs(math.log(c["e"] / p[0]["e"])) < math.log(1.3)]
        below = bool(near) and not near[-1][1]
        ax.annotate(", ".join(c["k"]), (c["t"], 100.0 * c["e"]), fontsize=7, xytext=(3, -9 if below else 2),
                    textcoords="offset points")
        placed.append((c, below))
    key.text(0.0, 1.0, "\n".join(f"{k}{'*' if r['id'] in front else ''}: {figure_label(r['label'], 60)}"
                                   for k, (_, _, r) in enumerate(numbered, 1)) + "\n(*: on the front)",
             va="top", ha="left", fontsize=6, family="monospace", transform=key.transAxes)
    fp = sorted((t, e) for t, e, r in pts if r["id"] in front)
    if fp:
        ax.step([p[0] for p in fp], [100.0 * p[1] for p in fp], where="post", color="C3", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    log_ticks(ax)
    ax.set_xlabel("reduced-model wall time, setup + run [s]")
    ref_words = {"vs_averaged_direct_sph": "vs averaged direct SPH", "vs_averaged_analytic": "vs averaged analytic",
                 "vs_analytic": "vs analytic"}.get(ref, ref)
    ax.set_ylabel(f"max error, % of the analytic peak\n({subset_words}, {ref_words})")
    title = table["experiment"].removeprefix("pareto_").replace("_", " ").replace("-", " ")
    ax.set_title(f"{title}: speed against error", fontsize=9)
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=110)


if __name__ == "__main__":
    main(*sys.argv[1:4])
