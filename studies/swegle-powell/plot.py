#!/usr/bin/env python3
"""Plots of the Swegle test in Powell's MCM configuration: for each h/dx, one log-KE-versus-time panel per formulation
with a curve per volume strain xi (Powell Fig. 4.2's layout and units: KE scaled so that the initial kinetic energy is
his 5e-23), ke_h<h>.png; and gamma_M against the measured rate for every case of the h sweep, growth.png.
Usage: plot.py RESULTS_DIR (reads ke.csv and runs.csv)."""
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, ordered, plt, read, xi_colour  # noqa: E402

POWELL_KE0 = 5e-23  # [Powell2012, Fig. 4.2 caption]: "The initial kinetic energy is in the graph's units 5e-23"


def main(out):
    ke, runs = read(os.path.join(out, "ke.csv")), read(os.path.join(out, "runs.csv"))
    main_runs = [r for r in runs if r["set"] == "main"]
    series = defaultdict(lambda: ([], []))
    for r in ke:
        if r["set"] == "main":
            s = series[(r["formulation"], num(r["h_over_dx"]), num(r["xi"]))]
            s[0].append(num(r["t"]))
            s[1].append(num(r["kinetic"]))
    forms = ordered(main_runs, "formulation")
    hs = sorted({num(r["h_over_dx"]) for r in main_runs})
    xis = sorted({num(r["xi"]) for r in main_runs})
    info = {(r["formulation"], num(r["h_over_dx"]), num(r["xi"])): r for r in main_runs}
    ncol = 3
    nrow = math.ceil(len(forms) / ncol)
    for h in hs:
        fig, axes = plt.subplots(nrow, ncol, figsize=(5.0 * ncol, 3.6 * nrow), sharex=True, sharey=True, squeeze=False)
        for k, form in enumerate(forms):
            ax = axes[k // ncol][k % ncol]
            for xi in xis:
                t, e = series.get((form, h, xi), ([], []))
                if not t:
                    continue
                r = info[(form, h, xi)]
                scale = POWELL_KE0 / e[0]
                label = f"xi = {xi:g} ({r['verdict']})"
                ax.semilogy(t, [v * scale for v in e], color=xi_colour(xi, xis), lw=1.2, label=label)
            ax.set_title(form)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7, loc="upper left")
        for k in range(len(forms), nrow * ncol):
            axes[k // ncol][k % ncol].axis("off")
        for ax in axes[-1]:
            ax.set_xlabel("t (us)")
        for row in axes:
            row[0].set_ylabel("kinetic energy (KE0 = 5e-23, Powell's units)")
        fig.suptitle(f"Swegle test, MCM configuration (leap-frog, XSPH 0.1, bulk viscosity 1.5/0.06), h = {h:g} dx; "
                     "legend: verdict class")
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"ke_h{h:g}.png"), dpi=100)
        plt.close(fig)

    fig, ax = plt.subplots(figsize=(6.5, 5))
    markers = "osD^v<>"
    for k, form in enumerate(forms):
        rows = [r for r in main_runs if r["formulation"] == form and num(r["gamma_map_class"]) > 0]
        ax.plot([num(r["gamma_map_class"]) for r in rows],
                [num(r["gamma_measured"]) if r["grew"] == "1" else 0.03 for r in rows], markers[k % len(markers)],
                color=f"C{k}", label=form, alpha=0.8)
    lim = [0.02, 40]
    ax.plot(lim, lim, "k--", lw=0.8, label="measured = map")
    floor = num(main_runs[0]["floor"])
    ax.axvline(floor, color="grey", lw=0.8, ls=":", label="detection floor")
    ax.set(xscale="log", yscale="log", xlim=lim, ylim=lim)
    ax.set_xlabel("gamma_M, leap-frog map with XSPH (1/us), excited mirror class")
    ax.set_ylabel("measured gamma (1/us); 0.03: stayed below the window")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "growth.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/swegle-powell")
