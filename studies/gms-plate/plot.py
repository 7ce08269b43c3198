#!/usr/bin/env python3
"""Plots of the gms-plate study. Usage: plot.py RESULTS_DIR.

periods.png: period against tip speed per shear modulus, H = 2 and H = 1: sphstab runs, GMS Tables 1/2 (T_sph), the
thin-plate (7.1) and Timoshenko periods. convergence.png: period against dp (H = 2, mu = 0.22, V_f = 0.01) with the
linear (spectral) period and the extrapolated limit; tip histories; CPU seconds against the period error (Pareto).
root.png: snapshots of sigma_xx near the root for the mu = 0.6, V_f = 0.05 plate with eps = 0 and eps = 0.3, and the
most unstable mode of the frozen state at t = 140 (viscosity on) for both eps. frozen.png: every frozen spectrum's
most unstable mode.
"""
import glob
import math
import os
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import frozen_modes, num, plt, read, read_vtp  # noqa: E402

MU_COLOUR = {"0.22": "tab:blue", "0.3": "tab:orange", "0.6": "tab:green"}


def periods(out):
    rows = read(os.path.join(out, "periods.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, H in zip(axes, ("2", "1")):
        sub = [r for r in rows if r["H"] == H]
        for mu in MU_COLOUR:
            s = [r for r in sub if r["mu"] == mu]
            if not s:
                continue
            v = [num(r["tip_speed"]) for r in s]
            c = MU_COLOUR[mu]
            ax.plot(v, [num(r["period"]) for r in s], "o-", color=c, label=f"sphstab μ = {mu}")
            ax.plot(v, [num(r["paper_period"]) for r in s], "s--", mfc="none", color=c, label=f"GMS T_sph μ = {mu}")
            ax.axhline(num(s[0]["timoshenko_period"]), color=c, lw=0.8, ls=":")
            ax.axhline(num(s[0]["thin_period"]), color=c, lw=0.6, ls="-.")
        ax.set_xscale("log")
        ax.set_xlabel("tip speed V_f / c0")
        ax.set_ylabel("period (cm / c0)")
        ax.set_title(f"H = {H}, {sub[0]['across']} particles across (dotted: Timoshenko, dash-dot: thin plate)",
                     fontsize=9)
    axes[0].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "periods.png"), dpi=130)
    plt.close(fig)


def convergence(out):
    conv = read(os.path.join(out, "convergence.csv"))
    lin = {r["across"]: num(r["linear_period"]) for r in read(os.path.join(out, "linear.csv"))}
    ext = read(os.path.join(out, "extrapolation.csv"))
    fig, axes = plt.subplots(1, 3, figsize=(16, 4.2))
    ax = axes[0]
    dp = [num(r["dp"]) for r in conv]
    ax.plot(dp, [num(r["period"]) for r in conv], "o-", label="run, V_f = 0.01, ε = 0.3")
    bad = [r for r in conv if not num(r["max_bond_stretch"]) <= 1.5]  # plate_tables.hpp kRearrangedStretch
    if bad:
        ax.plot([num(r["dp"]) for r in bad], [num(r["period"]) for r in bad], "x", color="tab:red", ms=9,
                label="rearranged (bond > 1.5 dp): not in the fit")
    ld = [(num(r["dp"]), lin[r["across"]]) for r in conv if r["across"] in lin]
    if ld:
        ax.plot([a for a, _ in ld], [b for _, b in ld], "^", label="linear: spectrum of the initial state")
    for fit in ext:  # the headline fit (unrearranged runs) solid, the finest-three sensitivity dashed
        if not math.isnan(num(fit["extrapolated_period"])):
            head = fit["fit"] == "unrearranged"
            ax.axhline(num(fit["extrapolated_period"]), color="k", lw=0.8, ls="-" if head else "--",
                       label=f"extrapolated from {fit['from_across']} (order {num(fit['observed_order']):.2f})")
    ax.axhline(num(conv[0]["paper_period"]), color="tab:red", ls="--", lw=0.8, label="GMS T_sph 1671.5")
    ax.axhline(num(conv[0]["timoshenko_period"]), color="0.4", ls=":", lw=0.8, label="Timoshenko")
    ax.axhline(num(conv[0]["thin_period"]), color="0.4", ls="-.", lw=0.8, label="thin plate (7.1)")
    ax.set_xlabel("dp (cm)")
    ax.set_ylabel("period (cm / c0)")
    ax.set_title("H = 2, μ = 0.22: resolution", fontsize=9)
    ax.legend(fontsize=7)
    ax = axes[1]
    for r in conv:
        s = read(os.path.join(out, "series", r["tag"] + ".csv"))
        ax.plot([num(x["t"]) for x in s], [num(x["tip_displacement"]) for x in s], lw=0.9,
                label=f"{r['across']} across")
    ax.set_xlabel("t (cm / c0)")
    ax.set_ylabel("tip displacement (cm)")
    ax.legend(fontsize=7)
    # Cost against accuracy: the run thread's CPU seconds against the period error, per resolution.
    ax = axes[2]
    cpu = [num(r["cpu_seconds"]) for r in conv]
    refs = [("Timoshenko", num(conv[0]["timoshenko_period"]), "o-")]
    if ext and not math.isnan(num(ext[0]["extrapolated_period"])):
        refs.append(("the extrapolated period", num(ext[0]["extrapolated_period"]), "s--"))
    for name, ref, style in refs:
        ax.loglog(cpu, [abs(num(r["period"]) / ref - 1) for r in conv], style, label=f"vs {name}")
    for r, c in zip(conv, cpu):
        ax.annotate(f"{r['across']} across", (c, abs(num(r["period"]) / refs[0][1] - 1)), fontsize=7,
                    textcoords="offset points", xytext=(4, 4))
    t_end = max(num(x["t"]) for x in read(os.path.join(out, "series", conv[0]["tag"] + ".csv")))
    ax.set_xlabel(f"CPU seconds of the run ({t_end / num(conv[0]['thin_period']):.2g} thin-plate periods; "
                  "rearranged runs: crosses in the left panel)")
    ax.set_ylabel("|period error|")
    ax.set_title("cost against period error (Pareto)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "convergence.png"), dpi=130)
    plt.close(fig)


def root(out):
    runs = read(os.path.join(out, "root.csv"))
    fig, axes = plt.subplots(4, 2, figsize=(12, 9))
    for col, r in enumerate(runs):
        files = sorted(glob.glob(os.path.join(out, "vtk", r["tag"], r["tag"] + "_*.vtp")),
                       key=lambda f: int(f.rsplit("_", 1)[1].split(".")[0]))
        pvd = os.path.join(out, "vtk", r["tag"], r["tag"] + ".pvd")
        times = [float(ds.get("timestep")) for ds in ET.parse(pvd).getroot().iter("DataSet")]
        for row, k in enumerate([1, 3, 6]):
            if k >= len(files):
                continue
            px, py, f = read_vtp(files[k], ["sigma_xx"])
            keep = [i for i, x in enumerate(px) if x < 7]
            ax = axes[row][col]
            sc = ax.scatter([px[i] for i in keep], [py[i] for i in keep], c=[f["sigma_xx"][i] for i in keep],
                            s=4, cmap="coolwarm", vmin=-0.06, vmax=0.06)
            ax.set_aspect("equal")
            ax.set_title(f"ε = {r['eps']}, t = {times[k]:.0f}: σ_xx", fontsize=9)
        fig.colorbar(sc, ax=axes[2][col], orientation="horizontal", fraction=0.08)
    for col, e in enumerate(("0", "0.3")):
        path = os.path.join(out, f"frozen_mode_t140_eps{e}_visc.csv")
        if not os.path.exists(path):
            continue
        m = read(path)
        ax = axes[3][col]
        x = [num(r["x"]) for r in m]
        y = [num(r["y"]) for r in m]
        a = [math.hypot(num(r["vx"]), num(r["vy"])) for r in m]
        amax = max(a) or 1
        ax.scatter(x, y, c=[v / amax for v in a], s=3, cmap="viridis")
        ax.quiver(x, y, [num(r["vx"]) / amax for r in m], [num(r["vy"]) / amax for r in m], scale=25, width=0.002)
        ax.set_aspect("equal")
        ax.set_title(f"most unstable mode, frozen state at t = 140 (about T/8), viscosity on, ε = {e} (|v| coloured)", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "root.png"), dpi=120)
    plt.close(fig)


def main():
    out = sys.argv[1]
    periods(out)
    convergence(out)
    root(out)
    frozen_modes(out, "Cantilever plate, mu = 0.6, V_f = 0.05, eps = 0 run before the root break: linearised spectra")


if __name__ == "__main__":
    main()
