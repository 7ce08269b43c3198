#!/usr/bin/env python3
"""Plots of the tl-instability study: the fastest growing mode of the non-variational NCSPH TL form at rest on the
clamped CSM3 beam, the free beam and the free block (arrows: the mode's displacement, colour: its magnitude; grey
squares: clamp), and the eigenvalues mu of A on the beam for the ncsph and ncsph-variational forms.
Usage: plot.py RESULTS_DIR (reads modes.csv, spectrum.csv)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402


def main(out):
    modes = read(os.path.join(out, "modes.csv"))
    fig = plt.figure(figsize=(14, 10))
    panels = [("beam", "clamped CSM3 beam"), ("free-beam", "the same particles, all free"), ("block", "free block")]
    for k, (name, title) in enumerate(panels):
        ax = fig.add_subplot(4, 1, k + 1) if name != "block" else fig.add_subplot(2, 3, 4)
        rows = [r for r in modes if r["set"] == name and r["form"] == "ncsph"]
        free = [r for r in rows if r["role"] == "free"]
        fixed = [r for r in rows if r["role"] == "fixed"]
        x = [num(r["x"]) for r in free]
        y = [num(r["y"]) for r in free]
        mx = [num(r["mode_x"]) for r in free]
        my = [num(r["mode_y"]) for r in free]
        mag = [math.hypot(a, b) for a, b in zip(mx, my)]
        if fixed:
            ax.scatter([num(r["x"]) for r in fixed], [num(r["y"]) for r in fixed], marker="s", s=14, color="0.6")
        sc = ax.scatter(x, y, c=mag, cmap="viridis", s=18)
        ax.quiver(x, y, mx, my, mag, cmap="viridis", angles="xy", scale_units="xy",
                  scale=max(mag) / (0.8 * (abs(y[1] - y[0]) if len(y) > 1 and y[1] != y[0] else 0.005)), width=0.002)
        ax.set_aspect("equal")
        ax.set_title(f"fastest growing mode, ncsph form: {title}", fontsize=10)
        fig.colorbar(sc, ax=ax, fraction=0.02, pad=0.01, label="|mode|")
    ax = fig.add_subplot(2, 3, (5, 6))
    spec = read(os.path.join(out, "spectrum.csv"))
    for form, colour, marker in [("ncsph-variational", "tab:blue", "o"), ("ncsph", "tab:red", "x")]:
        rows = [r for r in spec if r["form"] == form]
        ax.scatter([num(r["mu_re"]) for r in rows], [num(r["mu_im"]) for r in rows], s=10, color=colour,
                   marker=marker, label=f"{form} (beam)")
    ax.set_xscale("symlog", linthresh=1e4)
    decorate(ax, "Re mu (1/s^2)", "Im mu (1/s^2)",
             "eigenvalues of A at rest on the clamped beam: the variational form's are real and >= 0", title_size=10)
    save(fig, os.path.join(out, "tl_instability.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-instability")
