"""Helpers shared by the studies' plot.py scripts (import after adding studies/common to sys.path)."""
import csv
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    """Rows of a CSV file as dicts."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(x):
    """float(x), NaN for text that is not a number."""
    try:
        return float(x)
    except ValueError:
        return math.nan


def xi_colour(xi, xis):
    """Colour of a volume strain xi: black at 1, blue for compression, red for tension (coolwarm)."""
    if abs(xi - 1) < 1e-12:
        return "k"
    cmap = plt.get_cmap("coolwarm")
    lo, hi = min(xis), max(xis)
    return cmap(0.5 + 0.5 * (xi - 1) / max(hi - 1, 1 - lo, 1e-12))


def read_vtp(path, names):
    """Points (lists x, y) and the named point-data arrays (first component, lists) of an ASCII .vtp file written by
    io/vtk.hpp's write_vtp."""
    import re

    with open(path) as f:
        text = f.read()

    def array(name):
        m = re.search(r'<DataArray[^>]*Name="%s"[^>]*NumberOfComponents="(\d+)"[^>]*>(.*?)</DataArray>' % re.escape(name),
                      text, re.S)
        if not m:
            raise KeyError(f"{path}: no DataArray '{name}'")
        k = int(m.group(1))
        v = [float(s) for s in m.group(2).split()]
        return [v[i::k] for i in range(k)]

    pts = array("Points")
    return pts[0], pts[1], {n: array(n)[0] for n in names}
