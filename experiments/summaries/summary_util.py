"""Helpers shared by the summarize_*.py scripts (imported from the scripts' own folder)."""
import math


def fmt(x, digits=3):
    """A table cell: '-' for missing, integers as they are, other numbers to `digits` significant digits."""
    if x is None:
        return "-"
    if isinstance(x, int) and not isinstance(x, bool):
        return str(x)
    return f"{x:.{digits}g}"


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
