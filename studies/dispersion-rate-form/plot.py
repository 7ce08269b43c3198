#!/usr/bin/env python3
"""Plots of the dispersion-rate-form study. Usage: plot.py RESULTS_DIR.

dispersion_2d.png: the two acoustic branches omega dx / c_P (solid) and growth rates (dashed, where omega^2 < 0)
along Gamma-X-M-Gamma of the square lattice, h = 1.3 dx, one panel per formulation, a colour per volume strain xi.
bar_1d.png: infinite-lattice critical stress of 1D basic SPH from the symbol against the closed form.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save, xi_colour  # noqa: E402


def dispersion(out, h="1.3"):
    rows = [r for r in read(os.path.join(out, "branches_2d.csv")) if r["h_over_dx"] == h]
    forms = list(dict.fromkeys(r["formulation"] for r in rows))
    xis = sorted({num(r["xi"]) for r in rows})
    ncol = 4
    nrow = math.ceil(len(forms) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.4 * nrow), squeeze=False, sharey=True)
    for k, form in enumerate(forms):
        ax = axes[k // ncol][k % ncol]
        for xi in xis:
            sub = [r for r in rows if r["formulation"] == form and num(r["xi"]) == xi]
            s = [num(r["s"]) for r in sub]
            colour = xi_colour(xi, xis)
            for b, lw in (("l", 1.2), ("t", 0.8)):
                ax.plot(s, [num(r["omega_" + b]) for r in sub], "-", color=colour, lw=lw,
                        label=f"xi {xi:g}" if b == "l" else None)
                g = [num(r["growth_" + b]) for r in sub]
                if max(g) > 0:
                    ax.plot(s, g, "--", color=colour, lw=lw)
        for x in (1, 2):
            ax.axvline(x, color="0.8", lw=0.6)
        ax.set_xticks([0, 1, 2, 2 + math.sqrt(2)], ["Γ", "X", "M", "Γ"])
        ax.set_title(form, fontsize=10)
        if k % ncol == 0:
            ax.set_ylabel("ω dx / c_P (solid), growth (dashed)")
        if k == 0:
            ax.legend(fontsize=7)
    for k in range(len(forms), nrow * ncol):
        axes[k // ncol][k % ncol].axis("off")
    fig.suptitle(f"Rate-form scheme, square lattice, cubic spline, h = {h} dx, steel: acoustic branches "
                 "(thick: the higher branch)", fontsize=10)
    save(fig, os.path.join(out, "dispersion_2d.png"), dpi=130)


def bar(out):
    rows = read(os.path.join(out, "bar_1d.csv"))
    h = [num(r["h_over_dx"]) for r in rows]
    floor = 1e-10
    sym = [max(num(r["sigma_crit_over_M_symbol"]), floor) for r in rows]
    cf = [max(num(r["closed_form_grid"]), floor) for r in rows]
    inf = [max(num(r["closed_form_infinite"]), floor) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogy(h, sym, "o", mfc="none", label="bisection on the symbol's spectrum")
    ax.semilogy(h, cf, "x", label="|g|² / (2L − |g|²), same k grid")
    ax.semilogy(h, inf, "-", lw=0.8, label="T/(1 − T), grid-free infimum")
    decorate(ax, "h / dx", "σ0,crit / M (floor 1e-10 = unstable at any tension)",
             "1D basic SPH rate form, infinite lattice, cubic spline", title_size=10)
    save(fig, os.path.join(out, "bar_1d.png"), dpi=130)


if __name__ == "__main__":
    dispersion(sys.argv[1])
    bar(sys.argv[1])
