#!/usr/bin/env python3
"""Plots of the plane-wave reflection study: the energy reflected by each SPH absorbing boundary against the angle of
incidence, measured (points) and from the plane-wave analysis (lines, spectral/plane_wave_reflection.hpp); and the
energy histories 2 KE / KE0. Usage: plot.py RESULTS_DIR (reads runs.csv, series/<tag>.csv)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read  # noqa: E402

COLOURS = {"P": "tab:orange", "M": "tab:green", "H-Powell": "tab:red", "H-Higdon": "tab:purple",
           "traction": "tab:brown", "periodic": "k"}


def main(out):
    rows = read(os.path.join(out, "runs.csv"))
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(15, 6))
    lam = min(num(r["lambda"]) for r in rows if num(r["ny"]) > 0)
    angled = [r for r in rows if num(r["lambda"]) == 2 * lam and r["gradient"] == "normalised"]
    for cond, colour in COLOURS.items():
        mine = sorted((r for r in angled if r["condition"] == cond), key=lambda r: num(r["theta_deg"]))
        th = [num(r["theta_deg"]) for r in mine]
        if cond == "periodic":
            ax.plot(th, [100 * abs(num(r["measured"]) - 1) for r in mine], "kx", label="periodic strip: |2 KE/KE0 - 1|")
            continue
        ax.plot(th[1:], [100 * num(r["analytic"]) for r in mine[1:]], "-", color=colour, lw=1,
                label=f"{cond} analytic (0 at normal incidence)")
        ax.plot(th, [100 * num(r["measured"]) for r in mine], "o", color=colour, label=f"{cond} SPH")
    ax.set_yscale("log")
    ax.set_ylim(1e-4, 200)
    ax.set_xlabel("angle of incidence (degrees)")
    ax.set_ylabel("reflected energy (% of the incident)")
    ax.set_title(f"plane P wave at an absorbing boundary, lambda = {2 * lam:g} dx: SPH against (2.49)")
    ax.legend(fontsize=7, ncol=2)
    for r in rows:
        if r["condition"] not in ("P", "periodic") or r["gradient"] != "normalised" or num(r["lambda"]) != 2 * lam:
            continue
        s = read(os.path.join(out, "series", f"{r['condition']}_ny{r['ny']}_lambda{num(r['lambda']):g}.csv"))
        ax2.plot([num(x["t"]) for x in s], [num(x["two_ke_over_ke0"]) for x in s],
                 ls="-" if r["condition"] == "P" else ":", lw=1,
                 label=f"{r['condition']} {num(r['theta_deg']):.1f} deg")
    ax2.set_yscale("log")
    ax2.set_xlabel("t (us)")
    ax2.set_ylabel("2 KE / KE0")
    ax2.set_title(f"energy histories, lambda = {2 * lam:g} dx (P and the periodic check)")
    ax2.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "reflection.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1])
