#!/usr/bin/env python3
"""Plots of the time-step study (Ismail 2009 (4.47)): the linear leap-frog limit in units of Ismail's h/c against
support/dx for each kernel (symbol and clamped bar), and the energy ratio of the validation-bar runs against the step.
Usage: plot.py RESULTS_DIR (reads limits.csv, energy.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, ordered, plt, read, save  # noqa: E402


def main(out):
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.5))
    ax = axes[0]
    rows = read(os.path.join(out, "limits.csv"))
    for k in ordered(rows, "kernel"):
        sel = [r for r in rows if r["kernel"] == k]
        s = [num(r["support_over_dx"]) for r in sel]
        line, = ax.plot(s, [num(r["dt_symbol_over_ismail_rule"]) for r in sel], "o-", label=f"{k}: periodic symbol")
        ax.plot(s, [num(r["dt_bar_over_ismail_rule"]) for r in sel], "x--", color=line.get_color(),
                label=f"{k}: clamped bar")
    ax.axhline(1.0, color="k", lw=1, label="Ismail's rule dt = h/c")
    ax.axhline(0.7226, color="0.5", lw=0.8, ls=":", label="0.7226 h/c (notes, mollifier)")
    decorate(ax, "kernel support / dx", "leap-frog limit dt c / h (h: Ismail's kernel h)",
             "linear stability limit of the TL form vs Ismail's h/c", legend=7)
    ax = axes[1]
    energy = read(os.path.join(out, "energy.csv"))
    for run in ordered(energy, "run"):
        sel = [r for r in energy if r["run"] == run]
        ax.semilogy([num(r["step"]) for r in sel], [num(r["energy_ratio"]) for r in sel], label=run)
    decorate(ax, "step", "E / E0", "validation bar, modified mollifier support 5.5 dx: energy from a random start")
    save(fig, os.path.join(out, "tl_time_step.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-time-step")
