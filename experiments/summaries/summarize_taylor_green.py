#!/usr/bin/env python3
"""Markdown summary of a direct_sph_validation table of the Taylor-Green scene
(results/taylor_green/tvf_re100_perturbed/tvf_re100_perturbed.json).

Usage: python3 experiments/summaries/summarize_taylor_green.py TABLE.json > summary.md
Every number printed is read from the table: per row, the largest particle speed against the exact decay
U exp(-8 pi^2 t / Re) at each saved time (|max|v| - U e^{bt}| / U e^{bt}), the particles against the exact field at the
end, the number density's spread, the cost and the reference-store entry holding the particles at the saved times.
"""
import sys

from summary_util import dirty_mark, fmt, get, load_table, pct


def main(path):
    table = load_table(path)
    prov = table["provenance"]
    rows = table["rows"]
    print(f"# {table['experiment']}: direct SPH of the Taylor-Green vortex\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}` by `python3 experiments/summaries/summarize_taylor_green.py {path}`; commit "
          f"`{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, {prov['threads']} thread(s), "
          f"{prov['date_utc']}, command `{prov['command']}`. Table complete: {table['complete']}.\n")
    print("*max|v|*: |max over particles of |v| - U exp(-8 pi^2 t / Re)| / (U exp(-8 pi^2 t / Re)), in %; *worst*: over "
          "the saved times; *from t = 0.5*: the worst at t >= 0.5; *particles max* / *L2*: the particles against the exact "
          "field at the end (max |v - v_exact| / max|v_exact|, and the relative L2 norm), in %; *n spread*: (max - min) / "
          "mean of the summation number density at the end; *store entry*: the reference-store entry that holds the "
          "particles at the saved times (particles.h5part: one Step#k per saved time, then the final state); *avg max* / "
          "*avg L2*: the particles averaged onto the averaging mesh against the exact field times the window's symbol "
          "(the reference a reduced model of the transient is scored against), max over nodes relative to the averaged "
          "field's largest speed, and the relative L2 norm, in %.\n")
    print("| n | h/dx | perturbation | status | max\\|v\\| worst | at t | from t = 0.5 | at the end | particles max | "
          "particles L2 | avg max worst | n spread | steps | SPH wall s | store entry |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        p = r["params"]["scene"]
        ms = get(r, "errors", "max_speed") or {}
        times, rel = ms.get("times", []), ms.get("relative_error", [])
        at = times[rel.index(max(rel))] if rel else None
        late = [e for t, e in zip(times, rel) if t >= 0.5 - 1e-12]
        pv = get(r, "errors", "particles_vs_exact") or {}
        c = r.get("cost", {})
        print(f"| {p.get('n')}{dirty_mark(r)} | {fmt(p.get('h_over_dx'))} | {fmt(p.get('perturbation'))} | {r['status']} | "
              f"{pct(ms.get('worst'))} | {fmt(at)} | {pct(max(late) if late else None)} | {pct(ms.get('final'))} | "
              f"{pct(pv.get('max_rel'))} | {pct(pv.get('l2_rel'))} | "
              f"{pct(get(r, 'errors', 'averaged_vs_averaged_exact', 'worst_max_rel'))} | "
              f"{fmt(get(r, 'errors', 'number_density', 'spread_over_mean'))} | {fmt(c.get('steps'))} | "
              f"{fmt(c.get('wall_seconds'))} | `{get(r, 'direct_sph', 'reference_store', 'entry') or '-'}` |")
    with_times = [r for r in rows if get(r, "errors", "max_speed", "times")]
    if not with_times:
        return
    print("\nAt each saved time: max|v| against the exact decay (relative difference, %), and the averaged particles "
          "against the averaged exact field (avg max / avg L2, %):\n")
    print("| t | exact | " + " | ".join(f"n = {r['params']['scene'].get('n')}: max\\|v\\| | avg max | avg L2"
                                        for r in with_times) + " |")
    print("|---|---|" + "---|---|---|" * len(with_times))
    ms0 = with_times[0]["errors"]["max_speed"]
    for k, t in enumerate(ms0["times"]):
        cells = []
        for r in with_times:
            rel = r["errors"]["max_speed"]["relative_error"]
            avg = r["errors"].get("averaged_vs_averaged_exact", {})
            am, al = avg.get("max_rel", []), avg.get("l2_rel", [])
            cells.append(" | ".join(pct(a[k]) if k < len(a) else "-" for a in (rel, am, al)))
        print(f"| {fmt(t)} | {fmt(ms0['exact'][k], 5)} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
