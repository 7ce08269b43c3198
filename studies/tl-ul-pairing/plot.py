#!/usr/bin/env python3
"""Plots of the TL-vs-UL pairing study (Ismail 2009 §4.7): the middle 7 particles' displacements (relative to the
pre-stretched equilibrium) for TL and UL, and the pairing measure min gap / spacing over time.
Usage: plot.py RESULTS_DIR (reads middle7.csv, pairing.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read  # noqa: E402


def main(out):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    middle = read(os.path.join(out, "middle7.csv"))
    for ax, run in zip(axes[:2], ["TL", "UL"]):
        rows = [r for r in middle if r["run"] == run]
        t = [num(r["t"]) for r in rows]
        for k in range(-3, 4):
            ax.plot(t, [num(r[f"d{k}_over_dx"]) for r in rows], label=f"particle {k:+d}")
        ax.set_xlabel("t (dx / c)")
        ax.set_ylabel("u - u_eq (spacing)")
        ax.set_title(f"{run}: middle 7 particles")
        ax.legend(fontsize=7)
    ax = axes[2]
    pairing = read(os.path.join(out, "pairing.csv"))
    for run in ["TL", "UL"]:
        rows = [r for r in pairing if r["run"] == run]
        ax.plot([num(r["t"]) for r in rows], [num(r["min_gap_over_spacing"]) for r in rows], label=f"{run} min gap")
    ax.axhline(0.5, color="0.6", lw=0.8, ls=":", label="pairing threshold 0.5")
    ax.set_xlabel("t (dx / c)")
    ax.set_ylabel("min (x_{i+1} - x_i) / spacing")
    ax.set_title("pairing measure")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tl_ul_pairing.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-ul-pairing")
