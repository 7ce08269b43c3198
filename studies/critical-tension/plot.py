#!/usr/bin/env python3
"""Plots for the critical-tension study: python3 plot.py RESULTS_DIR (reads the CSVs written by main.cpp)."""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KERNELS = ["cubic", "quartic", "quintic", "wendland-c2", "wendland-c4", "gaussian"]
STYLE = {k: dict(color=c, marker=m) for k, c, m in zip(KERNELS, ["C0", "C1", "C2", "C3", "C4", "C5"], "osd^vx")}


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def col(rows, key, kernel=None, **match):
    out = []
    for r in rows:
        if kernel is not None and r["kernel"] != kernel:
            continue
        if any(abs(float(r[k]) - v) > 1e-9 for k, v in match.items()):
            continue
        out.append(float(r[key]))
    return out


def positive(xs, ys):
    pairs = [(x, y) for x, y in zip(xs, ys) if y > 0 and math.isfinite(y)]
    return [p[0] for p in pairs], [p[1] for p in pairs]


def main(out):
    sweep = read(f"{out}/fig32.csv")
    vn = read(f"{out}/versus_n.csv")

    fig, ax = plt.subplots(2, 2, figsize=(11, 8.5))
    for k in KERNELS:
        h = col(sweep, "h_over_dx", k)
        kw = dict(label=k, markersize=3, linewidth=1, **STYLE[k])
        ax[0, 0].plot(h, col(sweep, "t_first_minor", k), **kw)
        ax[0, 0].plot(h, col(sweep, "t_second_minor", k), color=STYLE[k]["color"], linestyle=":", linewidth=1)
        ax[0, 1].semilogy(*positive(h, col(sweep, "tcrit", k)), **kw)
        ax[1, 0].semilogy(*positive(h, col(sweep, "ratio_first_minor", k)), **kw)
        ti = [t if t > 1e-12 else float("nan") for t in col(sweep, "tcrit_infinite", k)]  # NaN breaks the line
        ax[0, 1].semilogy(h, ti, color=STYLE[k]["color"], linestyle="--", linewidth=1)
        n = sorted({int(r["N"]) for r in vn})
        t = [col(vn, "tcrit", k, h_over_dx=1.2, N=float(x))[0] for x in n]
        ax[1, 1].loglog(*positive(n, t), **kw)
    ns = [15, 960]
    ax[1, 1].loglog(ns, [2e-1 / x**2 for x in ns], "k--", linewidth=1, label="N$^{-2}$")
    ax[0, 0].set(xlabel="h/dx", ylabel="T", title="(a) first minor (3.42), solid; second minors (3.49), dotted")
    ax[0, 1].set(xlabel="h/dx", ylabel="T$_{crit}$",
                 title="(b) matrix T$_{crit}$, N = 30; dashed: infinite lattice")
    ax[1, 0].axhline(100, color="k", linewidth=0.8, linestyle="--")
    ax[1, 0].set(xlabel="h/dx", ylabel="(3.42) / T$_{crit}$", title="(c) overestimate of (3.42), N = 30")
    ax[1, 1].set(xlabel="N (free particles)", ylabel="T$_{crit}$", title="(d) T$_{crit}$ versus N at h/dx = 1.2")
    for a in ax.flat:
        a.grid(True, which="both", alpha=0.3)
    ax[0, 1].legend(fontsize=8)
    ax[1, 1].legend(fontsize=8)
    fig.suptitle("Critical tension of a 1D SPH bar, conservative form (Powell 2012, Fig. 3.2)")
    fig.tight_layout()
    fig.savefig(f"{out}/fig32.png", dpi=130)

    hs = sorted({float(r["h_over_dx"]) for r in vn})
    fig, ax = plt.subplots(1, len(hs), figsize=(4 * len(hs), 4), sharey=True)
    for a, hv in zip(ax, hs):
        for k in KERNELS:
            rows = [r for r in vn if r["kernel"] == k and abs(float(r["h_over_dx"]) - hv) < 1e-9]
            ok = [r for r in rows if r["status"] == "successful"]
            n = [int(r["N"]) for r in ok]
            t = [float(r["tcrit"]) for r in ok]
            a.loglog(*positive(n, t), label=k, markersize=3, linewidth=1, **STYLE[k])
            tinf = float(rows[0]["tcrit_infinite"])
            if tinf > 1e-12:
                a.axhline(tinf, color=STYLE[k]["color"], linestyle="--", linewidth=0.8)
        a.loglog(ns, [2e-1 / x**2 for x in ns], "k--", linewidth=1, label="N$^{-2}$")
        a.set(xlabel="N (free particles)", title=f"h/dx = {hv:g}")
        a.grid(True, which="both", alpha=0.3)
    ax[0].set_ylabel("T$_{crit}$ (dashed: infinite lattice)")
    ax[-1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{out}/tcrit_vs_n.png", dpi=130)

    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    for k in KERNELS:
        h = col(sweep, "h_over_dx", k)
        ax[0].plot(h, col(sweep, "l_hat_sawtooth", k), label=k, markersize=3, linewidth=1, **STYLE[k])
        ti = [t if t > 1e-12 else float("nan") for t in col(sweep, "tcrit_infinite", k)]
        if any(math.isfinite(t) for t in ti):  # NaN breaks the line between separate windows
            ax[1].semilogy(h, ti, label=k, markersize=3, linewidth=1, **STYLE[k])
    ax[0].axhline(0, color="k", linewidth=0.8)
    ax[0].set_yscale("symlog", linthresh=1e-3)
    ax[0].set(xlabel="h/dx", ylabel="L$^\\wedge$($\\pi$/dx)",
              title="sawtooth symbol: > 0 means T$_{crit,\\infty}$ = 0")
    ax[1].set(xlabel="h/dx", ylabel="T$_{crit,\\infty}$", title="infinite-lattice T$_{crit}$ where > 1e-12")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/infinite_limit.png", dpi=130)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/critical-tension")
