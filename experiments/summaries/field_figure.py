"""The coarse fields of a 2D reduced-model row (its `fields`, docs/row_schema.md) as a figure: the averaged direct
SPH and the reduced model in one colour range, their difference, the solid drawn. Used by the force-density view
(summarize_force_density_2d.py) and experiments/cylinders/reduced_summary.py.

`fields` holds the coarse axes `x` (nx nodes) and `y` (ny nodes) and, per field, the node values flat with index
j * nx + i (x fastest): reshaped to (ny, nx), row j is y[j]."""
import math

from summary_util import get


def node_count(row):
    f = row.get("fields") or {}
    return len(f.get("x", [])), len(f.get("y", []))


def _grid(np, f, name, comp):
    return np.array(f[name][comp], dtype=float).reshape(len(f["y"]), len(f["x"]))


def _solid_outline(plt, ax, row, np, colour):
    """The solid as the scene defines it where it is a known shape (the cylinder of cylinder-lattice and
    cylinder-channel at the box's centre, the walls of cylinder-channel), and the coarse nodes inside it from
    `outside_solid` (any scene)."""
    scene = get(row, "params", "scene") or {}
    name, length = scene.get("name"), scene.get("l", 1.0)
    a = scene.get("radius_over_length")
    if name in ("cylinder-lattice", "cylinder-channel") and a is not None:
        ax.add_patch(plt.Circle((0.5 * length, 0.5 * length), a * length, fill=False, color=colour, lw=1.5))
    f = row["fields"]
    if "outside_solid" in f:
        x, y = np.array(f["x"]), np.array(f["y"])
        inside = ~np.array(f["outside_solid"], dtype=bool).reshape(len(y), len(x))
        if inside.any():
            xx, yy = np.meshgrid(x, y)
            ax.plot(xx[inside], yy[inside], "x", color=colour, ms=3, mew=0.8, label="coarse nodes in the solid")


def draw(plt, row, path, title, model="reduced", model_name="reduced model", difference_name="v_red - v_direct"):
    """Writes the figure of `row` to `path`. Two panels per field (direct, and the model's: `fields[model]`, named
    `model_name`) share one colour range; the difference is in % of the averaged direct SPH's peak speed. One column
    of nodes (an x-invariant scene) is drawn as profiles of v_x against y. Returns False (nothing written) when the
    row has no such fields."""
    import numpy as np
    f = row.get("fields")
    if not f or model not in f:
        return False
    nx, ny = node_count(row)
    has_direct = "direct_average" in f
    rx, ry = _grid(np, f, model, "vx"), _grid(np, f, model, "vy")
    if has_direct:
        dx, dy = _grid(np, f, "direct_average", "vx"), _grid(np, f, "direct_average", "vy")
        peak = float(np.hypot(dx, dy).max()) or 1.0
    else:
        peak = float(np.hypot(rx, ry).max()) or 1.0
    x, y = np.array(f["x"]), np.array(f["y"])
    if nx == 1:
        fig, (ax, ex) = plt.subplots(1, 2, figsize=(9.0, 4.0))
        if has_direct:
            ax.plot(y, dx[:, 0] / peak, "bs", mfc="none", label="averaged direct SPH")
        ax.plot(y, rx[:, 0] / peak, "r.-", label=model_name)
        ax.set_xlabel("y")
        ax.set_ylabel("v_x / peak")
        ax.legend(fontsize=8, loc="best")
        if has_direct:
            ex.plot(y, 100.0 * np.hypot(rx - dx, ry - dy)[:, 0] / peak, "r.-")
            ex.set_ylabel(f"|{difference_name}| / peak (%)")
        else:
            ex.axis("off")
        ex.set_xlabel("y")
        fig.suptitle(title, fontsize=9)
        fig.tight_layout()
        fig.savefig(path, dpi=110)
        plt.close(fig)
        return True
    dxs = x[1] - x[0]
    dys = y[1] - y[0] if ny > 1 else dxs
    extent = [x[0] - 0.5 * dxs, x[-1] + 0.5 * dxs, y[0] - 0.5 * dys, y[-1] + 0.5 * dys]
    panels = ([(dx, dy, "averaged direct SPH |v| / peak")] if has_direct else []) + \
        [(rx, ry, model_name + " |v| / peak")]
    vmax = max(float(np.hypot(u, v).max()) for u, v, _ in panels) / peak
    ncols = len(panels) + (1 if has_direct else 0)
    fig, axes = plt.subplots(1, ncols, figsize=(4.4 * ncols, 4.2), squeeze=False)
    axes = axes[0]
    images = []
    for ax, (u, v, name) in zip(axes, panels):
        images.append(ax.imshow(np.hypot(u, v) / peak, origin="lower", extent=extent, vmin=0.0, vmax=vmax,
                                cmap="viridis", interpolation="nearest"))
        ax.set_title(name, fontsize=9)
    # One colour bar for the panels that share the range.
    fig.colorbar(images[-1], ax=list(axes[:len(panels)]), fraction=0.046, pad=0.03, format="%.2f")
    if has_direct:
        diff = 100.0 * np.hypot(rx - dx, ry - dy) / peak
        im = axes[-1].imshow(diff, origin="lower", extent=extent, cmap="magma", interpolation="nearest")
        axes[-1].set_title(f"|{difference_name}| / peak (%)", fontsize=9)
        fig.colorbar(im, ax=axes[-1], fraction=0.046, pad=0.03, format="%.2g")
    for k, ax in enumerate(axes):
        _solid_outline(plt, ax, row, np, "w" if k < len(panels) else "c")
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        ax.set_aspect("equal")
        ax.set_xlabel("x")
    axes[0].set_ylabel("y")
    fig.suptitle(title, fontsize=9)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return True


def figure_row(rows, label=None):
    """The row to draw: the one labelled `label` (None if it has no fields), else the ok row with fields and a
    direct reference at the finest resolution, the smallest all-node error first; None without such a row."""
    if label is not None:
        return next((r for r in rows if r.get("label") == label and "fields" in r), None)

    def resolution(r):
        s = get(r, "params", "scene") or {}
        return s.get("n", s.get("n_y", 0))

    def err(r):
        e = get(r, "errors", "vs_averaged_direct_sph", "all_nodes", "max_rel")
        return math.inf if e is None else e

    ok = [r for r in rows if r.get("status") == "ok" and "fields" in r]
    if not ok:
        ok = [r for r in rows if "fields" in r]
    if not ok:
        return None
    with_direct = [r for r in ok if "direct_average" in r["fields"]] or ok
    finest = max(resolution(r) for r in with_direct)
    return min((r for r in with_direct if resolution(r) == finest), key=err)
