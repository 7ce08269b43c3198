#!/usr/bin/env python3
"""Plots of the TL-vs-UL pairing study (Ismail 2009 §4.7): the middle 7 particles' displacements (relative to the
pre-stretched equilibrium) for TL, UL and the rate-form runs, the pairing measure min gap / spacing over time and the
rate form's linear growth rate over the tension (1D); the 2D block's bond-ratio histories and particle snapshots (2D,
when pairing_2d.csv exists).
Usage: plot.py RESULTS_DIR (reads middle7.csv, pairing.csv, critical.csv, middle7_rate_form.csv, pairing_rate_form.csv,
growth_rate_form.csv, pairing_2d.csv, snapshots_2d.csv)."""
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, ordered, plt, read, save  # noqa: E402


def middle7_panel(ax, rows, run, title):
    sel = [r for r in rows if r["run"] == run]
    t = [num(r["t"]) for r in sel]
    for k in range(-3, 4):
        ax.plot(t, [num(r[f"d{k}_over_dx"]) for r in sel], label=f"particle {k:+d}")
    decorate(ax, "t (dx / c)", "u - u_eq (spacing)", title, legend=7)


def main(out):
    rate_form = os.path.exists(os.path.join(out, "pairing_rate_form.csv"))
    fig, axes = plt.subplots(2, 3, figsize=(17, 9.5)) if rate_form else plt.subplots(1, 3, figsize=(16, 5))
    axes = list(axes.flat)
    middle = read(os.path.join(out, "middle7.csv"))
    for ax, run in zip(axes[:2], ["TL", "UL"]):
        middle7_panel(ax, middle, run, f"{run}: middle 7 particles")
    pairing = read(os.path.join(out, "pairing.csv"))
    runs = ["TL", "UL"]
    if rate_form:
        middle_rf = read(os.path.join(out, "middle7_rate_form.csv"))
        middle7_panel(axes[2], middle_rf, "RF", "rate form (basic SPH): middle 7 particles")
        middle7_panel(axes[3], middle_rf, "RF-AS", "rate form + artificial stress 0.3: middle 7 particles")
        pairing += read(os.path.join(out, "pairing_rate_form.csv"))
        runs += ["RF", "RF-AS"]
    ax = axes[4] if rate_form else axes[2]
    styles = {"TL": "-", "UL": "-", "RF": "--", "RF-AS": ":"}
    for run in runs:
        rows = [r for r in pairing if r["run"] == run]
        ax.plot([num(r["t"]) for r in rows], [num(r["min_gap_over_spacing"]) for r in rows], styles[run],
                label=f"{run} min gap")
    ax.axhline(0.5, color="0.6", lw=0.8, ls=":", label="pairing threshold 0.5")
    decorate(ax, "t (dx / c)", "min (x_{i+1} - x_i) / spacing", "pairing measure")
    if rate_form:  # linear growth rate of the rate form over the tension (the runs' stretched states)
        ax = axes[5]
        growth = read(os.path.join(out, "growth_rate_form.csv"))
        for run, label in [("RF", "basic SPH"), ("RF-AS", "artificial stress 0.3")]:
            sel = [r for r in growth if r["run"] == run and r["family"] == "stretched"]
            ax.semilogx([num(r["sigma0_over_m"]) for r in sel], [num(r["growth_rate"]) for r in sel], styles[run],
                        marker=".", ms=3, label=label)
        tcrit = [num(r["t_crit"]) for r in read(os.path.join(out, "critical.csv"))
                 if r["form"] == "UL plus" and r["route"] == "eigen"]
        if tcrit:
            ax.axvline(tcrit[0], color="0.5", lw=0.8, ls="--", label="T_crit (UL plus)")
        with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
            tension = num(json.load(f).get("tension", "nan"))
        ax.axvline(tension, color="tab:red", lw=0.8, ls=":", label=f"run tension {tension:g}")
        decorate(ax, "sigma0 / M (= T)", "growth rate max Re lambda (c / dx)", "rate form: linear growth rate at rest")
    save(fig, os.path.join(out, "tl_ul_pairing.png"))


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
    save(fig, os.path.join(out, "tl_ul_pairing_2d.png"))

    snaps = read(os.path.join(out, "snapshots_2d.csv"))
    labels = [lab for lab in ordered(snaps, "snapshot") if lab != "end"] + ["end"]
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
