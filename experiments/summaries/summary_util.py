"""Helpers shared by the summarize_*.py scripts (imported from the scripts' own folder)."""
import json
import math
import os
import sys

# The repository's python/ package (closurelab.tables), found from this file's place, so that a summary run from any
# folder reads rows as the pandas reader reads them.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "python"))
from closurelab.tables import _rename_legacy_node_sets  # noqa: E402


def fmt(x, digits=3):
    """A table cell: '-' for missing, integers as they are, other numbers to `digits` significant digits."""
    if x is None:
        return "-"
    if isinstance(x, int) and not isinstance(x, bool):
        return str(x)
    return f"{x:.{digits}g}"


def pct(x, digits=3):
    """A fraction as a percentage cell: '-' for missing, else 100 x to `digits` significant digits and ' %'."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{100.0 * x:.{digits}g} %"


def spct(x, digits=3):
    """A signed fraction (a relative difference) as a percentage cell, the sign always shown."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{100.0 * x:+.{digits}g} %"


NOISY_SPREAD = 0.10  # the runner's status line uses the same threshold (kNoisySpread, core/base/timing_noise.hpp)
NOISY_NOTE = ("*noisy*: the reduced model's repeated runs spread by more than 10 % ((median - min) / min): its time, "
              "and so the speed-up, is not resolved to better than that spread (load from other work).")


def noisy_note(lines):
    """[blank line, NOISY_NOTE] when some line marks a speed-up " (noisy)", else nothing."""
    return ["", NOISY_NOTE] if any(" (noisy)" in line for line in lines) else []


def speed_up_cell(speed_up, spread):
    """A speed-up for a table, marked " (noisy)" where the repeated runs' spread exceeds NOISY_SPREAD."""
    text = fmt(speed_up)
    if speed_up is not None and spread is not None and spread > NOISY_SPREAD:
        text += " (noisy)"
    return text


def get(d, *keys):
    """d[k1][k2]..., or None where a key is missing."""
    for k in keys:
        if not isinstance(d, dict) or k not in d:
            return None
        d = d[k]
    return d


def slope(points):
    """Least-squares slope of log(y) against log(x) over the positive (x, y) points; nan with fewer than two."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sum((p[0] - mx) ** 2 for p in pts)


def _joined(values):
    return ", ".join(str(v) for v in values) if values else "unknown"


def load_table(path):
    """A table as the views read it. A table whose provenance is derived from its rows (the runner's format since
    rows record their own provenance) gets the display fields the views print: the commits its rows came from,
    marked when rows came from a dirty build, the compilers, build types, thread counts, the span of dates and the
    commands; a row computed by a dirty build has " [dirty build]" appended to its label. Older tables, whose
    header held the provenance of one run, are returned as they are (so their summaries regenerate unchanged)."""
    with open(path) as f:
        table = json.load(f)
    _rename_legacy_node_sets(table.get("rows", []))
    prov = table.get("provenance", {})
    if prov.get("derived_from") != "rows":
        return table
    rows = table.get("rows", [])
    row_prov = [r.get("provenance") for r in rows if isinstance(r.get("provenance"), dict)]
    commits = _joined(prov.get("commits", []))
    notes = []
    if prov.get("dirty_rows"):
        notes.append(f"{prov['dirty_rows']} row(s) from a dirty build")
    if prov.get("rows_without_provenance"):
        notes.append(f"{prov['rows_without_provenance']} row(s) without provenance")
    first, last = prov.get("first_date_utc", ""), prov.get("last_date_utc", "")
    table["provenance"] = {
        "git_commit": commits + (f" ({'; '.join(notes)})" if notes else ""),
        "compiler": _joined(prov.get("compilers", [])),
        "build_type": _joined(prov.get("build_types", [])),
        "threads": _joined(sorted({p.get("threads") for p in row_prov if p.get("threads") is not None})),
        "date_utc": first if first == last else f"{first} to {last}",
        "command": "; ".join(sorted({p.get("command", "") for p in row_prov})) or "unknown",
        "host": _joined(prov.get("hosts", [])),
    }
    for r in rows:
        if isinstance(r.get("provenance"), dict) and r["provenance"].get("dirty"):
            r["label"] = r.get("label", "") + " [dirty build]"
    return table


def figure_label(label, width=40):
    """A cell label for a figure: axis values "a.b.c=v" shortened to "c=v" (no internal key paths), wrapped."""
    import textwrap
    parts = []
    for p in label.split(", "):
        key, eq, value = p.partition("=")
        parts.append(f"{key.rsplit('.', 1)[-1]}={value}" if eq and " " not in key.strip() else p)
    return "\n".join(textwrap.wrap(", ".join(parts), width)) or label


def dirty_mark(row):
    """" [dirty build]" for a row computed by a build with uncommitted changes (for views that print no label)."""
    p = row.get("provenance")
    return " [dirty build]" if isinstance(p, dict) and p.get("dirty") else ""


def log_ticks(ax, which="both"):
    """Enough labelled ticks on log axes: at 1, 2 and 5 per decade where the axis spans few decades (matplotlib
    labels only the powers of ten, one label or none on an axis within a decade), as plain numbers."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    axes = {"x": [ax.xaxis], "y": [ax.yaxis], "both": [ax.xaxis, ax.yaxis]}[which]
    for axis in axes:
        if axis.get_scale() != "log":
            continue
        lo, hi = sorted(axis.get_view_interval())
        if lo <= 0 or hi / lo > 1e4:
            continue
        axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_formatter(NullFormatter())


def pyplot_or_none():
    """matplotlib.pyplot on the Agg backend. Where matplotlib is missing the summary fails loudly (exit 1, naming
    the interpreter and the package), unless figures were turned off (summarize.py --no-figures, or
    CLOSURELAB_FIGURES=off): then None, with a note on stderr, and only the Markdown is written."""
    if os.environ.get("CLOSURELAB_FIGURES") == "off":
        print("figures off: no figure drawn", file=sys.stderr)
        return None
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        return plt
    except ImportError:
        raise SystemExit(f"summary: cannot draw the figure: matplotlib is not importable by {sys.executable} "
                         "(Debian: apt-get install python3-matplotlib, and run the summaries with /usr/bin/python3; "
                         "or pass --no-figures for the tables alone)")
