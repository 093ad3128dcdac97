"""Read closurelab results tables (`DIR/<name>.json`, docs/row_schema.md) into pandas and numpy.

    import sys; sys.path.insert(0, "python")          # or: PYTHONPATH=python from the repository root
    from closurelab.tables import load, load_fields
    df = load("results/cylinders/reduced/reduced.json")
    df[["label", "errors.vs_averaged_direct_sph.all_nodes.max_rel", "errors.permeability.reduced_vs_direct_sph",
        "cost.speed_up"]]
    f = load_fields(df[df.label == "a=0.2L n=192"].iloc[0])
    f["reduced_vx"].shape                              # (ny, nx): f["reduced_vx"][j, i] at (f["x"][i], f["y"][j])

`load(path)`: a DataFrame with one record per row of the table and the columns `closurelab export` writes: `id`,
`label`, `status`, then every leaf of the row's `params`, `errors` and `cost` as one dotted column
(`params.scene.n`, `errors.vs_averaged_direct_sph.all_nodes.max_rel`, `cost.reduced_timing.min_seconds`); errors
are fractions, as stored (relative to the peak the row's kind names). A row without a value has NaN (None) there.
Short lists of numbers (at most 8, such as snapshot times) are kept as lists; longer ones (profiles, fields) are
left out: read them with `load_fields`. Also `message` (the row's error or status message, where it has one),
`note` (a warning that leaves the status as it is, e.g. a parameter rule's choice at the edge of its scan) and
`table` (the path read, which `load_fields` uses). The table's own keys (`experiment`, `kind`, `description`,
`complete`, `path`) are in `df.attrs`. Rows written before the node sets were renamed (`all` beside `all_nodes`)
are read with `fluid_nodes`, as the summaries read them; rows that name the averaging width `eta_over_ly` (the
channels and kolmogorov before every scene said `eta_over_l`) are read with `params.scene.eta_over_l`.

`load_fields(row)`: the row's coarse fields as numpy arrays. `row` is a record of `load` (a pandas Series; the table
is read again from its `table` column) or a row as parsed from the JSON (a dict). A 2D row (`fields`): `x` (nx,),
`y` (ny,), and per field `<name>_vx`, `<name>_vy` of shape (ny, nx) (`reduced`, `direct_average`,
`averaged_analytic`, whichever the row has), `outside_solid` (ny, nx) booleans and `reduced_density_deviation`
(ny, nx) where the row has them (docs/row_schema.md, "fields"). A column row (`profile`, 1D): every list of the
profile as a 1D array (`y`, `reduced`, `analytic`, `analytic_average`, `direct_average`). A row with neither (a
failed cell): ValueError.
"""
import json
import os

__all__ = ["load", "load_fields", "read_table", "flatten"]

_SECTIONS = ("params", "errors", "cost")
_SHORT_LIST = 8


def _rename_legacy_node_sets(obj):
    """Rows written before the node sets were named for what they hold reported the fluid nodes as "all" beside
    "all_nodes"; such a pair is read as "fluid_nodes" and "all_nodes" (the numbers are the same). The summaries
    (experiments/summaries/summary_util.py) read rows through this one function too."""
    if isinstance(obj, dict):
        if "all" in obj and "all_nodes" in obj and "fluid_nodes" not in obj:
            obj["fluid_nodes"] = obj.pop("all")
        for v in obj.values():
            _rename_legacy_node_sets(v)
    elif isinstance(obj, list):
        for v in obj:
            _rename_legacy_node_sets(v)


def _rename_legacy_scene_keys(rows):
    """The channels' and kolmogorov's averaging width was stored as `eta_over_ly` before every scene named it
    `eta_over_l`: such a row's scene is read with `eta_over_l` (as `closurelab export` and the runner read it)."""
    for row in rows:
        scene = row.get("params", {}).get("scene") if isinstance(row, dict) else None
        if isinstance(scene, dict) and "eta_over_ly" in scene and "eta_over_l" not in scene:
            scene["eta_over_l"] = scene.pop("eta_over_ly")


_cache = {}


def read_table(path):
    """The table at `path` as parsed JSON (a dict with `rows`), legacy node sets renamed; cached per file version."""
    st = os.stat(path)
    key = (os.path.abspath(path), st.st_mtime_ns, st.st_size)
    if key not in _cache:
        with open(path) as f:
            table = json.load(f)
        if not isinstance(table, dict) or not isinstance(table.get("rows"), list):
            raise ValueError(f"{path}: not a closurelab results table (no \"rows\" array)")
        _rename_legacy_node_sets(table["rows"])
        _rename_legacy_scene_keys(table["rows"])
        _cache.clear()  # one table at a time: fields make tables large
        _cache[key] = table
    return _cache[key]


def flatten(value, prefix, out):
    """The leaves of `value` under the dotted `prefix` into `out` (as `closurelab export` names them): objects
    descend; numbers, strings and booleans are leaves; lists of at most 8 scalars are kept as lists, longer ones and
    nulls left out."""
    if isinstance(value, dict):
        for k, v in value.items():
            flatten(v, f"{prefix}.{k}" if prefix else k, out)
    elif isinstance(value, list):
        if len(value) <= _SHORT_LIST and all(not isinstance(e, (dict, list)) for e in value):
            out[prefix] = list(value)
    elif value is not None:
        out[prefix] = value
    return out


def _record(row, path):
    r = {k: row.get(k) for k in ("id", "label", "status")}
    for section in _SECTIONS:
        if section in row:
            flatten(row[section], section, r)
    message = row.get("error") or row.get("message")
    if message is None and isinstance(row.get("reduced_model"), dict):
        message = row["reduced_model"].get("message")
    r["message"] = message
    r["note"] = row.get("note")
    r["table"] = path
    return r


def load(path):
    """The table at `path` as a pandas DataFrame: one record per row, one dotted column per leaf of params, errors
    and cost (see the module's docstring)."""
    import pandas as pd
    table = read_table(path)
    records = [_record(row, path) for row in table["rows"]]
    front = ["id", "label", "status"]
    tail = ["message", "note", "table"]
    columns = front + sorted({c for r in records for c in r} - set(front) - set(tail)) + tail
    df = pd.DataFrame.from_records(records, columns=columns)
    for k in ("experiment", "kind", "description", "complete"):
        df.attrs[k] = table.get(k)
    df.attrs["path"] = path
    return df


def _raw_row(row):
    if isinstance(row, dict):
        return row
    # a record of load(): find the row again in its table by id (or label where ids repeat)
    get = row.get if hasattr(row, "get") else (lambda k, d=None: d)
    path = get("table")
    if not isinstance(path, str):
        raise ValueError("load_fields: a record of load() (with its `table` column) or a row dict is needed")
    rows = read_table(path)["rows"]
    matches = [r for r in rows if r.get("id") == get("id")]
    if len(matches) > 1:
        matches = [r for r in matches if r.get("label") == get("label")]
    if not matches:
        raise ValueError(f"load_fields: row id {get('id')!r} not in {path}")
    return matches[0]


def load_fields(row):
    """The coarse fields of `row` as numpy arrays (see the module's docstring)."""
    import numpy as np
    raw = _raw_row(row)
    f = raw.get("fields")
    if isinstance(f, dict) and "x" in f and "y" in f:
        x, y = np.asarray(f["x"], dtype=float), np.asarray(f["y"], dtype=float)
        shape = (len(y), len(x))
        out = {"x": x, "y": y}
        for name, value in f.items():
            if name in ("x", "y"):
                continue
            if isinstance(value, dict):
                for comp, values in value.items():
                    out[f"{name}_{comp}"] = np.asarray(values, dtype=float).reshape(shape)
            elif isinstance(value, list) and len(value) == shape[0] * shape[1]:
                dtype = bool if value and isinstance(value[0], bool) else float
                out[name] = np.asarray(value, dtype=dtype).reshape(shape)
        return out
    p = raw.get("profile")
    if isinstance(p, dict):
        return {k: np.asarray(v, dtype=float) for k, v in p.items()
                if isinstance(v, list) and all(isinstance(e, (int, float)) and not isinstance(e, bool) for e in v)}
    label = raw.get("label")
    raise ValueError(f"load_fields: row {label!r} (status {raw.get('status')!r}) has no fields or profile")


if __name__ == "__main__":  # a quick look: python3 python/closurelab/tables.py TABLE.json
    import sys
    frame = load(sys.argv[1])
    print(f"{len(frame)} rows, {len(frame.columns)} columns; kind {frame.attrs['kind']}")
    print(frame[["label", "status"]].to_string())
