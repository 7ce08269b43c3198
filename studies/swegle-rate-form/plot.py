#!/usr/bin/env python3
"""Plots of the rate-form Swegle study: one log-KE-versus-time panel per formulation with a curve per volume strain
xi (Powell Fig. 4.2 layout), and measured versus full-state linear growth rates. Usage: plot.py RESULTS_DIR (reads
ke.csv and runs.csv)."""
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read, xi_colour  # noqa: E402


def main(out):
    ke, runs = read(os.path.join(out, "ke.csv")), read(os.path.join(out, "runs.csv"))
    series = defaultdict(lambda: ([], []))
    for r in ke:
        s = series[(r["formulation"], num(r["xi"]))]
        s[0].append(num(r["t"]))
        s[1].append(num(r["kinetic"]))
    forms = list(dict.fromkeys(r["formulation"] for r in runs))
    xis = sorted({num(r["xi"]) for r in runs})
    info = {(r["formulation"], num(r["xi"])): r for r in runs}

    ncol = 3
    nrow = math.ceil(len(forms) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.0 * ncol, 3.6 * nrow), sharex=True, sharey=True, squeeze=False)
    for k, form in enumerate(forms):
        ax = axes[k // ncol][k % ncol]
        for xi in xis:
            t, e = series.get((form, xi), ([], []))
            if not t:
                continue
            r = info[(form, xi)]
            label = f"xi = {xi:g}" + ("" if r["status"] == "completed" else f" (stop {num(r['t_stop']):.3g})")
            ax.semilogy(t, e, color=xi_colour(xi, xis), lw=1.2, label=label)
        ax.set_title(form)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    for k in range(len(forms), nrow * ncol):
        axes[k // ncol][k % ncol].axis("off")
    for ax in axes[-1]:
        ax.set_xlabel("t (us)")
    for row in axes:
        row[0].set_ylabel("kinetic energy (g cm^2/us^2 per cm)")
    fig.suptitle("Swegle test, rate-form scheme (continuity, EOS, Jaumann rate); runs stop at KE = 1e10 KE0")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "ke_all.png"), dpi=110)
    plt.close(fig)

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.6))
    markers = "osD^v<>"
    for k, form in enumerate(forms):
        rows = [info[(form, xi)] for xi in xis if (form, xi) in info]
        lin = [num(r["gamma_linear_class"]) for r in rows]
        meas = [num(r["gamma_measured"]) for r in rows]
        m = markers[k % len(markers)]
        ax1.plot(lin, meas, m, color=f"C{k}", label=form, alpha=0.8)
        ax2.plot(xis, [g if g > 1e-3 else math.nan for g in lin], "-", color=f"C{k}", alpha=0.6)
        ax2.plot(xis, meas, m, color=f"C{k}", label=form)
    lim = [1e-1, 30]
    ax1.plot(lim, lim, "k--", lw=0.8, label="measured = linear")
    ax1.set(xscale="log", yscale="log", xlim=lim, ylim=lim)
    ax1.set_xlabel("full-state linear gamma (1/us), excited mirror class")
    ax1.set_ylabel("measured gamma (1/us), fit of log KE / 2")
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=7)
    ax2.set_yscale("log")
    ax2.set_xlabel("xi = V/V0")
    ax2.set_ylabel("gamma (1/us): lines linear, markers measured")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "growth.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/swegle-rate-form")
