#!/usr/bin/env python3
"""Summary of a coarse_continuum_2d table (the coarse continuum Navier-Stokes baseline on the 2D reduced model's
mesh, experiments/kinds/coarse_continuum.cpp).

Usage: python3 experiments/summaries/summarize_coarse_continuum.py TABLE.json OUT_PREFIX
Writes OUT_PREFIX.md: a row per cell with the baseline's errors against the averaged direct SPH, the averaged exact
field and the exact field, the reference's own error (floor), the baseline's amplitude on the mode, the transient,
the cost and the speed-up. Every number is read from the table.
"""
import sys

from summary_util import fmt, get, load_table, pct, spct


def error(row, ref="vs_averaged_direct_sph"):
    return get(row, "errors", ref, "all_nodes", "max_rel")


def main(path, prefix):
    table = load_table(path)
    prov = table["provenance"]
    lines = [f"# {table['experiment']}: the coarse continuum Navier-Stokes baseline\n",
             f"{table['description']}\n",
             f"From `{path}`; commit `{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, "
             f"{prov['threads']} thread(s), {prov['date_utc']}; command `{prov['command']}`; complete: "
             f"{table['complete']}.\n",
             "The baseline: incompressible Navier-Stokes on the reduced model's coarse mesh (collocated central "
             "differences, AB2, exact FFT projection; core/continuum/coarse_navier_stokes_2d.hpp), no closure. Errors: "
             "max over all coarse nodes of |v_baseline - v_ref| (vector norm) in % of the scene's velocity scale; "
             "*peak*: the relative difference of the largest |v| against the averaged direct SPH; *floor*: the "
             "averaged direct SPH against the averaged exact field (the reference's own error). *amplitude*: the "
             "baseline's amplitude on the mode over the averaged exact one (over the exact one where the start and "
             "the force are sampled). *transient*: the error against the averaged direct SPH at the transient's "
             "times. *total s*: the baseline's setup plus run; *speed-up*: the direct SPH's wall time over that.\n",
             "| cell | status | start | force | vs averaged direct SPH | peak | vs averaged exact | vs exact | floor | "
             "amplitude | transient | total s | steps | direct SPH s | speed-up |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in table["rows"]:
        c = r.get("cost", {})
        if r.get("status") != "ok":
            lines.append(f"| {r['label']} | {r.get('status')}: {(r.get('message') or r.get('error') or '')[:80]} |"
                         + " - |" * 13)
            continue
        solver = get(r, "params", "solver") or {}
        sampled = solver.get("initial") == "sampled" and solver.get("force") == "sampled"
        amplitude = get(r, "errors", "amplitude", "ratio" if sampled else "ratio_to_averaged_analytic")
        transient = ", ".join(pct(get(s, "baseline_vs_averaged_direct_sph", "all_nodes", "max_rel"))
                              for s in r.get("transient", []))
        total = c["wall_seconds"] + c["setup_seconds"]
        lines.append(
            f"| {r['label']} | ok | {solver.get('initial', '-')} | {solver.get('force', '-')} | {pct(error(r))} | "
            f"{spct(get(r, 'errors', 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
            f"{pct(error(r, 'vs_averaged_analytic'))} | {pct(error(r, 'vs_analytic'))} | "
            f"{pct(error(r, 'direct_sph_vs_averaged_analytic'))} | {fmt(amplitude, 5)} | {transient or '-'} | "
            f"{fmt(total)} | {fmt(c.get('steps'))} | {fmt(c.get('direct_sph_wall_seconds'))} | "
            f"{fmt(c.get('speed_up'))} |")
    open(prefix + ".md", "w").write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
