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
