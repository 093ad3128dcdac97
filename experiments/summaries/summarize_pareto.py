#!/usr/bin/env python3
"""Speed-vs-error table and figure for a reduced_model table whose cells are closure strategies on one scene.

Usage: python3 experiments/summaries/summarize_pareto.py TABLE.json OUT_PREFIX [ERROR_KEY]
writes OUT_PREFIX.md and (where matplotlib is available) OUT_PREFIX.png. ERROR_KEY picks the error measure,
"reference/subset" with reference in vs_averaged_direct_sph, vs_averaged_analytic, vs_analytic and subset in
all, interior (default: vs_averaged_direct_sph/all when present, else vs_averaged_analytic/all); the measure is
the max-norm error relative to the analytic peak. A cell is on the Pareto front unless another cell is no slower
(reduced-model setup + run wall time) and no less accurate, and strictly better in one of the two. Every number is read from the table; wall times are on
one shared core, so ratios are meaningful within one table only.
"""
import json
import sys

from summary_util import fmt, load_table, pyplot_or_none


def error_of(row, ref, subset):
    try:
        return row["errors"][ref][subset]["max_rel"]
    except (KeyError, TypeError):
        return None


def total_seconds(row):
    c = row.get("cost", {})
    return None if "wall_seconds" not in c else c["wall_seconds"] + c.get("setup_seconds", 0.0)


def main(path, prefix, key=None):
    table = load_table(path)
    prov = table["provenance"]
    rows = table["rows"]
    if key is None:
        key = "vs_averaged_direct_sph/all" if any("vs_averaged_direct_sph" in r.get("errors", {}) for r in rows) \
            else "vs_averaged_analytic/all"
    ref, subset = key.split("/")
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
    lines = [f"# {table['experiment']}: speed against error\n", f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: {table['complete']}.\n",
             f"Error: max over the coarse nodes ({subset}) of |v_reduced - v_ref| / analytic peak, reference `{ref}`; "
             "*peak*: the paper's metric against the same reference. *total s*: the reduced model's setup plus its run to "
             "steady state (or the target time), of which *deconv s* in the deconvolution. **Bold**: on the Pareto front.\n",
             "| strategy | status | error | peak | vs analytic | total s | deconv s | steps | speed-up vs direct SPH |",
             "|---|---|---|---|---|---|---|---|---|"]
    order = sorted(rows, key=lambda r: (r.get("status") != "ok",
                                        1e300 if error_of(r, ref, subset) is None else error_of(r, ref, subset)))
    for r in order:
        e, c = (r.get("errors", {}) if r.get("status") == "ok" else {}), r.get("cost", {})
        label = f"**{r['label']}**" if r["id"] in front else r["label"]
        message = r.get("error") or r.get("reduced_model", {}).get("message") or ""
        status = r.get("status", "") if r.get("status") == "ok" else f"{r.get('status')}: {message[:80]}"
        lines.append(f"| {label} | {status} | {fmt(error_of({'errors': e}, ref, subset))} | {fmt(e.get(ref, {}).get('peak_relative_difference'))} | "
                     f"{fmt(error_of({'errors': e}, 'vs_analytic', subset))} | {fmt(total_seconds(r))} | "
                     f"{fmt(c.get('deconvolution_seconds'))} | {fmt(c.get('steps'))} | {fmt(c.get('speed_up'))} |")
    if pts:
        best = min(pts, key=lambda p: p[1])
        fastest = min(pts, key=lambda p: p[0])
        lines.append(f"\nMost accurate: {best[2]['label']} (error {fmt(best[1])}, {fmt(best[0])} s). "
                     f"Fastest: {fastest[2]['label']} ({fmt(fastest[0])} s, error {fmt(fastest[1])}).")
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")
    plt = pyplot_or_none()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for t, e, r in pts:
        on = r["id"] in front
        ax.plot(t, e, "o" if on else "x", color="C3" if on else "0.4")
        ax.annotate(r["label"], (t, e), fontsize=6, xytext=(3, 2), textcoords="offset points")
    fp = sorted((t, e) for t, e, r in pts if r["id"] in front)
    if fp:
        ax.step([p[0] for p in fp], [p[1] for p in fp], where="post", color="C3", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("reduced-model wall time, setup + run [s]")
    ax.set_ylabel(f"max error / analytic peak ({ref}, {subset})")
    ax.set_title(table["experiment"], fontsize=9)
    fig.tight_layout()
    fig.savefig(prefix + ".png", dpi=110)


if __name__ == "__main__":
    main(*sys.argv[1:4])
