#!/usr/bin/env python3
"""The headline of a quick run: per reduced_model table (one scene each), the closures ranked by their error
against the averaged direct SPH, as the max over ALL coarse nodes the reduced model reports (the wall-surface
nodes included, DESIGN.md par. 6), with the paper's peak metric beside it, the speed-up over the direct SPH, and
the reference's own error (the averaged direct SPH against the averaged analytic solution, same nodes).

Usage: python3 experiments/summaries/summarize_headline.py OUT_DIR TABLE.json [TABLE.json ...]
writes OUT_DIR/summary.md and prints the headline (best closure, its speed-up, the reference's error) per scene.
Errors are relative to the analytic peak. Where a row has no "all_nodes" error set, the max over all nodes is
taken from its profile (the same nodes, the reduced and averaged direct velocities), with the analytic peak as
the analytic peak recovered from the row's fluid-node error (see scale_of).
"""
import os
import sys

from summary_util import NOISY_NOTE, NOISY_SPREAD, fmt, get, load_table, speed_up_cell


def pct(x):
    return "-" if x is None else f"{100 * x:.2f} %"


def scale_of(row):
    """The analytic peak the row's errors are relative to, recovered from the row: its "fluid_nodes" max
    error against the averaged direct SPH and the same nodes of its profile (every node, or every node but the
    two wall-surface nodes); else the largest analytic value at the nodes."""
    p = row.get("profile", {})
    e = get(row, "errors", "vs_averaged_direct_sph", "fluid_nodes")
    if e and e.get("max_rel") and "direct_average" in p:
        d = [abs(a - b) for a, b in zip(p["reduced"], p["direct_average"])]
        if e.get("count") == len(d) - 2:
            d = d[1:-1]
        if e.get("count") == len(d):
            return max(d) / e["max_rel"]
    a = p.get("analytic")
    return max(abs(v) for v in a) if a else None


def max_all_nodes(row, ref_key="direct_average"):
    """max over every coarse node of |v_reduced - v_ref| / analytic peak."""
    e = get(row, "errors", "vs_averaged_direct_sph", "all_nodes", "max_rel")
    if e is not None and ref_key == "direct_average":
        return e
    p, s = row.get("profile", {}), scale_of(row)
    if ref_key not in p or not s:
        return None
    return max(abs(a - b) for a, b in zip(p["reduced"], p[ref_key])) / s


def fluid_error(row):
    return get(row, "errors", "vs_averaged_direct_sph", "fluid_nodes", "max_rel")


def rank(row):
    """Max over all nodes first; ties (the wall-surface nodes often set it for every closure) by the fluid nodes."""
    a, f = max_all_nodes(row), fluid_error(row)
    return (1e300 if a is None else round(a, 12), 1e300 if f is None else f)


def total_seconds(row):
    """The reduced run's setup + loop: the fastest of its repeated runs where the row records them."""
    c = row.get("cost", {})
    if isinstance(c.get("reduced_timing"), dict):
        return c["reduced_timing"].get("min_seconds")
    return c.get("wall_seconds", 0.0) + c.get("setup_seconds", 0.0) if "wall_seconds" in c else None


def speed_up_text(row):
    """The speed-up over the direct SPH from the fastest reduced run, with the one at the median run and the count
    of runs where the row records them ("timed once" otherwise)."""
    c = row.get("cost", {})
    t = c.get("reduced_timing")
    if not isinstance(t, dict) or t.get("repeats", 1) < 2:
        return f"{fmt(c.get('speed_up'))} (reduced run timed once)"
    noisy = t.get("spread") is not None and t["spread"] > NOISY_SPREAD
    return (f"{fmt(c.get('speed_up'))} ({fmt(c.get('speed_up_at_median'))} at the median of {t['repeats']} runs"
            + (f"; noisy: the runs spread by {pct(t['spread'])})" if noisy else ")"))


def is_paper_formulation(row):
    """The paper's balance (5.8): the stress divergence, wall-surface nodes imposed by (5.6)."""
    return get(row, "params", "solver", "balance") in (None, "stress_divergence")


def reference_error(row):
    """The averaged direct SPH against the averaged analytic solution, max over every coarse node / peak."""
    p, s = row.get("profile", {}), scale_of(row)
    if "direct_average" not in p or not s:
        return None
    return max(abs(a - b) for a, b in zip(p["direct_average"], p["analytic_average"])) / s


def main(out_dir, paths):
    lines = ["# Quick run: headline\n",
             "Each scene: the reduced model with several closures and formulations against the averaged direct SPH "
             "of the same scene, "
             "computed from scratch by `scripts/reproduce.sh`. *max all nodes*: max over every coarse node the "
             "reduced model reports, the wall-surface nodes included, of |v_reduced - v_direct| / analytic peak; "
             "*fluid nodes*: the same without the wall-surface nodes; *peak*: the paper's metric (relative difference "
             "of the peak velocities), never alone. *total s*: the reduced model's setup + run, the fastest of its "
             "repeated runs (*runs*, *spread* = (median - min) / min). *speed-up*: direct SPH wall time / that "
             "fastest reduced run, same machine. *reference's own error*: the averaged direct SPH against the averaged analytic "
             "solution at the same nodes. " + NOISY_NOTE + "\n"]
    headline = []
    for path in paths:
        t = load_table(path)
        rows = [r for r in t["rows"] if r.get("status") == "ok" and max_all_nodes(r) is not None]
        prov = t["provenance"]
        name = t["experiment"]
        lines += [f"## {name}\n", f"{t['description']}\n",
                  f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
                  f"{prov['threads']} thread(s), {prov['date_utc']}. Figures: `{name}/front.png` (speed against "
                  f"error), `{name}/profiles.png` (profiles).\n",
                  "| closure | status | max all nodes | fluid nodes | interior | peak | total s | runs | spread | speed-up |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for r in sorted(t["rows"], key=lambda r: (r.get("status") != "ok", rank(r))):
            timing = r.get("cost", {}).get("reduced_timing") or {}
            lines.append(f"| {r['label']} | {r.get('status')} | {pct(max_all_nodes(r))} | "
                         f"{pct(get(r, 'errors', 'vs_averaged_direct_sph', 'fluid_nodes', 'max_rel'))} | "
                         f"{pct(get(r, 'errors', 'vs_averaged_direct_sph', 'interior', 'max_rel'))} | "
                         f"{pct(get(r, 'errors', 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
                         f"{fmt(total_seconds(r))} | {fmt(timing.get('repeats', 1))} | {pct(timing.get('spread'))} | "
                         f"{speed_up_cell(get(r, 'cost', 'speed_up'), timing.get('spread'))} |")
        if rows:
            best = min(rows, key=rank)
            ref = reference_error(best)
            direct_s = get(best, "cost", "direct_sph_wall_seconds")
            paper = [r for r in rows if is_paper_formulation(r)]
            best_paper = min(paper, key=rank) if paper and not is_paper_formulation(best) else None
            beside = (f" The paper's formulation at its best: {best_paper['label']}, {pct(max_all_nodes(best_paper))} "
                      f"(max over all nodes; {pct(fluid_error(best_paper))} without the wall-surface nodes), speed-up "
                      f"{speed_up_text(best_paper)}." if best_paper else "")
            lines.append(f"\nBest closure: **{best['label']}**, {pct(max_all_nodes(best))} (max over all nodes; "
                         f"{pct(fluid_error(best))} without the wall-surface nodes), "
                         f"speed-up {speed_up_text(best)} over the direct SPH ({fmt(direct_s)} s); the "
                         f"reference's own error {pct(ref)}.{beside}\n")
            headline.append(f"  {name}: best closure {best['label']}: error {pct(max_all_nodes(best))} of the peak "
                            f"(max over all coarse nodes, wall-surface nodes included, vs the averaged direct SPH; "
                            f"{pct(fluid_error(best))} without them); "
                            f"speed-up {speed_up_text(best)}; the reference's own error {pct(ref)}")
            if best_paper:
                headline.append(f"    the paper's formulation at its best, {best_paper['label']}: "
                                f"{pct(max_all_nodes(best_paper))} ({pct(fluid_error(best_paper))} without the "
                                f"wall-surface nodes); speed-up {speed_up_text(best_paper)}")
        else:
            lines.append("\nNo closure ended ok.\n")
            headline.append(f"  {name}: no closure ended ok")
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(headline))


if __name__ == "__main__":
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    main(sys.argv[1], sys.argv[2:])
