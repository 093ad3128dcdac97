#!/usr/bin/env python3
"""Generates results/README.md, the index of the committed results: per result folder its question, its
headline numbers (read from its table), the commits its rows came from, and links to its summary and figure.

Usage: python3 experiments/summaries/results_index.py > results/README.md
The questions are the one hand-written part (below, one per folder); every number is read from the tables.
"""
import glob
import os

from summary_util import fmt, get, load_table

ROOT = "results"
QUESTIONS = {
    "sph_validation": "Does the direct SPH reference converge to the analytic channel profiles (5.15)/(D.3)?",
    "stability": "Do the deconvolution strategies stay finite and choose good parameters on hard, ill-posed cases?",
    "paper/appendix_b": "Does the convective stress of the steady direct SPH match Appendix B and scale like eta'^2?",
    "paper/appendix_c": "How accurate and how fast is the coarse stress quadrature (5.27) against the exact pair sum?",
    "paper/fig2": "Fig. 2: how does the zero-order reduced model's error grow with eta'?",
    "paper/fig3": "Fig. 3: how coarse can the stress quadrature be (N/N_C) before the error grows?",
    "paper/fig4": "Fig. 4: does a higher-order Landweber closure beat zero order under a periodic force?",
    "paper/kolmogorov": "Without walls, does the steady amplitude follow the Landweber prediction e/(1-(1-e)^(n+1))?",
    "paper/speed_up": "How much faster than the direct SPH is the reduced model, and at what error?",
    "speed_vs_error/poiseuille_uniform": "Which closure is fastest for its error (uniform-force channel)?",
    "speed_vs_error/poiseuille_periodic": "Which closure is fastest for its error (periodic-force channel)?",
    "speed_vs_error/kolmogorov": "Which closure is fastest for its error (wall-free kolmogorov flow)?",
    "cellular/direct": "Does the direct SPH of the cellular flow reach the exact steady amplitude g/(2k^2 nu), and at what order?",
    "cellular/reduced": "Does the two-dimensional reduced model of the cellular flow reach the averaged direct SPH, and how much faster is it as eta'/eps' grows?",
    "cellular/coarse_continuum": "How close does the coarse continuum Navier-Stokes baseline on the reduced model's mesh come to the averaged direct SPH of the cellular flow (issue 43)?",
    "cavity/coarse_continuum_re100": "How close does a coarse continuum Navier-Stokes solve on the reduced model's 16 x 16 mesh (staggered, no-slip walls, sliding lid) come to the averaged direct SPH of the lid-driven cavity at Re = 100 over the transient, and how far is the direct SPH itself from the converged Navier-Stokes flow (issue 43)?",
    "taylor_green/coarse_continuum_re100": "How close does the coarse continuum Navier-Stokes baseline come to the averaged exact and direct Taylor-Green vortex at Re = 100 (issue 43)?",
    "taylor_green/reduced_2d_re100": "How close does the 2D reduced model stepped in time, linear and nonlinear (incompressible, convective flux of the closure), come to the averaged direct Taylor-Green vortex at Re = 100 over the transient, and at what cost (issue 43)?",
    "taylor_green/reference_sound_speed_re100": "Is the Taylor-Green reduced model's error against the direct SPH the reference's own: does the reference's floor (averaged direct SPH against the averaged exact field) fall as its sound speed grows from 10 to 40 U?",
    "speed_vs_error/cellular": "Which closure is fastest for its error in two dimensions (cellular flow)?",
    "two_phase/direct": "Does the direct SPH of the layered two-phase flow reach the analytic piecewise parabolas?",
    "two_phase/two_phase": "Section 7: how close is the reduced model of the two-phase flow to the direct SPH?",
    "two_phase/two_phase_eta": "Section 7: does the two-phase reduced model's error fall as eta' shrinks?",
    "error_budget/poiseuille_uniform": "Which ingredient limits the reduced model (oracle substitution), uniform-force channel?",
    "error_budget/fig4": "Which ingredient limits the reduced model (oracle substitution), Fig. 4's periodic-force channel?",
    "error_budget/two_phase_case3": "Which ingredient limits the reduced model (oracle substitution), two-phase case 3?",
    "near_wall/fig2": "With the near-wall formulation, does the error stay small and fall as eta' falls (Fig. 2's sweep)?",
    "near_wall/two_phase": "With the near-wall formulation, how close is the two-phase reduced model (cases 1, 2)?",
    "near_wall/fig2_192": "Fig. 2's sweep with the near-wall formulation at the paper's resolution (n_y = 192): does the error stay small?",
    "near_wall/two_phase_192": "With the near-wall formulation at the paper's resolution (n_y = 192), how close is the two-phase reduced model (cases 1, 2)?",
    "near_wall/fig2_192_steady1e-6": "As near_wall/fig2_192, the direct SPH run to a ten times tighter steady test: does the error depend on where the reference stopped?",
    "near_wall/two_phase_192_steady1e-6": "As near_wall/two_phase_192, the direct SPH run to a ten times tighter steady test: does the error depend on where the reference stopped?",
    "near_wall/landweber_known_zeros_uniform": "Does the paper's Landweber closure of order n = 0, 1, 2 improve under the near-wall balance when it knows the wall rows' zeros (uniform channel, n_y = 192)?",
    "near_wall/landweber_known_zeros_fig4": "Does the paper's Landweber closure of order n = 0, 1, 2 with the known zeros reach Fig. 4's second-order target (<= 8 %) under the near-wall balance?",
    "near_wall/landweber_known_zeros_two_phase": "Does the paper's second-order Landweber closure with the known zeros reach <= 1.5 % on the two-phase cases 1-3 (n_y = 192)?",
    "cavity/reduced_2d_re100": "How close does the 2D reduced model stepped in time (the walls as data and forces, CGLS coarse-fine, the exact quadrature) come to the averaged direct SPH of the lid-driven cavity at Re = 100 over the transient, against the coarse continuum baseline on the same mesh, and at what cost (issue 43)?",
    "cavity/tvf_re100": "Does the transport-velocity direct SPH with the generalized wall condition reproduce Ghia, Ghia & Shin's centre-line velocities of the lid-driven cavity at Re = 100 (within 2 % of the lid speed at n = 100), and where are its particles saved for a reduced model's transient?",
    "cylinders/linearised_steady": "What permeability does the direct SPH's steady state on its frozen lattice give, solved by one sparse solve instead of marched, and how close is it to the marched direct SPH's (cylinders/direct)?",
    "cylinders/reduced_steady_like_for_like": "How fast is the steady reduced model against the direct SPH also solved for its steady state (one sparse solve, not 57,600 marched steps), and how close is it to that frozen-lattice direct SPH?",
    "cylinders/reduced_tvf": "Does the force-density reduced model, with the reference's transport-velocity pair forces and the convective flux, reach the averaged transport-velocity direct SPH at Re ~ 1 and 10 (all-node max <= 1 %, k within 0.5 %), with parameters chosen on the Stokes lattice?",
    "cylinders/reduced_tvf_marched": "Marched in time from rest like the direct SPH (the closure applied at every rate evaluation, SUNDIALS ARKODE), how close is the nonlinear force-density model to the averaged transport-velocity direct SPH at the same time at Re ~ 1 and 10, and how fast is it, marched against marched?",
    "cylinders/reduced_tvf_transient": "Over the transient, not only at its end: how close is the marched force-density model to the averaged transport-velocity direct SPH at six times from t = 0.0125 to 0.4, and does the max over those times meet the 1 % target?",
    "cylinders/reduced_tvf/diagnostics": "Is the force-density model's remaining error at Re ~ 10 the closure's (eta', alpha, reconstruction refinement), or the model's?",
    "cylinders/tvf_re1": "Does the transport-velocity direct SPH (the generalized wall condition on the cylinders) give a permeability at Re ~ 1 that converges in n, where the standard WCSPH's moved away from the Stokes value with each refinement?",
    "cylinders/tvf_re10": "How far below the Stokes value does the permeability of the cylinder lattice fall at Re ~ 10 in the transport-velocity direct SPH, and does it agree between n = 48 and 96?",
    "taylor_green/tvf_re100_perturbed": "Does the transport-velocity direct SPH of the Taylor-Green vortex (Re = 100, started off the lattice as PySPH's --perturb 0.3 --hdx 1.5) follow the exact decay of its largest speed, and where are its particles saved for the reduced model's transient?",
    "near_wall/tikhonov_rules_two_phase": "Which alpha does each rule choose for the near-wall closure on the two-phase cases 1-3 (n_y = 192), and at what error?",
}


def pct(x):
    return "-" if x is None else f"{100 * x:.3g} %"


def best_reduced(rows):
    # Every coarse node (wall-surface nodes included) where the table has that subset; older tables: fluid nodes.
    every = any(get(r, "errors", "vs_averaged_direct_sph", "all_nodes") for r in rows)
    subset = "all_nodes" if every else "fluid_nodes"

    def err(r):
        return get(r, "errors", "vs_averaged_direct_sph", subset, "max_rel") or get(r, "errors", "vs_averaged_analytic", "fluid_nodes", "max_rel")
    def oracle(r):  # oracle rows are diagnostics (the error budget), not closures
        return bool(get(r, "params", "oracle", "closure")) or get(r, "params", "oracle", "boundary") not in (None, "none")
    ok = [r for r in rows if r.get("status") == "ok" and err(r) is not None and not oracle(r)]
    if not ok:
        return "no row ended ok"
    b = min(ok, key=err)
    ref = "averaged direct SPH" if get(b, "errors", "vs_averaged_direct_sph") else "averaged analytic"
    s = f"best: {b['label']}, max error {pct(err(b))} vs the {ref} ({'all coarse nodes' if every else 'fluid nodes'})"
    if get(b, "cost", "speed_up") is not None:
        s += f", speed-up {fmt(get(b, 'cost', 'speed_up'))}"
    return s


def headline(t):
    rows, kind = t["rows"], t["kind"]
    if kind in ("reduced_model", "reduced_model_2d", "coarse_continuum_2d"):
        return best_reduced(rows)
    if kind == "direct_sph_validation":
        e = [get(r, "errors", "particles_vs_analytic", "all", "max_rel") for r in rows]
        e = [x for x in e if x is not None]
        amp = [get(r, "errors", "amplitude", "relative_difference") for r in rows]
        amp = [abs(x) for x in amp if x is not None]
        worst = [get(r, "errors", "max_speed", "worst") for r in rows]
        worst = [(r["label"], x) for r, x in zip(rows, worst) if x is not None]
        ghia = [(r["label"], get(r, "errors", "centrelines", "worst")) for r in rows]
        ghia = [(l, x) for l, x in ghia if x is not None]
        perm = [(r["label"], get(r, "errors", "permeability", "relative_difference")) for r in rows]
        perm = [(l, x) for l, x in perm if x is not None]
        if perm:  # porous media: the Darcy permeability against the scene's Stokes reference
            return "k vs the Stokes reference: " + ", ".join(f"{l} {pct(x)}" for l, x in perm)
        if ghia:  # the lid-driven cavity: the centre lines against Ghia's, in units of the lid speed
            return "centre lines vs Ghia et al., largest \\|difference\\| / U: " + ", ".join(f"{l} {pct(x)}" for l, x in ghia)
        if worst:  # the Taylor-Green vortex: the largest speed against the exact decay
            return "max\\|v\\| vs exact decay, worst over the saved times: " + ", ".join(f"{l} {pct(x)}" for l, x in worst)
        if amp:  # cellular scenes: the fitted amplitude against the exact one
            return f"steady amplitude vs exact from {pct(min(amp))} to {pct(max(amp))}"
        if t["experiment"] == "appendix_b":
            d = [get(r, "errors", "convective_xx_vs_appendix_b_max_abs") for r in rows]
            d = [x for x in d if x is not None]
            return f"\\|T_c,xx SPH - App. B\\| from {fmt(min(d))} to {fmt(max(d))} (absolute)" if d else "-"
        return f"particle max error vs analytic from {pct(min(e))} to {pct(max(e))}" if e else "-"
    if kind == "quadrature_convergence":
        e = [get(r, "errors", "interior", "max_rel") for r in rows]
        e = [x for x in e if x is not None]
        return f"interior max error from {fmt(min(e))} to {fmt(max(e))}" if e else "-"
    if kind == "deconvolution_stability":
        finite = sum(1 for r in rows if r.get("all_finite"))
        return f"{finite} of {len(rows)} rows with finite output"
    return "-"


def link(folder, pattern):
    hits = sorted(glob.glob(os.path.join(ROOT, folder, pattern)))
    return ", ".join(f"[{os.path.basename(h)}]({os.path.relpath(h, ROOT)})" for h in hits) or "-"


def main():
    print("# Results index\n")
    print("Generated by `python3 experiments/summaries/results_index.py > results/README.md` (run by "
          "`scripts/reproduce.sh --full` and `--summaries`); every number is read from the committed tables. "
          "Per folder: its question, a headline number, the commits its rows came from (for tables from before "
          "rows recorded their own provenance: the commit of the run that wrote the table), and its summary and "
          "figures. Errors are relative to the analytic peak unless said otherwise.\n")
    print("| folder | question | headline | rows | commits | summary | figures |")
    print("|---|---|---|---|---|---|---|")
    tables = sorted(p for p in glob.glob(os.path.join(ROOT, "**", "*.json"), recursive=True)
                    if "/cells/" not in p and os.path.basename(p) != "bench_quadrature.json")
    for path in tables:
        folder = os.path.relpath(os.path.dirname(path), ROOT)
        t = load_table(path)
        if "rows" not in t:
            continue
        summary = link(folder, "summary.md") if glob.glob(os.path.join(ROOT, folder, "summary.md")) else link(folder, "SUMMARY.md")
        if folder.startswith("two_phase/two_phase"):
            summary = link("two_phase/reduced", "summary.md")
            figures = link("two_phase/reduced", "case*.png")
        else:
            figures = link(folder, "*.png")
        question = QUESTIONS.get(folder, t.get("description", "")[:120])
        print(f"| [{folder}]({folder}/) `{os.path.basename(path)}` | {question} | {headline(t)} | {len(t['rows'])} | "
              f"`{t['provenance'].get('git_commit', '?')}` | {summary} | {figures} |")


if __name__ == "__main__":
    main()
