#!/usr/bin/env python3
"""Plots of the 1D Neo-Hookean TL-SPH study (Ismail 2009 §5.3): the centre particle's Cauchy stress T11 during the
quasi-static stretch to 6 against the analytic curve and the reference table (nu = 0.3, 0.49), the spread of F over
the particles for ramps of 30-1000 transit times at nu = 0.49, and the material tangent dP/dF with the smallest
eigenvalue of the linearised TL Jacobian, which cross zero together.
Usage: plot.py RESULTS_DIR (reads table.csv, ramps.csv, history_nu*_ramp*.csv, hyperbolicity.csv, summary.json)."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read  # noqa: E402


def history(out, nu, ramp):
    return read(os.path.join(out, f"history_nu{nu}_ramp{ramp:g}.csv"))


def main(out):
    table = read(os.path.join(out, "table.csv"))
    ramps = read(os.path.join(out, "ramps.csv"))
    summary = json.load(open(os.path.join(out, "summary.json")))
    main_ramp = num(summary["ramp"])
    f_star = num(summary["f_tangent"])
    fig, axes = plt.subplots(2, 2, figsize=(14, 10))
    for ax, nu, colour in ((axes[0, 0], "0.3", "tab:blue"), (axes[0, 1], "0.49", "tab:red")):
        h = history(out, nu, main_ramp)
        lam = [num(r["lambda_imposed"]) for r in h]
        ax.plot(lam, [num(r["t11_analytic_over_mu"]) for r in h], color="k", lw=1.5, label="analytic (5.5), 1D strain")
        ax.plot(lam, [num(r["t11_centre_over_mu"]) for r in h], color=colour, lw=0.8,
                label=f"SPH centre particle, ramp {main_ramp:g} L/c_L")
        rows = [r for r in table if abs(num(r["nu"]) - float(nu)) < 1e-9]
        ax.plot([num(r["lambda1"]) for r in rows], [num(r["t11_thesis_over_mu"]) for r in rows], "ko", mfc="none",
                ms=9, label="reference table [Ismail2009, (5.5)]")
        ax.plot([num(r["lambda1"]) for r in rows], [num(r["t11_static_sph_over_mu"]) for r in rows], "x",
                color=colour, ms=8, label="SPH, homogeneous stretch (static)")
        if nu == "0.49":
            ax.axvline(f_star, color="0.5", ls=":", label=f"dP/dF = 0 (F = {f_star:.4f})")
            ax.set_ylim(0, 24)
        ax.set_xlabel("imposed stretch lambda_1")
        ax.set_ylabel("T11 / mu")
        ax.set_title(f"nu = {nu}: Cauchy stress T11 against stretch")
        ax.legend(fontsize=8, loc="lower right")
    ax = axes[1, 0]
    for r in ramps:
        if r["nu"] != "0.49":
            continue
        h = history(out, "0.49", num(r["ramp_transits"]))
        ax.semilogy([num(x["lambda_imposed"]) for x in h], [num(x["F_max"]) - num(x["F_min"]) for x in h],
                    lw=0.9, label=f"ramp {num(r['ramp_transits']):g} L/c_L (departure {num(r['departure_lambda']):.3f})")
    ax.axvline(f_star, color="0.5", ls=":", label="dP/dF = 0")
    ax.axhline(num(summary["spread"]), color="0.7", ls="--", lw=0.8, label="departure threshold")
    ax.set_xlabel("imposed stretch lambda_1")
    ax.set_ylabel("max F - min F over the free particles")
    ax.set_title("nu = 0.49: spread of the deformation gradient")
    ax.legend(fontsize=8, loc="upper left")
    hy = read(os.path.join(out, "hyperbolicity.csv"))
    F = [num(r["F_sph"]) for r in hy]
    ax = axes[1, 1]
    ax.plot(F, [num(r["tangent_over_modulus"]) for r in hy], "k-", label="material tangent dP/dF / (lambda + 2 mu)")
    ax.plot(F, [num(r["mu_min_over_mu_min_rest"]) for r in hy], "r--",
            label="smallest eigenvalue of the TL Jacobian / its value at rest")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.axvline(f_star, color="0.5", ls=":")
    ax.axvline(num(summary["f_tangent_upper"]), color="0.5", ls=":")
    ax.set_yscale("symlog", linthresh=1e-2)  # for dP/dF < 0 the smallest eigenvalue is dP/dF times cond(K)
    ax.set_xlabel("SPH deformation gradient F (homogeneous stretch)")
    ax.set_title(f"nu = 0.49: zero crossings at F = {f_star:.5f} (material), {num(summary['f_sph']):.5f} (SPH)")
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tl_neo_hookean_1d.png"), dpi=110)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-neo-hookean-1d")
