#!/usr/bin/env python3
"""Plot of the swegle-nonlinear study: measured growth rate versus kick amplitude v0, one panel per formulation, a
curve per (xi, integrator), with the full-state linear growth rate as a horizontal line. Runs that did not grow are
drawn at the bottom of the panel (open markers). Usage: plot.py RESULTS_DIR (reads runs.csv, writes growth_vs_v0.png).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read, xi_colour  # noqa: E402


def main(out):
    runs = read(os.path.join(out, "runs.csv"))
    forms = list(dict.fromkeys(r["formulation"] for r in runs))
    xis = sorted({num(r["xi"]) for r in runs})
    # the production dt is the largest dt per (formulation, xi); the dt/2 rows belong to the dt study
    dt_main = max(num(r["dt"]) for r in runs)
    main_rows = [r for r in runs if abs(num(r["dt"]) - dt_main) < 1e-2 * dt_main]
    ncol = min(3, len(forms))
    nrow = math.ceil(len(forms) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.0 * ncol, 3.8 * nrow), squeeze=False)
    floor = 1e-3
    styles = {"predictor-corrector": ("o", "-"), "leapfrog": ("s", "--")}
    for k, form in enumerate(forms):
        ax = axes[k // ncol][k % ncol]
        for xi in xis:
            colour = xi_colour(xi, xis)
            rows = [r for r in main_rows if r["formulation"] == form and num(r["xi"]) == xi]
            if not rows:
                continue
            lin = num(rows[0]["gamma_linear"])
            if lin > 0:
                ax.axhline(lin, color=colour, lw=0.8, ls=":", label=f"xi {xi:g}: linear")
            for integ, (marker, ls) in styles.items():
                sub = sorted((r for r in rows if r["integrator"] == integ), key=lambda r: num(r["v0"]))
                v0 = [num(r["v0"]) for r in sub]
                g = [num(r["gamma_measured"]) if r["grew"] == "1" else floor for r in sub]
                ax.plot(v0, g, ls, color=colour, lw=0.8, alpha=0.7)
                for x, y, r in zip(v0, g, sub):
                    ax.plot(x, y, marker, color=colour, mfc=colour if r["grew"] == "1" else "none", ms=5)
                ax.plot([], [], marker + ls, color=colour, label=f"xi {xi:g}: {integ}")
        ax.set(xscale="log", yscale="log", title=form, xlabel="kick v0 (cm/us)")
        ax.set_ylabel("gamma (1/us); bottom: no growth")
        ax.set_ylim(floor * 0.7, None)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6, loc="lower left")
    for k in range(len(forms), nrow * ncol):
        axes[k // ncol][k % ncol].axis("off")
    fig.suptitle("Swegle test, rate-form scheme: measured growth versus kick amplitude (dotted: full-state linear)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "growth_vs_v0.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/swegle-nonlinear")
