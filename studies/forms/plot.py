#!/usr/bin/env python3
"""Plots for the forms study: python3 plot.py RESULTS_DIR.

tension_compression.png   conservative T_crit (tension) and |T_crit^-| (compression) vs h/dx per kernel
compression_conditions.png kernel x h map: L positive semi-definite (stable in compression) or not, with Powell's
                          conditions 1 (W'' negative definite, free block) and 3 (row sum of W'' > 0) marked
asymmetry.png             Jacobian asymmetry per form and configuration (1D, 2D) and against the displacement amplitude
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from matplotlib.colors import ListedColormap  # noqa: E402
from plot_common import ordered, plt, read, save  # noqa: E402

FORMS = ["uncorrected", "plus", "minus", "conservative"]


def tension_compression(out):
    rows = read(f"{out}/tcrit.csv")
    kernels = ordered(rows, "kernel")
    ceiling = 1e3
    fig, axes = plt.subplots(2, (len(kernels) + 1) // 2, figsize=(17, 7), sharex=True, sharey=True)
    for ax, k in zip(axes.flat, kernels):
        for direction, style in (("tension", dict(color="C3", marker="o")), ("compression", dict(color="C0",
                                                                                                   marker="s"))):
            pts = sorted((float(r["h_over_dx"]), abs(float(r["tcrit"]))) for r in rows
                         if r["kernel"] == k and r["form"] == "conservative" and r["direction"] == direction)
            ax.plot([p[0] for p in pts], [ceiling if math.isinf(p[1]) else max(p[1], 1e-9) for p in pts], ms=3, lw=1,
                    label=("T_crit" if direction == "tension" else "|T_crit^-|"), **style)
        ax.set_yscale("log")
        ax.set_ylim(1e-7, 3 * ceiling)
        ax.axhspan(0.5 * ceiling, 3 * ceiling, color="0.9", zorder=0)
        ax.set_title(k)
        ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("h / dx")
    for ax in axes[:, 0]:
        ax.set_ylabel("critical |T| (conservative)")
    axes.flat[0].legend(fontsize=8, loc="lower left")
    for ax in list(axes.flat)[len(kernels):]:
        ax.set_visible(False)
    fig.suptitle("1D bar, N = 30: critical tension and compression of the conservative form "
                 "(uncorrected 4x, plus 2x; top band: none)")
    save(fig, f"{out}/tension_compression.png", dpi=130, announce=True)


def compression_conditions(out):
    rows = read(f"{out}/compression_conditions.csv")
    kernels = ordered(rows, "kernel")
    hs = sorted({float(r["h_over_dx"]) for r in rows})
    grid = [[0.0] * len(hs) for _ in kernels]
    fig, ax = plt.subplots(figsize=(16, 5.5))
    for r in rows:
        i, j = kernels.index(r["kernel"]), hs.index(float(r["h_over_dx"]))
        stable = math.isinf(float(r["tcrit_minus_conservative"]))
        grid[i][j] = 1.0 if stable else 0.0
        marks = ("1" if r["cond1_w2_negative_definite"] == "1" else "") + ("3" if r["cond3_row_sum_positive"] == "1"
                                                                         else "")
        if marks:
            ax.text(j, i, marks, ha="center", va="center", fontsize=7)
    ax.imshow(grid, cmap=ListedColormap(["#e8a0a0", "#a8d8a8"]), vmin=0, vmax=1, aspect="auto")
    ax.set_yticks(range(len(kernels)))
    ax.set_yticklabels(kernels)
    step = max(1, len(hs) // 16)
    ax.set_xticks(range(0, len(hs), step))
    ax.set_xticklabels([f"{h:g}" for h in hs[::step]])
    ax.set_xlabel("h / dx")
    ax.set_title("Compression, N = 30: green = stable for every T < 0 (L positive semi-definite), red = finite "
                 "T_crit^-;\ntext: Powell's condition 1 (W'' negative definite) and/or 3 (row sum of W'' > 0) holds")
    save(fig, f"{out}/compression_conditions.png", dpi=130, announce=True)


def asymmetry(out):
    rows = read(f"{out}/asymmetry.csv")
    amp = read(f"{out}/asymmetry_vs_amplitude.csv")
    floor = 1e-17
    fig, axes = plt.subplots(1, 3, figsize=(18, 5), gridspec_kw=dict(width_ratios=[1.2, 1.2, 1]))
    for ax, dim in zip(axes[:2], ["1", "2"]):
        sub = [r for r in rows if r["dim"] == dim]
        configs = ordered(sub, "config")
        width = 0.2
        for k, form in enumerate(FORMS):
            values = [max(floor, float(next(r for r in sub if r["config"] == c and r["form"] == form)
                                       ["relative_asymmetry"])) for c in configs]
            ax.bar([i + (k - 1.5) * width for i in range(len(configs))], values, width, label=form)
        ax.set_yscale("log")
        ax.set_ylim(floor / 2, 10)
        ax.set_xticks(range(len(configs)))
        ax.set_xticklabels(configs, rotation=25, ha="right", fontsize=8)
        ax.set_title(f"{dim}D: " + ("pre-stressed bar" if dim == "1" else "plane-strain elasticity"))
        ax.axhline(1e-15, color="grey", lw=0.8, ls="--")
    axes[0].set_ylabel(r"$\|A - A^T\|_F / \|A\|_F$")
    axes[1].legend(fontsize=8)
    ax = axes[2]
    for k, form in enumerate(FORMS):
        for load, ls in (("0.1", "-"), ("0", ":"), ("-0.1", "--")):
            pts = sorted((float(r["amplitude_dx"]), max(floor, float(r["relative_asymmetry"]))) for r in amp
                         if r["kernel"] == "cubic" and r["form"] == form and r["load"] == load)
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], ls=ls, color=f"C{k}", marker="o", ms=3,
                      label=f"{form}" if load == "0.1" else None)
    ax.set_xlabel("displacement amplitude a / dx")
    ax.set_title("1D, cubic h = 1.3: against the amplitude\n(solid T = 0.1, dotted T = 0, dashed T = -0.1)")
    ax.legend(fontsize=8)
    fig.suptitle("Symmetry of the exact Jacobian A = -da/du (dashed line: round-off level)")
    save(fig, f"{out}/asymmetry.png", dpi=130, announce=True)


def main(out):
    tension_compression(out)
    compression_conditions(out)
    asymmetry(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/forms")
