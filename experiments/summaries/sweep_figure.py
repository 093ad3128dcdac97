"""Error against each swept key of a table (its spec's `axes`): one panel per axis with scalar values, one line per
series (the cell label without that axis's "key=value"), the error in % on the y axis. Used by summarize.py for
every table that sweeps a key; the figure is written beside the summary as <summary>_sweep.png.

The error plotted is the first of these the rows carry (its name is the y label): the max over all coarse nodes
against the averaged direct SPH, against the averaged analytic solution, against the analytic solution; the direct
SPH's particles against the analytic solution; the closure's stress against the exact pair sum; a deconvolution's
relative error."""
import math

from summary_util import figure_label, get, log_ticks

ERRORS = [
    (("errors", "vs_averaged_direct_sph", "all_nodes", "max_rel"), "max error vs averaged direct SPH, all nodes (%)"),
    (("errors", "vs_averaged_analytic", "all_nodes", "max_rel"), "max error vs averaged analytic, all nodes (%)"),
    (("errors", "vs_analytic", "all_nodes", "max_rel"), "max error vs analytic, all nodes (%)"),
    (("errors", "particles_vs_analytic", "all", "max_rel"), "particles: max error vs analytic (%)"),
    (("errors", "stress_xy", "channel", "max_rel"), "T_xy: max error vs exact pair sum (%)"),
    (("errors", "relative_error",), "relative error of the solution (%)"),
]
MAX_SERIES = 12


def _param(row, key):
    return get(row.get("params", {}), *key.split("."))


def sweeps(table):
    """[(axis key, numeric?)] of the spec's axes whose values are scalars and take at least two values."""
    axes = (table.get("spec") or {}).get("axes") or {}
    out = []
    for key, values in axes.items():
        if not isinstance(values, list) or len(values) < 2:
            continue
        if any(isinstance(v, (dict, list)) for v in values):
            continue
        numeric = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)
        out.append((key, numeric))
    return out


def error_key(rows):
    for path, name in ERRORS:
        if any(isinstance(get(r, *path), (int, float)) for r in rows):
            return path, name
    return None, None


def _series_name(label, key):
    parts = [p for p in label.split(", ") if not p.startswith(key + "=")]
    return ", ".join(parts) or "all"


def draw(plt, table, path):
    """Writes the figure to `path`; False (nothing written) when the table sweeps no scalar key, its rows carry no
    known error, or there are more than MAX_SERIES lines per panel."""
    rows = [r for r in table.get("rows", []) if r.get("status") == "ok"]
    axes = sweeps(table)
    err_path, err_name = error_key(rows)
    if not axes or err_path is None:
        return False
    panels = []
    for key, numeric in axes:
        series = {}
        for r in rows:
            x, e = _param(r, key), get(r, *err_path)
            if x is None or not isinstance(e, (int, float)) or isinstance(x, (dict, list)):
                continue
            series.setdefault(_series_name(r.get("label", ""), key), []).append((x, 100.0 * e))
        if series and len(series) <= MAX_SERIES:
            panels.append((key, numeric, series))
    if not panels:
        return False
    fig, axs = plt.subplots(1, len(panels), figsize=(5.6 * len(panels), 4.4), squeeze=False)
    for ax, (key, numeric, series) in zip(axs[0], panels):
        categories = []
        if not numeric:
            for pts in series.values():
                for x, _ in pts:
                    if x not in categories:
                        categories.append(x)
        ys = []
        for k, (name, pts) in enumerate(sorted(series.items())):
            pts = sorted(pts, key=lambda p: p[0] if numeric else categories.index(p[0]))
            xs = [p[0] if numeric else categories.index(p[0]) for p in pts]
            ax.plot(xs, [p[1] for p in pts], marker="os^vD<>ph*xX"[k % 12], label=figure_label(name, 38))
            ys += [p[1] for p in pts]
        if not numeric:
            ax.set_xticks(range(len(categories)))
            ax.set_xticklabels([str(c) for c in categories], rotation=20, fontsize=8)
        else:
            xs_all = [p[0] for pts in series.values() for p in pts]
            if min(xs_all) > 0 and max(xs_all) / min(xs_all) > 4:
                ax.set_xscale("log")
            if all(isinstance(x, int) for x in xs_all):  # orders, counts: integer ticks
                from matplotlib.ticker import MaxNLocator
                ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        positive = [y for y in ys if y > 0]
        if positive and max(positive) / min(positive) > 20:
            ax.set_yscale("log")
        log_ticks(ax)
        ax.set_xlabel(key)
        ax.set_ylabel(err_name, fontsize=9)
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=2, frameon=False)
    fig.suptitle(f"{table.get('experiment', '')}: error against the swept key (the rows that ended ok)", fontsize=10)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return True
