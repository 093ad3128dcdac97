#!/usr/bin/env python3
"""Markdown summary of a direct_sph_validation table of the lid-driven cavity (results/cavity/tvf_re100/).

Usage: python3 experiments/summaries/summarize_cavity.py TABLE.json > summary.md
Every number printed is read from the table: per row, the centre-line velocities against Ghia, Ghia & Shin (1982)
at their points inside the cavity (u on x = L/2, v on y = L/2; the mean over the last five saved times, and the end
alone), how far the profiles move between those saved times, the number density's spread, the cost and the
reference-store entry holding the particles at the saved times; then the profiles point by point.
"""
import sys

from summary_util import dirty_mark, fmt, get, load_table, pct


def main(path):
    table = load_table(path)
    prov = table["provenance"]
    rows = table["rows"]
    print(f"# {table['experiment']}: direct SPH of the lid-driven cavity\n")
    print(f"{table['description']}\n")
    print(f"Generated from `{path}` by `python3 experiments/summaries/summarize_cavity.py {path}`; commit "
          f"`{prov['git_commit']}`, {prov['compiler']}, {prov['build_type']}, {prov['threads']} thread(s), "
          f"{prov['date_utc']}, command `{prov['command']}`. Table complete: {table['complete']}.\n")
    print("*u*, *v*: the largest |difference| from Ghia's values over their points inside the cavity (15 on each "
          "centre line; the points on the walls are the boundary conditions), in % of the lid speed, of the profiles "
          "averaged over the last five saved times (*mean over t*); *worst*: the larger; *at the end*: the same for the "
          "final state alone; *change*: the largest change of the profiles between successive saved times of that "
          "window, in % of the lid speed; *n spread*: (max - min) / mean of the fluid's summation number density at "
          "the end; *store entry*: the reference-store entry that holds the particles at the saved times.\n")
    print("| n | status | mean over t | u | v | worst | at the end | change | n spread | steps | SPH wall s | "
          "store entry |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        p = r["params"]["scene"]
        c = get(r, "errors", "centrelines") or {}
        window = c.get("mean_over_times") or []
        cost = r.get("cost", {})
        print(f"| {p.get('n')}{dirty_mark(r)} | {r['status']} | "
              f"{'-'.join(fmt(t) for t in window) if window else '-'} | {pct(c.get('max_abs_u'))} | "
              f"{pct(c.get('max_abs_v'))} | {pct(c.get('worst'))} | {pct(c.get('worst_end'))} | "
              f"{pct(c.get('largest_change_between_saved_times'))} | "
              f"{fmt(get(r, 'errors', 'number_density', 'spread_over_mean'))} | {fmt(cost.get('steps'))} | "
              f"{fmt(cost.get('wall_seconds'))} | `{get(r, 'direct_sph', 'reference_store', 'entry') or '-'}` |")
    with_lines = [r for r in rows if get(r, "errors", "centrelines", "u")]
    if not with_lines:
        return
    c0 = with_lines[0]["errors"]["centrelines"]
    for axis, coord, ref, name in (("u", "y", "u_ghia", "u(x = L/2, y)"), ("v", "x", "v_ghia", "v(x, y = L/2)")):
        print(f"\n{name} against Ghia's, in units of the lid speed (mean over the window):\n")
        print(f"| {coord} | Ghia | " + " | ".join(f"n = {r['params']['scene'].get('n')}" for r in with_lines) + " |")
        print("|---|---|" + "---|" * len(with_lines))
        for k, x in enumerate(c0[coord]):
            print(f"| {fmt(x)} | {fmt(c0[ref][k], 5)} | " +
                  " | ".join(fmt(r["errors"]["centrelines"][axis][k], 4) for r in with_lines) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
