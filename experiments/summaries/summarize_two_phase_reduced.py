#!/usr/bin/env python3
"""Tables and figures of the two-phase reduced model (paper par. 7, Figs. 6-8) from
results/two_phase/two_phase/two_phase.json and (optionally) the eta' sweep two_phase_eta.json.

Usage: /usr/bin/python3 experiments/summaries/summarize_two_phase_reduced.py MAIN.json [ETA.json] OUT_DIR
writes OUT_DIR/summary.md and, where matplotlib is available, OUT_DIR/case{1,2,3}.png (profiles of the
reduced model against the averaged direct SPH at each t* and at steady state, like the paper's Figs. 6-8) and
OUT_DIR/pareto_case{1,2,3}.png (error against wall time per strategy). Every number is read from the tables.
"""
import json
import os
import sys

from summary_util import fmt, get, load_table, pyplot_or_none

PAPER = {"case1": 0.10, "case2": 0.06, "case3": 0.02}  # par. 7, second-order closure, peak-velocity metric
PAPER_CLOSURE = "landweber n=2 (paper)"



def snapshot_time(s):
    """A transient snapshot's t / tau (t* = t v_max / L for the channels): t_over_tau, or t_star in rows stored before
    the reduced models shared one transient vocabulary."""
    return s["t_over_tau"] if "t_over_tau" in s else s["t_star"]

def pct(x):
    return "-" if x is None else f"{100 * x:+.2f} %"


def peak_or(row, default):
    x = get(row, "errors", "vs_averaged_direct_sph", "peak_relative_difference")
    return default if x is None else x


def label_of(row):
    return row["label"].rsplit(", scene.case=", 1)[0]


def total_seconds(row):
    c = row.get("cost", {})
    return c.get("wall_seconds", 0.0) + c.get("setup_seconds", 0.0)


def provenance_line(path, table):
    p = table["provenance"]
    return (f"`{path}`: commit `{p['git_commit']}`, {p['compiler']}, {p['build_type']}, {p['threads']} thread(s), "
            f"{p['date_utc']}, command `{p['command']}`, complete: {table['complete']}.")


def main(args):
    out = args[-1]
    main_path = args[0]
    eta_path = args[1] if len(args) > 2 else None
    table = load_table(main_path)
    rows = [r for r in table["rows"]]
    cases = sorted({r["params"]["scene"]["case"] for r in rows})
    L = ["# Two-phase layered flow: the reduced model against direct SPH (paper par. 7)\n",
         f"{table['description']}\n", "From " + provenance_line(main_path, table) + "\n",
         "*peak*: the paper's metric, (max v_reduced - max v_ref) / max v_ref at steady state; *max*: max over the "
         "channel's coarse nodes of |v_reduced - v_ref| / analytic peak. *ref*: the averaged direct SPH of the same "
         "strip (direct) or the Gaussian average of the piecewise-parabolic solution (analytic). *cost ratio*: this "
         "strategy's reduced-model time (setup + run) over the second-order Landweber's, same case, same run. "
         "*speed-up*: direct SPH wall time / reduced-model time (setup + run), measured in this run. Snapshot times "
         "t = t* L / v_max use the analytic peak for v_max (known before the runs; the paper uses the direct "
         "solution's steady peak, a few % higher with zero-velocity walls).\n"]
    # Headline: the paper's closure beside the paper's numbers.
    L += ["## The paper's closure (second-order Landweber) beside the paper\n",
          "| case | paper (peak) | ours peak vs direct | ours peak vs analytic | max vs direct | max vs analytic | reduced s | direct s | speed-up |",
          "|---|---|---|---|---|---|---|---|---|"]
    by_case = {c: [r for r in rows if r["params"]["scene"]["case"] == c] for c in cases}
    for c in cases:
        ref = [r for r in by_case[c] if label_of(r) == PAPER_CLOSURE]
        if not ref:
            continue
        r = ref[0]
        e, cost = r.get("errors", {}), r.get("cost", {})
        L.append(f"| {c} | <= {100 * PAPER[c]:.0f} % | {pct(get(e, 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
                 f"{pct(get(e, 'vs_averaged_analytic', 'peak_relative_difference'))} | {fmt(get(e, 'vs_averaged_direct_sph', 'fluid_nodes', 'max_rel'))} | "
                 f"{fmt(get(e, 'vs_averaged_analytic', 'fluid_nodes', 'max_rel'))} | {fmt(total_seconds(r))} | "
                 f"{fmt(cost.get('direct_sph_wall_seconds'))} | {fmt(cost.get('speed_up'))} |")
    # Every strategy, per case.
    for c in cases:
        base = [r for r in by_case[c] if label_of(r) == PAPER_CLOSURE]
        t0 = total_seconds(base[0]) if base else None
        L += [f"\n## {c}: every strategy\n",
              "| strategy | status | peak vs direct | max vs direct | peak vs analytic | max vs analytic | reduced s | cost ratio | deconv s |",
              "|---|---|---|---|---|---|---|---|---|"]
        ok = sorted(by_case[c], key=lambda r: (r.get("status") != "ok", abs(peak_or(r, 1e9))))
        for r in ok:
            e = r.get("errors", {}) if r.get("status") == "ok" else {}  # a failed run's errors say nothing
            status = r.get("status") if r.get("status") == "ok" else \
                f"{r.get('status')}: {(r.get('error') or get(r, 'reduced_model', 'message') or '')[:70]}"
            L.append(f"| {label_of(r)} | {status} | {pct(get(e, 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
                     f"{fmt(get(e, 'vs_averaged_direct_sph', 'fluid_nodes', 'max_rel'))} | {pct(get(e, 'vs_averaged_analytic', 'peak_relative_difference'))} | "
                     f"{fmt(get(e, 'vs_averaged_analytic', 'fluid_nodes', 'max_rel'))} | {fmt(total_seconds(r))} | "
                     f"{fmt(total_seconds(r) / t0) if t0 else '-'} | {fmt(get(r, 'cost', 'deconvolution_seconds'))} |")
        # Transient of the paper's closure.
        if base and base[0].get("transient"):
            L += [f"\nTransient of the second-order closure ({c}): the reduced model against the averaged direct SPH at the same model time.\n",
                  "| t* | t | max vs direct | peak vs direct | direct peak |", "|---|---|---|---|---|"]
            for s in base[0]["transient"]:
                L.append(f"| {fmt(snapshot_time(s))} | {fmt(s['time'])} | {fmt(get(s, 'vs_averaged_direct_sph', 'fluid_nodes', 'max_rel'))} | "
                         f"{pct(get(s, 'vs_averaged_direct_sph', 'peak_relative_difference'))} | {fmt(max(s['direct_average'])) if 'direct_average' in s else '-'} |")
    if eta_path and os.path.exists(eta_path):
        eta_table = load_table(eta_path)
        L += ["\n## Does the error fall as eta' shrinks?\n", "From " + provenance_line(eta_path, eta_table) +
              " The eta'/L = 1/16 rows are from the main table above.\n",
              "| case | closure | eta'/L | peak vs direct | max vs direct | peak vs analytic | max vs analytic | reduced s | direct s |",
              "|---|---|---|---|---|---|---|---|---|"]
        pts = []
        for r in eta_table["rows"] + [r for r in rows if label_of(r) in ("landweber n=0", PAPER_CLOSURE)]:
            order = get(r, "params", "closure", "deconvolver", "order")
            if get(r, "params", "closure", "deconvolver", "name") != "landweber" or order not in (0, 2):
                continue
            if get(r, "params", "solver", "scheme") != "staggered" or get(r, "params", "closure", "discretization") != "coarse_coarse":
                continue
            pts.append((r["params"]["scene"]["case"], order, r["params"]["scene"]["eta_over_l"], r))
        for c, order, eta, r in sorted(pts, key=lambda p: (p[0], p[1], -p[2])):
            e = r.get("errors", {})
            L.append(f"| {c} | Landweber n={order} | 1/{round(1 / eta)} | {pct(get(e, 'vs_averaged_direct_sph', 'peak_relative_difference'))} | "
                     f"{fmt(get(e, 'vs_averaged_direct_sph', 'fluid_nodes', 'max_rel'))} | {pct(get(e, 'vs_averaged_analytic', 'peak_relative_difference'))} | "
                     f"{fmt(get(e, 'vs_averaged_analytic', 'fluid_nodes', 'max_rel'))} | {fmt(total_seconds(r))} | {fmt(get(r, 'cost', 'direct_sph_wall_seconds'))} |")
    os.makedirs(out, exist_ok=True)
    open(os.path.join(out, "summary.md"), "w").write("\n".join(L) + "\n")
    plt = pyplot_or_none()
    if plt is None:
        return
    for c in cases:
        base = [r for r in by_case[c] if label_of(r) == PAPER_CLOSURE]
        if not base or "profile" not in base[0]:
            continue
        r = base[0]
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        y = r["profile"]["y"]
        for k, s in enumerate(r.get("transient", [])):
            if "reduced" not in s:
                continue
            ax.plot(y, s["direct_average"], "-", color=f"C{k}", label=f"direct, t* = {snapshot_time(s):.3g}")
            ax.plot(y, s["reduced"], "d", color=f"C{k}", mfc="none")
        ax.plot(y, r["profile"]["direct_average"], "k-", label="direct, steady")
        ax.plot(y, r["profile"]["reduced"], "kd", mfc="none", label="reduced (diamonds), steady")
        ax.plot(y, r["profile"]["analytic_average"], "k:", label="averaged analytic, steady")
        ax.set_xlabel("y")
        ax.set_ylabel("averaged v_x")
        ax.set_title(f"{c}: second-order Landweber closure vs averaged direct SPH", fontsize=9)
        ax.legend(fontsize=6)
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"{c}.png"), dpi=110)
        plt.close(fig)
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        for r in by_case[c]:
            e = get(r, "errors", "vs_averaged_direct_sph", "peak_relative_difference")
            if r.get("status") != "ok" or e is None:
                continue
            ax.plot(total_seconds(r), max(abs(e), 1e-6), "o", color="C3" if label_of(r) == PAPER_CLOSURE else "0.3")
            ax.annotate(label_of(r), (total_seconds(r), max(abs(e), 1e-6)), fontsize=6, xytext=(3, 2), textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("reduced-model wall time, setup + run [s]")
        ax.set_ylabel("|peak error| vs averaged direct SPH")
        ax.set_title(f"{c}: speed against error", fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"pareto_{c}.png"), dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1:])
