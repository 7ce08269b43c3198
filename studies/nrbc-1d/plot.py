#!/usr/bin/env python3
"""Plots of the 1D non-reflecting-boundary study (Powell 2012 ch. 2 §3.1): velocity of particle 80 against time for
every formulation and absorbing-layer count (Powell Figs. 2.8-2.11), the h-study (Fig. 2.12) and the largest stable
CFL number of each configuration. Usage: plot.py RESULTS_DIR (reads table.csv, series/*.csv, h_study.csv,
dt_limit.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402

FORMS = ["SPH", "XSPH", "NCSPH", "NCXSPH"]


def tag(row):
    kind = ("upwind" if row["upwind"] == "1" else "layers") + row["layers"]
    return (f"{row['form']}_n{row['particles']}_{kind}_{row['timing']}_h{num(row['h_over_dx']):g}"
            f"_cfl{num(row['cfl']):g}" + ("" if row["viscosity"] == "1" else "_novisc")
            + ("" if row["mirror"] == "1" else "_free"))


def profiles(out, rows, timing):
    fig, axes = plt.subplots(4, 1, figsize=(9, 12), sharex=True)
    for ax, form in zip(axes, FORMS):
        mine = [r for r in rows if r["form"] == form and r["viscosity"] == "1" and r["mirror"] == "1"
                and (r["timing"] == timing or r["particles"] == "800")]
        for r in mine:
            s = read(os.path.join(out, "series", tag(r) + ".csv"))
            t, v = [num(x["t"]) for x in s], [num(x["v80"]) for x in s]
            if r["particles"] == "800":
                label, style = "reference (800 particles)", dict(color="k", ls="--", lw=1.2, zorder=5)
            else:
                kind = "upwind " if r["upwind"] == "1" else ""
                label = f"{kind}{r['layers']} absorbing" + ("" if r["status"] == "completed" else " (unstable)")
                style = dict(lw=0.9)
            ax.plot(t, v, label=label, **style)
        ax.plot(t, [num(x["exact"]) for x in s], color="0.6", lw=0.6, label="exact (2.68)")
        ax.set_ylim(-0.025, 0.01)
        ax.set_ylabel("v at particle 80 (cm/us)")
        ax.set_title(f"{form}, {timing}-step boundary acceleration")
        ax.legend(fontsize=7, ncol=3, loc="lower right")
    axes[-1].set_xlabel("t (us)")
    save(fig, os.path.join(out, f"profiles_{timing}.png"))


def h_study(out):
    rows = read(os.path.join(out, "h_study.csv"))
    h = [num(r["h_over_dx"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4))
    for key, label, m in (("reference_error", "reference (800)", "o"), ("half_error", "NRBC, half-step (Powell)", "s"),
                          ("whole_error", "NRBC, whole-step", "^")):
        ax.semilogy(h, [100 * num(r[key]) for r in rows], marker=m, label=label)
    decorate(ax, "h / dx", "mean relative error x 100, 3 < t < 10 us",
             "NCXSPH, floor(2h/dx) + 1 absorbing particles (Powell Fig. 2.12)")
    save(fig, os.path.join(out, "h_study.png"))


def dt_limit(out):
    rows = read(os.path.join(out, "dt_limit.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, timing in zip(axes, ("half", "whole")):
        for k, form in enumerate(FORMS):
            mine = [r for r in rows if r["form"] == form and r["timing"] == timing]
            labels = ["ref" if r["particles"] == "800" else ("up8" if r["upwind"] == "1" else r["layers"]) for r in mine]
            xs = [i + 0.2 * (k - 1.5) for i in range(len(mine))]
            ax.bar(xs, [num(r["max_stable_cfl"]) for r in mine], width=0.2, label=form)
            ax.plot(xs, [num(r["linear_max_cfl_damped"]) for r in mine], "k_", ms=9,
                    label="linearised step (damped)" if k == 0 else None)
        ax.set_xticks(range(len(labels)), labels)
        ax.set_xlabel("absorbing particles")
        ax.set_title(f"{timing}-step boundary acceleration")
        ax.set_yscale("log")
    axes[0].set_ylabel("largest stable c dt / dx (runs to 20 us)")
    axes[0].legend(fontsize=8)
    save(fig, os.path.join(out, "dt_limit.png"))


def main(out):
    rows = read(os.path.join(out, "table.csv"))
    for timing in ("half", "whole"):
        profiles(out, rows, timing)
    h_study(out)
    dt_limit(out)


if __name__ == "__main__":
    main(sys.argv[1])
