#!/usr/bin/env python3
"""Plots of the 1D validation-bar study (Ismail 2009 §4.6.3, §5.3.1): stress histories at the probes x = 0.05, 0.10,
0.15 m for each material against the exact linear d'Alembert solution, and the wave speed measured between the
first two probes against resolution. Usage: plot.py RESULTS_DIR (reads probes_*.csv, speeds.csv)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402

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
        decorate(ax, "t (us)", "T11 (kPa)", run, loc="lower left")
    ax = axes[1, 1]
    speeds = read(os.path.join(out, "speeds.csv"))
    for run in RUNS:
        rows = [r for r in speeds if r["run"] == run]
        ax.semilogx([num(r["dx"]) * 1e3 for r in rows],
                    [100 * (num(r["speed_sph_005_010"]) / num(r["c_model"]) - 1) for r in rows], "o-", label=run)
    ax.axhline(0, color="0.6", lw=0.6)
    decorate(ax, "dx (mm), h = 2.75 dx", "speed between 0.05 and 0.10 m vs model speed (%)",
             "arrival-time wave speed (c_b for 1D stress, c_L for 1D strain)")
    save(fig, os.path.join(out, "tl_bar_wave_1d.png"))
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
    ax.set_ylim(-450, 150)
    decorate(ax, "t (us)", "T11 at the fixed-end particle (kPa)", "fixed end, Hooke 1D stress, base resolution")
    ax = axes[1]
    for m in methods:
        rows = [r for r in speeds if r["run"].startswith("hooke") and r["fixed_end"] == m]
        ax.loglog([num(r["n"]) for r in rows], [num(r["max_error_kpa_x0.15"]) for r in rows], "o-", label=m)
    decorate(ax, "free particles n (h = 2.75 dx)", "max |T11 - exact| at the fixed-end particle (kPa)",
             "fixed-end error against resolution")
    save(fig, os.path.join(out, "tl_bar_wave_1d_fixed_end.png"))
    closure(out)


def closure(out):
    """The closed loop of each fixed end: the end-particle error against time with the modified closure's linear
    growth e^(rate t) through the last point, the modified closure's fastest mode near the wall, and W_CC's condition
    number and the modified closure's growth against the number of constrained ghost layers."""
    growth = read(os.path.join(out, "closure_growth.csv"))
    err = read(os.path.join(out, "end_error.csv"))
    fig, axes = plt.subplots(1, 3, figsize=(17, 5))
    ax = axes[0]
    colours = {"300": "tab:blue", "600": "tab:orange", "1200": "tab:green"}
    for n, colour in colours.items():
        for m, ls in [("modified", "-"), ("mirror", ":")]:
            rows = [r for r in err if r["fixed_end"] == m and r["n"] == n]
            t = [num(r["t_us"]) for r in rows]
            e = [max(num(r["error_kpa"]), 1e-6) for r in rows]
            ax.semilogy(t, e, ls, color=colour, lw=1, label=f"{m}, n = {n}")
            if m == "modified":
                rate = [num(g["leapfrog_rate"]) for g in growth if g["fixed_end"] == m and g["n"] == n][0]
                t0 = t[-1] - 15
                ax.semilogy([t0, t[-1]], [e[-1] * math.exp(-rate * 15e-6), e[-1]], "k--", lw=0.8)
    ax.set_ylim(1e-2, 1e5)
    decorate(ax, "t (us)", "|T11 - exact| at the fixed-end particle (kPa)",
             "end error; dashed: e^(rate t) of the linearised closed loop", title_size=10, legend=7)
    ax = axes[1]
    modes = read(os.path.join(out, "closure_mode.csv"))
    for n, colour in colours.items():
        rows = [r for r in modes if r["n"] == n]
        dx = 0.15 / int(n)
        xs = [(0.15 - num(r["x"])) / dx for r in rows]
        sh = [num(r["shape"]) for r in rows]
        sign = 1 if sh[-1] > 0 else -1
        ax.plot(xs, [sign * v for v in sh], "o-", ms=3, color=colour, label=f"n = {n}")
    ax.set_xlim(20, 0)
    decorate(ax, "distance from the fixed end (L - x) / dx", "mode (unit norm)",
             "modified closure: the growing mode (real mu < 0)", title_size=10)
    ax = axes[2]
    wcc = [r for r in read(os.path.join(out, "wcc_conditioning.csv")) if r["n"] == "300"]
    layers = [read(os.path.join(out, "closure_layers.csv"))][0]
    ax.semilogy([num(r["layers"]) for r in wcc], [num(r["cond2"]) for r in wcc], "o-", label="cond2(W_CC)")
    ax.semilogy([num(r["layers"]) for r in wcc], [num(r["closure_gain_inf"]) for r in wcc], "s-",
                label="gain ||W_CC^-1 W_CI||_inf")
    ax.semilogy([num(r["layers"]) for r in layers], [1e3 * num(r["gamma_dx_over_c"]) for r in layers], "^-",
                label="1000 gamma dx / c of the closed loop")
    ax.axvline(5, color="0.6", lw=0.6)
    decorate(ax, "constrained ghost layers (5: the study's, within the wall's support)",
             title="modified matrix against the constrained set (n = 300)", title_size=10)
    save(fig, os.path.join(out, "tl_bar_wave_1d_closure.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-bar-wave-1d")
