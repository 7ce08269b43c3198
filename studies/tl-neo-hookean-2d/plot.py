#!/usr/bin/env python3
"""Plot of the 2D Neo-Hookean TL-SPH study (Ismail 2009 §5.4.3, Figs. 5.10-5.12): the centre particles' Cauchy stress
T11 against the imposed stretch lambda_1 for the three stretch paths, with the analytic (5.5) along each path and
the reference table. Usage: plot.py RESULTS_DIR (reads history_case{1,2,3}.csv, table.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read  # noqa: E402

TITLES = {1: "lambda_2 = 1 (Fig. 5.10)", 2: "lambda_2 = 2 (Fig. 5.11)", 3: "lambda_2 1 -> 2 with lambda_1 (Fig. 5.12)"}


def main(out):
    table = read(os.path.join(out, "table.csv"))
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.8))
    for ax, case in zip(axes, (1, 2, 3)):
        h = read(os.path.join(out, f"history_case{case}.csv"))
        lam = [num(r["lambda1"]) for r in h]
        ax.plot(lam, [num(r["t11_analytic_over_mu"]) for r in h], "k-", lw=1.5, label="analytic (5.5) along the path")
        ax.plot(lam, [num(r["t11_sph_over_mu"]) for r in h], "tab:red", lw=0.8, label="SPH, centre particles")
        rows = [r for r in table if r["case"] == str(case)]
        notes = [(num(r["lambda1"]), num(r["t11_notes_over_mu"])) for r in rows if r["t11_notes_over_mu"] != "nan"]
        if notes:
            ax.plot(*zip(*notes), "ko", mfc="none", ms=9, label="reference table [Ismail2009, (5.5)]")
        ax.set_xlabel("imposed stretch lambda_1")
        ax.set_ylabel("T11 / mu")
        ax.set_title(TITLES[case])
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tl_neo_hookean_2d.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-neo-hookean-2d")
