#!/usr/bin/env python3
"""Plots of the Turek-Hron CSM3 study: the tip displacement u_y(A)(t) and u_x(A)(t) at the three resolutions against
the reference band (mean +- amplitude), the coarsest resolution with the other reference gradient and the wider
clamp, and the deformed beam at the largest deflection of the last period coloured by the Cauchy stress sigma_xx.
Usage: plot.py RESULTS_DIR (reads runs.csv, tip_<run>.csv, snapshot.csv)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402

REF = {"ux": (-14.305e-3, 14.645e-3), "uy": (-63.607e-3, 65.160e-3)}  # [TurekHron2006], CSM3: mean, amplitude (m)


def band(ax, key):
    mean, amp = REF[key]
    ax.axhspan(1e3 * (mean - amp), 1e3 * (mean + amp), color="0.85", zorder=0, label="reference mean ± amplitude")
    ax.axhline(1e3 * mean, color="0.4", lw=0.8, ls="--")


def main(out):
    runs = read(os.path.join(out, "runs.csv"))
    gradient = runs[0]["gradient"]
    clamp = runs[0]["clamp_layers"]
    main_runs = [r for r in runs if r["gradient"] == gradient and r["clamp_layers"] == clamp]
    side = [r for r in runs if r not in main_runs]
    fig, axes = plt.subplots(3, 1, figsize=(12, 12))
    for key, ax in zip(["uy", "ux"], axes[:2]):
        band(ax, key)
        for r in main_runs:
            rows = read(os.path.join(out, f"tip_{r['run']}.csv"))
            ax.plot([num(x["t"]) for x in rows], [1e3 * num(x[f"{key}_A"]) for x in rows], lw=1.0,
                    label=f"{r['across']} across ({r['free']} free), {gradient}")
        decorate(ax, "t (s)", f"{key[0]}_{key[1]}(A) (mm)", loc="lower left")
    axes[0].set_title("CSM3 tip displacement, finite-strain TL SPH (St Venant-Kirchhoff), no damping")
    ax = axes[2]
    band(ax, "uy")
    coarse = [r for r in main_runs if r["across"] == runs[0]["across"]] + side
    for r in coarse:
        rows = read(os.path.join(out, f"tip_{r['run']}.csv"))
        ax.plot([num(x["t"]) for x in rows], [1e3 * num(x["uy_A"]) for x in rows], lw=1.0, label=r["run"])
    decorate(ax, "t (s)", "u_y(A) (mm)", "coarsest resolution: reference gradient and clamp width", loc="lower left")
    save(fig, os.path.join(out, "tl_csm3_tip.png"))

    snap = os.path.join(out, "snapshot.csv")
    if os.path.exists(snap):
        rows = read(snap)
        fig, ax = plt.subplots(figsize=(12, 5))
        t = [math.radians(a) for a in range(0, 361, 2)]
        ax.fill([0.2 + 0.05 * math.cos(a) for a in t], [0.2 + 0.05 * math.sin(a) for a in t], color="0.8", zorder=0)
        free = [r for r in rows if r["fixed"] == "0"]
        fixed = [r for r in rows if r["fixed"] == "1"]
        sc = ax.scatter([num(r["x"]) for r in free], [num(r["y"]) for r in free],
                        c=[num(r["sigma_xx"]) / 1e3 for r in free], cmap="coolwarm", s=8)
        ax.scatter([num(r["x"]) for r in fixed], [num(r["y"]) for r in fixed], c="k", s=6, marker="s", label="clamp")
        ax.plot([0.6], [0.2], "k+", ms=10, label="A (undeformed)")
        fig.colorbar(sc, ax=ax, label="Cauchy sigma_xx (kPa)")
        ax.set_aspect("equal")
        decorate(ax, "x (m)", "y (m)", "deformed beam at the largest deflection of the last period (finest run)",
                 loc="upper right")
        save(fig, os.path.join(out, "tl_csm3_snapshot.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-csm3")
