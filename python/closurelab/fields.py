"""The coarse fields of a table's 2D rows as XDMF + HDF5, for ParaView (File > Open, the .xdmf, "Xdmf Reader").

    /usr/bin/python3 python/closurelab/fields.py TABLE.json OUT_DIR [--row LABEL ...]

writes OUT_DIR/<table>.h5 (one group per row with fields) and, per row, OUT_DIR/<table>_<k>.xdmf: the coarse mesh
as a 2D rectilinear grid (x, y: the nodes of the row's `fields`) with, at the nodes, the reduced model's velocity
`reduced`, the averaged direct SPH's `direct_average` and their `difference` (reduced - direct), as 3-component
vectors (v_z = 0, as ParaView's vector tools want), their magnitudes `*_speed`, and where the row has them
`averaged_analytic`, `outside_solid` (1 outside every solid, 0 inside) and `reduced_density_deviation`. Prints the
paths written. Needs h5py (Debian's python3-h5py). Rows without fields (a column model's rows, a failed cell) are
skipped with a note. In Python: `write_xdmf(table_path, out_dir, labels=None) -> [paths]`.

The layout (docs/row_schema.md, "fields"): a field's values are flat with node (i, j) at j * nx + i, so a
(ny, nx) array in C order; XDMF's 2DRectMesh takes Dimensions "ny nx" (slowest first) and the VXVY geometry
(the x nodes, then the y nodes), which is that order.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from closurelab.tables import load_fields, read_table  # noqa: E402

_VECTORS = ("reduced", "direct_average", "averaged_analytic")


def _stem(path):
    return os.path.splitext(os.path.basename(path))[0]


def _slug(label):
    return re.sub(r"[^A-Za-z0-9._=-]+", "_", label).strip("_")[:60] or "row"


def _arrays(row):
    """The row's named node arrays: (ny, nx, 3) vectors, (ny, nx) scalars; x and y."""
    import numpy as np
    f = load_fields(row)
    out = {}
    for name in _VECTORS:
        if f"{name}_vx" in f:
            v = np.stack([f[f"{name}_vx"], f[f"{name}_vy"], np.zeros_like(f[f"{name}_vx"])], axis=-1)
            out[name] = v
            out[f"{name}_speed"] = np.hypot(f[f"{name}_vx"], f[f"{name}_vy"])
    if "reduced" in out and "direct_average" in out:
        out["difference"] = out["reduced"] - out["direct_average"]
        out["difference_speed"] = np.hypot(out["difference"][..., 0], out["difference"][..., 1])
    if "outside_solid" in f:
        out["outside_solid"] = f["outside_solid"].astype(np.int8)
    if "reduced_density_deviation" in f:
        out["reduced_density_deviation"] = f["reduced_density_deviation"]
    return f["x"], f["y"], out


def _data_item(h5name, path, shape, dtype):
    number = "Char" if dtype.kind in "iub" and dtype.itemsize == 1 else ("Int" if dtype.kind in "iu" else "Float")
    return (f'<DataItem Dimensions="{" ".join(str(d) for d in shape)}" NumberType="{number}" '
            f'Precision="{dtype.itemsize}" Format="HDF">{h5name}:{path}</DataItem>')


def write_xdmf(table_path, out_dir, labels=None):
    """Writes OUT_DIR/<table>.h5 and one OUT_DIR/<table>_<k>.xdmf per row with fields (the rows labelled in
    `labels` only, when given); returns the paths written."""
    import h5py
    table = read_table(table_path)
    rows = [(k, r) for k, r in enumerate(table["rows"]) if isinstance(r.get("fields"), dict) and "x" in r["fields"]]
    if labels:
        missing = [lab for lab in labels if lab not in {r.get("label") for _, r in rows}]
        if missing:
            raise ValueError(f"{table_path}: no row with fields labelled {missing}; labels with fields: "
                             f"{[r.get('label') for _, r in rows]}")
        rows = [(k, r) for k, r in rows if r.get("label") in labels]
    if not rows:
        raise ValueError(f"{table_path}: no row has 2D fields (a column model's table, or every cell failed)")
    os.makedirs(out_dir, exist_ok=True)
    stem = _stem(table_path)
    h5name = stem + ".h5"
    h5path = os.path.join(out_dir, h5name)
    written = [h5path]
    with h5py.File(h5path, "w") as h5:
        h5.attrs["table"] = os.path.abspath(table_path)
        h5.attrs["experiment"] = str(table.get("experiment", ""))
        for k, row in rows:
            x, y, arrays = _arrays(row)
            group = f"/row_{k}"
            g = h5.create_group(group)
            g.attrs["label"] = row.get("label", "")
            g.attrs["status"] = row.get("status", "")
            g.create_dataset("x", data=x)
            g.create_dataset("y", data=y)
            for name, a in arrays.items():
                g.create_dataset(name, data=a)
            attributes = []
            for name, a in arrays.items():
                kind = "Vector" if a.ndim == 3 else "Scalar"
                attributes.append(f'   <Attribute Name="{name}" AttributeType="{kind}" Center="Node">\n    '
                                  f'{_data_item(h5name, f"{group}/{name}", a.shape, a.dtype)}\n   </Attribute>')
            label = (row.get("label", "") or "").replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")
            xdmf = "\n".join([
                '<?xml version="1.0" ?>',
                '<Xdmf Version="2.0">',
                ' <Domain>',
                f'  <Grid Name="{label}" GridType="Uniform">',
                f'   <Topology TopologyType="2DRectMesh" Dimensions="{len(y)} {len(x)}"/>',
                '   <Geometry GeometryType="VXVY">',
                f'    {_data_item(h5name, f"{group}/x", x.shape, x.dtype)}',
                f'    {_data_item(h5name, f"{group}/y", y.shape, y.dtype)}',
                '   </Geometry>',
                *attributes,
                '  </Grid>',
                ' </Domain>',
                '</Xdmf>', ""])
            path = os.path.join(out_dir, f"{stem}_{k}_{_slug(row.get('label', ''))}.xdmf")
            with open(path, "w") as f:
                f.write(xdmf)
            written.append(path)
    skipped = len(table["rows"]) - len(rows)
    if skipped and not labels:
        print(f"fields: {skipped} row(s) of {table_path} without 2D fields skipped", file=sys.stderr)
    return written


def main(argv):
    if len(argv) < 2 or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    labels, rest = [], []
    k = 0
    while k < len(argv):
        if argv[k] == "--row" and k + 1 < len(argv):
            labels.append(argv[k + 1])
            k += 2
        else:
            rest.append(argv[k])
            k += 1
    if len(rest) != 2:
        print("usage: fields.py TABLE.json OUT_DIR [--row LABEL ...]", file=sys.stderr)
        return 2
    try:
        paths = write_xdmf(rest[0], rest[1], labels or None)
    except ValueError as e:
        print(f"fields: {e}", file=sys.stderr)
        return 2
    for p in paths:
        print(f"fields: wrote {p}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
