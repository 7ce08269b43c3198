#!/usr/bin/env python3
"""Plots of the TL-vs-UL pairing study (Ismail 2009 §4.7): the middle 7 particles' displacements (relative to the
pre-stretched equilibrium) for TL and UL, and the pairing measure min gap / spacing over time (1D); the 2D block's
bond-ratio histories and particle snapshots (2D, when pairing_2d.csv exists).
Usage: plot.py RESULTS_DIR (reads middle7.csv, pairing.csv, pairing_2d.csv, snapshots_2d.csv)."""
import math
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


RUNS_2D = ["TL", "UL plus", "UL conservative"]
KINDS_2D = ["uniaxial", "isotropic"]


def main_2d(out):
    """History (min bond ratio, bond deviation over its initial value) and snapshots of the 2D runs."""
    rows = read(os.path.join(out, "pairing_2d.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(14, 5))
    styles = {"TL": "-", "UL plus": "--", "UL conservative": ":"}
    colours = {"uniaxial": "tab:blue", "isotropic": "tab:red"}
    for kind in KINDS_2D:
        for run in RUNS_2D:
            sel = [r for r in rows if r["prestrain"] == kind and r["run"] == run]
            t = [num(r["t"]) for r in sel]
            label = f"{run}, {kind}"
            axes[0].plot(t, [num(r["min_bond_ratio"]) for r in sel], styles[run], color=colours[kind], label=label)
            axes[1].semilogy(t, [num(r["deviation_over_initial"]) for r in sel], styles[run], color=colours[kind],
                             label=label)
    axes[0].axhline(0.5, color="0.6", lw=0.8, ls=":", label="pairing threshold 0.5")
    axes[0].set_ylabel("min bond length / its equilibrium length")
    axes[0].set_title("2D pairing measure (nearest-neighbour bonds)")
    axes[1].set_ylabel("max |bond ratio - 1| / its initial value")
    axes[1].set_title("2D bond deviation")
    for ax in axes:
        ax.set_xlabel("t (dx / c, c^2 = E / rho)")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tl_ul_pairing_2d.png"), dpi=110)
    plt.close(fig)

    snaps = read(os.path.join(out, "snapshots_2d.csv"))
    labels = []
    for r in snaps:
        if r["snapshot"] not in labels:
            labels.append(r["snapshot"])
    labels = [lab for lab in labels if lab != "end"] + ["end"]
    nrow = len(KINDS_2D) * len(labels)
    fig, axes = plt.subplots(nrow, len(RUNS_2D), figsize=(16, 1.05 * nrow + 1), squeeze=False)
    cmap = plt.get_cmap("viridis")
    sc = None
    for ki, kind in enumerate(KINDS_2D):
        for li, lab in enumerate(labels):
            for ri, run in enumerate(RUNS_2D):
                ax = axes[ki * len(labels) + li][ri]
                sel = [r for r in snaps if r["prestrain"] == kind and r["run"] == run and r["snapshot"] == lab]
                ax.set_xticks([])
                ax.set_yticks([])
                if not sel:
                    ax.text(0.5, 0.5, "run stopped earlier", ha="center", va="center", transform=ax.transAxes)
                    continue
                disp = [math.hypot(num(r["dx_from_eq"]), num(r["dy_from_eq"])) for r in sel]
                free = [r["free"] == "1" for r in sel]
                sc = ax.scatter([num(r["x"]) for r in sel], [num(r["y"]) for r in sel], c=disp, s=[9 if f else 4 for f in free],
                                cmap=cmap, vmin=0, vmax=0.5, marker="o", linewidths=0)
                ax.set_aspect("equal")
                ax.set_title(f"{run}, {kind}, t = {num(sel[0]['t']):.3g}" + (" (end)" if lab == "end" else ""),
                             fontsize=8)
    fig.colorbar(sc, ax=axes, shrink=0.5, label="|u - u_eq| / dx")
    fig.savefig(os.path.join(out, "tl_ul_pairing_2d_snapshots.png"), dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    results = sys.argv[1] if len(sys.argv) > 1 else "results/tl-ul-pairing"
    if os.path.exists(os.path.join(results, "middle7.csv")):
        main(results)
    if os.path.exists(os.path.join(results, "pairing_2d.csv")):
        main_2d(results)
