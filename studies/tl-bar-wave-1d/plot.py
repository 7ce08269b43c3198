#!/usr/bin/env python3
"""Plots of the 1D validation-bar study (Ismail 2009 §4.6.3, §5.3.1): stress histories at the probes x = 0.05, 0.10,
0.15 m for each material against the exact linear d'Alembert solution, and the wave speed measured between the
first two probes against resolution. Usage: plot.py RESULTS_DIR (reads probes_*.csv, speeds.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read  # noqa: E402

RUNS = ["hooke-1d-stress", "neo-hookean-1d-strain", "neo-hookean-1d-stress"]
PROBES = ["0.05", "0.1", "0.15"]


def main(out):
    fig, axes = plt.subplots(2, 2, figsize=(14, 9))
    for ax, run in zip(axes.flat, RUNS):
        rows = read(os.path.join(out, f"probes_{run}.csv"))
        t = [num(r["t_us"]) for r in rows]
        for probe, colour in zip(PROBES, ["tab:blue", "tab:orange", "tab:green"]):
            ax.plot(t, [num(r[f"sigma_exact_kpa_x{probe}"]) for r in rows], color=colour, lw=0.8, ls="--")
            ax.plot(t, [num(r[f"sigma_sph_kpa_x{probe}"]) for r in rows], color=colour, lw=1.2,
                    label=f"x = {probe} m (SPH solid, exact dashed)")
        ax.set_xlabel("t (us)")
        ax.set_ylabel("T11 (kPa)")
        ax.set_title(run)
        ax.legend(fontsize=8, loc="lower left")
    ax = axes[1, 1]
    speeds = read(os.path.join(out, "speeds.csv"))
    for run in RUNS:
        rows = [r for r in speeds if r["run"] == run]
        ax.semilogx([num(r["dx"]) * 1e3 for r in rows],
                    [100 * (num(r["speed_sph_005_010"]) / num(r["c_model"]) - 1) for r in rows], "o-", label=run)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_xlabel("dx (mm), h = 2.75 dx")
    ax.set_ylabel("speed between 0.05 and 0.10 m vs model speed (%)")
    ax.set_title("arrival-time wave speed (c_b for 1D stress, c_L for 1D strain)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tl_bar_wave_1d.png"), dpi=110)
    fixed_end(out, speeds)


def fixed_end(out, speeds):
    """The x = 0.15 m probe (fixed-end particle) for each fixed-end method, and its largest error against n."""
    methods = ["clamped", "mirror", "eta", "modified"]
    fig, axes = plt.subplots(1, 2, figsize=(14, 5))
    ax = axes[0]
    for m in methods:
        rows = read(os.path.join(out, "probes_hooke-1d-stress" + ("" if m == "clamped" else f"-{m}") + ".csv"))
        t = [num(r["t_us"]) for r in rows]
        if m == "clamped":
            ax.plot(t, [num(r["sigma_exact_kpa_x0.15"]) for r in rows], "k--", lw=0.8, label="exact")
        ax.plot(t, [num(r["sigma_sph_kpa_x0.15"]) for r in rows], lw=1.1, label=m)
    ax.set_xlabel("t (us)")
    ax.set_ylabel("T11 at the fixed-end particle (kPa)")
    ax.set_ylim(-450, 150)
    ax.set_title("fixed end, Hooke 1D stress, base resolution")
    ax.legend(fontsize=8)
    ax = axes[1]
    for m in methods:
        rows = [r for r in speeds if r["run"].startswith("hooke") and r["fixed_end"] == m]
        ax.loglog([num(r["n"]) for r in rows], [num(r["max_error_kpa_x0.15"]) for r in rows], "o-", label=m)
    ax.set_xlabel("free particles n (h = 2.75 dx)")
    ax.set_ylabel("max |T11 - exact| at the fixed-end particle (kPa)")
    ax.set_title("fixed-end error against resolution")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tl_bar_wave_1d_fixed_end.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-bar-wave-1d")
