#!/usr/bin/env python3
"""Plots of the time-step study (Ismail 2009 (4.47)): the linear leap-frog limit in units of Ismail's h/c against
support/dx for each kernel (symbol and clamped bar), and the energy ratio of the validation-bar runs against the step.
Usage: plot.py RESULTS_DIR (reads limits.csv, energy.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read  # noqa: E402


def main(out):
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.5))
    ax = axes[0]
    rows = read(os.path.join(out, "limits.csv"))
    kernels = []
    for r in rows:
        if r["kernel"] not in kernels:
            kernels.append(r["kernel"])
    for k in kernels:
        sel = [r for r in rows if r["kernel"] == k]
        s = [num(r["support_over_dx"]) for r in sel]
        line, = ax.plot(s, [num(r["dt_symbol_over_ismail_rule"]) for r in sel], "o-", label=f"{k}: periodic symbol")
        ax.plot(s, [num(r["dt_bar_over_ismail_rule"]) for r in sel], "x--", color=line.get_color(),
                label=f"{k}: clamped bar")
    ax.axhline(1.0, color="k", lw=1, label="Ismail's rule dt = h/c")
    ax.axhline(0.7226, color="0.5", lw=0.8, ls=":", label="0.7226 h/c (notes, mollifier)")
    ax.set_xlabel("kernel support / dx")
    ax.set_ylabel("leap-frog limit dt c / h (h: Ismail's kernel h)")
    ax.set_title("linear stability limit of the TL form vs Ismail's h/c")
    ax.legend(fontsize=7)
    ax = axes[1]
    energy = read(os.path.join(out, "energy.csv"))
    runs = []
    for r in energy:
        if r["run"] not in runs:
            runs.append(r["run"])
    for run in runs:
        sel = [r for r in energy if r["run"] == run]
        ax.semilogy([num(r["step"]) for r in sel], [num(r["energy_ratio"]) for r in sel], label=run)
    ax.set_xlabel("step")
    ax.set_ylabel("E / E0")
    ax.set_title("validation bar, modified mollifier support 5.5 dx: energy from a random start")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tl_time_step.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-time-step")
