#!/usr/bin/env python3
"""The one summary tool: reads a table's kind (and, where one kind has several views, its experiment name or
scene) and writes its summary with the matching view.

Usage: python3 experiments/summaries/summarize.py TABLE.json [MORE.json ...] [OUT_DIR]
OUT_DIR defaults to the first table's folder. Writes OUT_DIR/summary.md (OUT_DIR/SUMMARY.md for the
deconvolution hard-case suite, which takes all its tables at once) and, where python3-matplotlib is available
and the view draws one, OUT_DIR/summary.png (two-phase reduced model: case*.png, pareto_case*.png; it takes the
main table and the eta' sweep). `--which TABLE.json` prints the view that would be used and exits.
`--view front|profiles TABLE.json [OUT_DIR]` draws one reduced_model table's speed-against-error front
(OUT_DIR/front.md, .png) or its profiles (OUT_DIR/profiles.md, .png) whatever its name;
`--headline OUT_DIR TABLE.json ...` writes the quick run's OUT_DIR/summary.md and prints its headline.
A figure that cannot be drawn (matplotlib missing: run under Debian's /usr/bin/python3 with python3-matplotlib)
is an error, exit 1; `--no-figures` first writes the Markdown alone.

Views (the summarize_*.py files beside this one, kept importable and runnable on their own):
  deconvolution_stability                          summarize_stability      tables -> SUMMARY.md
  quadrature_convergence                           summarize_appendix_c     table  -> summary.md
  direct_sph_validation  experiment appendix_b     summarize_appendix_b     table  -> summary.md
                         layered-two-phase scene   summarize_two_phase      table  -> summary.md
                         cellular scene            summarize_cellular       table  -> summary.md
                         taylor-green scene        summarize_taylor_green   table  -> summary.md
                         lid-driven-cavity scene   summarize_cavity         table  -> summary.md
                         otherwise                 summarize_validation     table  -> summary.md
  reduced_model          experiment pareto_*       summarize_pareto         table  -> summary.md, summary.png
                         experiment error_budget_* summarize_error_budget  table  -> summary.md, summary.png
                         experiment two_phase      summarize_two_phase_reduced  main, eta -> OUT_DIR/
                         otherwise                 summarize_reduced_model  table  -> summary.md, summary.png
                         (rows of model force_density_2d: as reduced_model_2d_force_density; of mesh_2d: as
                         reduced_model_2d, whatever the experiment's name)
  reduced_model_2d                                 summarize_cellular_reduced  table -> summary.md, summary_fields.png
                                                   (experiment pareto_*: the front as above, and the fields)
  reduced_model_2d_force_density                   summarize_force_density_2d  table -> summary.md, summary_fields.png
  direct_sph_validation  cylinder scenes           ../cylinders/table       table  -> summary.md (permeability)
  snapshot_closure                                 summarize_snapshot_closure  table -> summary.md, summary.png
  coarse_continuum_2d                              summarize_coarse_continuum  table -> summary.md
A table whose spec sweeps a scalar key (`axes`) also gets OUT_DIR/summary_sweep.png (SUMMARY_sweep.png): the error
against each swept key, one line per cell (sweep_figure.py); not with --view or --no-figures.
Every number is read from the tables. Errors are printed in % (relative differences with their sign) by every view;
Appendix B's stresses are in model units. The paths written are printed, one a line ("summarize: wrote PATH").
"""
import contextlib
import json
import os
import runpy
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def view_of(table):
    kind, name = table.get("kind"), table.get("experiment", "")
    if kind == "deconvolution_stability":
        return "summarize_stability", "stdout", "SUMMARY.md"
    if kind == "quadrature_convergence":
        return "summarize_appendix_c", "stdout", "summary.md"
    rows = table.get("rows", [])
    scenes = {(r.get("params", {}).get("scene") or {}).get("name") for r in rows}
    if kind == "direct_sph_validation":
        if name == "appendix_b":
            return "summarize_appendix_b", "stdout", "summary.md"
        if scenes & {"cylinder-lattice", "cylinder-channel"}:
            return "../cylinders/table", "stdout", "summary.md"
        if "layered-two-phase" in scenes:
            return "summarize_two_phase", "stdout", "summary.md"
        if "cellular" in scenes:
            return "summarize_cellular", "stdout", "summary.md"
        if "taylor-green" in scenes:
            return "summarize_taylor_green", "stdout", "summary.md"
        if "lid-driven-cavity" in scenes:
            return "summarize_cavity", "stdout", "summary.md"
        return "summarize_validation", "stdout", "summary.md"
    if kind == "reduced_model":
        model = reduced_model_of(rows)
        if model == "force_density_2d":
            return "summarize_force_density_2d", "prefix", "summary"
        if model == "mesh_2d":
            return "summarize_cellular_reduced", "prefix", "summary"
        if name.startswith("pareto_"):
            return "summarize_pareto", "prefix", "summary"
        if name.startswith("error_budget_"):
            return "summarize_error_budget", "prefix", "summary"
        if name == "two_phase":
            return "summarize_two_phase_reduced", "folder", ""
        return "summarize_reduced_model", "prefix", "summary"
    if kind == "reduced_model_2d":
        return "summarize_cellular_reduced", "prefix", "summary"
    if kind == "reduced_model_2d_force_density":
        return "summarize_force_density_2d", "prefix", "summary"
    if kind == "snapshot_closure":
        return "summarize_snapshot_closure", "prefix", "summary"
    if kind == "coarse_continuum_2d":
        return "summarize_coarse_continuum", "prefix", "summary"
    raise SystemExit(f"summarize: table kind '{kind}' has no view; known kinds: deconvolution_stability, "
                     "quadrature_convergence, direct_sph_validation, reduced_model, reduced_model_2d, "
                     "reduced_model_2d_force_density, snapshot_closure, coarse_continuum_2d")


def reduced_model_of(rows):
    """Which reduced model a reduced_model table's rows ran: the row's "model" where the cell named one, else what
    its output says (the 2D models write `fields`, the force-density model's with `outside_solid`; the column
    writes `profile`); "column" when no row tells (rows that all failed)."""
    for r in rows:
        model = (r.get("params") or {}).get("model")
        if model:
            return model
    for r in rows:
        if "profile" in r:
            return "column"
        if "fields" in r:
            return "force_density_2d" if "outside_solid" in r["fields"] else "mesh_2d"
    return "column"


def run_view(script, args, stdout_file=None):
    path = os.path.join(HERE, script + ".py")
    saved_argv, saved_path = sys.argv, list(sys.path)
    sys.argv = [path] + args
    sys.path.insert(0, HERE)
    try:
        if stdout_file is None:
            runpy.run_path(path, run_name="__main__")
        else:
            with open(stdout_file, "w") as out, contextlib.redirect_stdout(out):
                runpy.run_path(path, run_name="__main__")
    finally:
        sys.argv, sys.path = saved_argv, saved_path


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv else 2
    if argv[0] == "--no-figures":  # the Markdown alone; otherwise a figure that cannot be drawn is an error
        os.environ["CLOSURELAB_FIGURES"] = "off"
        argv = argv[1:]
        if not argv:
            print(__doc__)
            return 2
    if argv[0] == "--headline":
        run_view("summarize_headline", argv[1:])
        return 0
    forced = None
    if argv[0] == "--view":
        views = {"front": ("summarize_pareto", "prefix", "front"),
                 "profiles": ("summarize_reduced_model", "prefix", "profiles")}
        if len(argv) < 3 or argv[1] not in views:
            print("usage: summarize.py --view front|profiles TABLE.json [OUT_DIR]", file=sys.stderr)
            return 2
        forced = views[argv[1]]
        argv = argv[2:]
    which = argv[0] == "--which"
    args = argv[1:] if which else argv
    tables = [a for a in args if a.endswith(".json")]
    rest = [a for a in args if not a.endswith(".json")]
    if not tables or len(rest) > 1:
        print("usage: summarize.py TABLE.json [MORE.json ...] [OUT_DIR]", file=sys.stderr)
        return 2
    missing = [t for t in tables if not os.path.isfile(t)]
    if missing:
        print(f"summarize: no such table: {', '.join(missing)} (arguments ending in .json are tables; an output "
              "folder must not end in .json)", file=sys.stderr)
        return 2
    for t in tables:  # a spec, a benchmark's or a peer's output has no rows: say so instead of failing in a view
        try:
            with open(t) as f:
                data = json.load(f)
        except ValueError as e:
            print(f"summarize: {t} is not JSON ({e})", file=sys.stderr)
            return 2
        if not isinstance(data, dict) or not isinstance(data.get("rows"), list) or "kind" not in data:
            what = "a spec" if isinstance(data, dict) and "cells" in data else "not a table"
            print(f"summarize: {t} is {what}: a closurelab table has a kind and rows (closurelab run writes one)",
                  file=sys.stderr)
            return 2
        if t == tables[0]:
            first = data
    script, contract, target = forced or view_of(first)
    if which:
        print(script)
        return 0
    out_dir = rest[0] if rest else (os.path.dirname(tables[0]) or ".")
    os.makedirs(out_dir, exist_ok=True)
    before = files_in(out_dir)
    if contract == "stdout":
        run_view(script, tables, os.path.join(out_dir, target))
    elif contract == "prefix":
        run_view(script, [tables[0], os.path.join(out_dir, target)])
    else:
        run_view(script, tables + [out_dir])
    if forced is None and os.environ.get("CLOSURELAB_FIGURES") != "off":
        sweep_figure_of(first, out_dir, os.path.splitext(target)[0] or "summary")
    for path in sorted(p for p, stamp in files_in(out_dir).items() if before.get(p) != stamp):
        print(f"summarize: wrote {path}")
    return 0


def sweep_figure_of(table, out_dir, stem):
    """OUT_DIR/<stem>_sweep.png: the error against each swept key of the (first) table (sweep_figure.py), where its
    spec sweeps a scalar key."""
    sys.path.insert(0, HERE)
    try:
        import sweep_figure
        from summary_util import pyplot_or_none
        if not sweep_figure.sweeps(table):
            return
        plt = pyplot_or_none()
        if plt is not None:
            sweep_figure.draw(plt, table, os.path.join(out_dir, stem + "_sweep.png"))
    finally:
        sys.path.remove(HERE)


def files_in(folder):
    """The files directly in `folder` with their modification time and size (to report what a view wrote)."""
    out = {}
    for name in os.listdir(folder):
        path = os.path.join(folder, name)
        if os.path.isfile(path):
            st = os.stat(path)
            out[path] = (st.st_mtime_ns, st.st_size)
    return out


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
