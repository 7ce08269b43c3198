#!/usr/bin/env python3
"""Plots of the Swegle study: one log-KE-versus-time panel per formulation with a curve per volume strain xi (like
Powell Fig. 4.2), measured versus predicted growth rates, the 1D version and the energy error of the conservative
form. Usage: plot.py RESULTS_DIR (reads ke.csv, runs.csv, onedim_ke.csv, onedim_runs.csv, energy_series.csv)."""
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, growth_panels, ke_panels, num, ordered, plt, read, save, xi_colour  # noqa: E402


def main(out):
    ke = read(os.path.join(out, "ke.csv"))
    runs = read(os.path.join(out, "runs.csv"))
    series, forms, xis, info = ke_panels(
        ke, runs, "Swegle test, 21 x 21 free particles, v0 = 1e-10 cm/us at the centre (x: run stopped, max |u| > 0.1 dx)",
        os.path.join(out, "ke_all.png"), mark_stops=True)
    # And one file per formulation.
    for form in forms:
        fig, ax = plt.subplots(figsize=(6.4, 4.2))
        for xi in xis:
            t, e = series.get((form, xi), ([], []))
            if t:
                ax.semilogy(t, e, color=xi_colour(xi, xis), lw=1.2, label=f"xi = {xi:g}")
        ax.grid(True, alpha=0.3)
        decorate(ax, "t (us)", "kinetic energy", f"Swegle test: {form}")
        save(fig, os.path.join(out, f"ke_{form}.png"), dpi=100)

    # Measured versus predicted growth rates.
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.6))
    markers = "osD^v<>ph*X"
    def measured(r):
        if r["run_verdict"] == "late growth":
            return num(r["gamma_late"]), True
        return num(r["gamma_measured"]), False

    def positive(x):
        return x if x > 1e-3 else math.nan

    for k, form in enumerate(forms):
        xs = [xi for xi in xis if (form, xi) in info]
        rows = [info[(form, xi)] for xi in xs]
        pred = [positive(num(r["gamma_predicted"])) for r in rows]
        meas = [measured(r) for r in rows]
        m = markers[k % len(markers)]
        full = [(p, g) for p, (g, late) in zip(pred, meas) if not late]
        late = [(p, g) for p, (g, late) in zip(pred, meas) if late]
        ax1.plot([p for p, _ in full], [g for _, g in full], m, color=f"C{k}", label=form, alpha=0.8)
        if late:
            ax1.plot([p for p, _ in late], [g for _, g in late], m, color=f"C{k}", mfc="none", alpha=0.8)
        ax2.plot(xs, pred, "-", color=f"C{k}", alpha=0.6)
        ax2.plot(xs, [positive(g) for g, _ in meas], m, color=f"C{k}", label=form)
    growth_panels(ax1, ax2, [1e-2, 30], "measured = predicted",
                  "linear theory gamma (1/us): excited mirror class; with XSPH the leap-frog map",
                  "measured gamma (1/us), fit of log KE (hollow: late-time slope)",
                  "gamma (1/us): lines linear theory, markers measured")
    save(fig, os.path.join(out, "growth_rates.png"))

    # 1D version.
    ke1 = read(os.path.join(out, "onedim_ke.csv"))
    s1 = defaultdict(lambda: ([], []))
    for r in ke1:
        key = (r["form"], num(r["T"]))
        s1[key][0].append(num(r["t"]))
        s1[key][1].append(num(r["kinetic"]))
    forms1 = ordered(ke1, "form")
    Ts = sorted({k[1] for k in s1})
    fig, axes = plt.subplots(1, len(forms1), figsize=(4.2 * len(forms1), 3.6), sharey=True, squeeze=False)
    for k, form in enumerate(forms1):
        ax = axes[0][k]
        for T in Ts:
            t, e = s1.get((form, T), ([], []))
            if t:
                ax.semilogy(t, e, color=xi_colour(1 + T, [1 + x for x in Ts]), lw=1.1, label=f"T = {T:+.2f}")
        ax.set_title(f"1D {form}")
        ax.set_xlabel("t (dx/c)")
        ax.grid(True, alpha=0.3)
    axes[0][0].set_ylabel("kinetic energy")
    axes[0][0].legend(fontsize=7)
    save(fig, os.path.join(out, "ke_1d.png"))

    # Energy error of the conservative form.
    es = read(os.path.join(out, "energy_series.csv"))
    by_dt = defaultdict(lambda: ([], []))
    for r in es:
        by_dt[num(r["dt"])][0].append(num(r["t"]))
        by_dt[num(r["dt"])][1].append(num(r["relative_energy_error"]))
    fig, ax = plt.subplots(figsize=(7, 4))
    for dt in sorted(by_dt, reverse=True):
        t, e = by_dt[dt]
        ax.plot(t, e, lw=0.8, label=f"dt = {dt:.4g} us")
    ax.set_xlabel("t (us)")
    ax.set_ylabel("(E - E0) / E0")
    ax.set_title("Conservative form, xi = 1, v0 = 0.01 cm/us: energy error of leap-frog")
    ax.grid(True, alpha=0.3)
    ax.legend()
    save(fig, os.path.join(out, "energy.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/swegle")
