#!/usr/bin/env python3
"""Plots of the rate-form Swegle study: one log-KE-versus-time panel per formulation with a curve per volume strain
xi (Powell Fig. 4.2 layout), and measured versus full-state linear growth rates. Usage: plot.py RESULTS_DIR (reads
ke.csv and runs.csv)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import growth_panels, ke_panels, num, plt, read, save  # noqa: E402


def main(out):
    ke, runs = read(os.path.join(out, "ke.csv")), read(os.path.join(out, "runs.csv"))
    series, forms, xis, info = ke_panels(
        ke, runs, "Swegle test, rate-form scheme (continuity, EOS, Jaumann rate); runs stop at KE = 1e10 KE0",
        os.path.join(out, "ke_all.png"))

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.6))
    markers = "osD^v<>"
    for k, form in enumerate(forms):
        rows = [info[(form, xi)] for xi in xis if (form, xi) in info]
        lin = [num(r["gamma_linear_class"]) for r in rows]
        meas = [num(r["gamma_measured"]) for r in rows]
        m = markers[k % len(markers)]
        ax1.plot(lin, meas, m, color=f"C{k}", label=form, alpha=0.8)
        ax2.plot(xis, [g if g > 1e-3 else math.nan for g in lin], "-", color=f"C{k}", alpha=0.6)
        ax2.plot(xis, meas, m, color=f"C{k}", label=form)
    growth_panels(ax1, ax2, [1e-1, 30], "measured = linear", "full-state linear gamma (1/us), excited mirror class",
                  "measured gamma (1/us), fit of log KE / 2", "gamma (1/us): lines linear, markers measured")
    save(fig, os.path.join(out, "growth.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/swegle-rate-form")
