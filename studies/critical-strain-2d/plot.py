#!/usr/bin/env python3
"""Plots for the critical-strain-2d study: python3 plot.py RESULTS_DIR (reads the CSVs written by main.cpp)."""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KERNELS = ["cubic", "quintic", "wendland-c2", "wendland-c4"]
STYLE = {k: dict(color=c, marker=m) for k, c, m in zip(KERNELS, ["C0", "C1", "C2", "C3"], "osd^")}
LATTICES = ["square", "hex"]


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def fnum(s):
    return float(s)


def select(rows, **match):
    return [r for r in rows if all(r[k] == v for k, v in match.items())]


def magnitude(values):
    """|e|, NaN where infinite or zero (log axes)."""
    out = []
    for v in values:
        a = abs(v)
        out.append(a if (a > 0 and math.isfinite(a)) else float("nan"))
    return out


def sweep_figure(out, sweep):
    fig, ax = plt.subplots(2, 2, figsize=(12, 9), sharex=True)
    for i, lat in enumerate(LATTICES):
        for j, direction in enumerate(["tension", "compression"]):
            a = ax[i, j]
            for k in KERNELS:
                for kind, ls in [("isotropic", "-"), ("uniaxial", "--")]:
                    rows = select(sweep, lattice=lat, kernel=k, form="conservative", prestrain=kind, direction=direction)
                    h = [fnum(r["h_over_dx"]) for r in rows]
                    e = magnitude([fnum(r["ecrit"]) for r in rows])
                    a.semilogy(h, e, linestyle=ls, markersize=3, linewidth=1,
                               label=f"{k} {kind}" if (i == 0 and j == 0) else None, **STYLE[k])
                    # infinite-lattice limit where finite and > 1e-6
                    einf = magnitude([fnum(r["ecrit_infinite"]) for r in rows])
                    hi = [x for x, y in zip(h, einf) if y > 1e-6]
                    yi = [y for y in einf if y > 1e-6]
                    if kind == "isotropic" and hi:
                        a.semilogy(hi, yi, linestyle="none", marker="x", color=STYLE[k]["color"], markersize=6)
                # stable for every e of this sign: marker at the top
                rows = select(sweep, lattice=lat, kernel=k, form="conservative", prestrain="isotropic", direction=direction)
                hs = [fnum(r["h_over_dx"]) for r in rows if math.isinf(fnum(r["ecrit"]))]
                if hs:
                    a.plot(hs, [2e2] * len(hs), linestyle="none", marker="^", color=STYLE[k]["color"], markersize=5)
            a.set(title=f"({'abcd'[2 * i + j]}) {lat}, {direction}", xlabel="h/dx", ylabel="|e_crit|")
            a.grid(True, which="both", alpha=0.3)
    ax[0, 0].legend(fontsize=7, ncol=2)
    n = sweep[0]["n"]
    fig.suptitle(f"Critical pre-strain, conservative form, n = {n} per side with fixed layers\n"
                 "solid: isotropic, dashed: uniaxial; x: infinite-lattice limit (> 1e-6); ^ at top: stable for every e")
    fig.tight_layout()
    fig.savefig(f"{out}/ecrit_vs_h.png", dpi=120)
    plt.close(fig)


def versus_n_figure(out, vn):
    fig, ax = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    for j, direction in enumerate(["tension", "compression"]):
        a = ax[j]
        for lat, mk in [("square", "o"), ("hex", "s")]:
            for k, col in [("cubic", "C0"), ("wendland-c2", "C2")]:
                for h, ls in [("1", "-"), ("1.3", "--")]:
                    rows = select(vn, lattice=lat, kernel=k, h_over_dx=h, direction=direction)
                    n = [int(r["n"]) for r in rows]
                    e = magnitude([fnum(r["ecrit"]) for r in rows])
                    if all(math.isnan(x) for x in e):
                        continue
                    a.loglog(n, e, linestyle=ls, marker=mk, color=col, markersize=4, linewidth=1,
                             label=f"{lat} {k} h={h}")
                    einf = abs(fnum(rows[0]["ecrit_infinite"]))
                    if einf > 1e-6 and math.isfinite(einf):
                        a.axhline(einf, color=col, linestyle=":", linewidth=0.8)
        ns = [10, 160]
        a.loglog(ns, [0.1 / x**2 for x in ns], "k--", linewidth=1, label="n$^{-2}$")
        a.set(title=f"{direction}", xlabel="n (free particles per side)", ylabel="|e_crit|")
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle("e_crit versus lattice size, conservative isotropic (dotted: infinite-lattice limit)")
    fig.tight_layout()
    fig.savefig(f"{out}/ecrit_vs_n.png", dpi=120)
    plt.close(fig)


def modes_figure(out, sweep):
    fig, ax = plt.subplots(1, 2, figsize=(12, 5.5))
    for a, lat in zip(ax, LATTICES):
        for direction, mk in [("tension", "o"), ("compression", "^")]:
            rows = [r for r in select(sweep, lattice=lat, form="conservative", direction=direction)
                    if math.isfinite(fnum(r["ecrit"]))]
            kx = [fnum(r["mode_kx_over_pi"]) for r in rows]
            ky = [fnum(r["mode_ky_over_pi"]) for r in rows]
            h = [fnum(r["h_over_dx"]) for r in rows]
            sc = a.scatter(kx, ky, c=h, cmap="viridis", marker=mk, s=18, label=direction, vmin=1.0, vmax=2.5)
        if lat == "square":
            a.plot([0, 1, 1], [1, 1, 0], "k-", linewidth=0.8)
        else:
            s3 = math.sqrt(3)
            a.plot([4 / 3, 2 / 3, 0], [0, 2 / s3, 2 / s3], "k-", linewidth=0.8)
        a.set(title=f"{lat}: wavevector of the critical mode (n = {rows[0]['n'] if rows else '?'})",
              xlabel="kx dx/pi", ylabel="ky dx/pi")
        a.set_aspect("equal")
        a.legend(fontsize=8)
        fig.colorbar(sc, ax=a, label="h/dx")
    fig.tight_layout()
    fig.savefig(f"{out}/modes.png", dpi=120)
    plt.close(fig)


def gms_figure(out, gms):
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for a, lat in zip(ax, ["square", "face-centred"]):
        rows = select(gms, lattice=lat)
        h = [fnum(r["h_over_dp"]) for r in rows]
        a.plot(h, [fnum(r["B_x"]) for r in rows], "o-", label="B_x = l^xx(pi,0)")
        a.plot(h, [fnum(r["B_y"]) for r in rows], "s-", label="B_y = l^yy(pi,0)")
        a.plot(h, [fnum(r["A_x"]) for r in rows], "^-", label="A_x = -s_x(pi,0)")
        a.axhline(0, color="k", linewidth=0.8)
        a.set(title=f"GMS lattice sums, {lat}, cubic spline", xlabel="h/dp", ylabel="(units 1/dp^2, 1/dp)")
        a.set_ylim(-0.5, 4.2)
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(f"{out}/gms.png", dpi=120)
    plt.close(fig)


def main(out):
    sweep = read(f"{out}/sweep.csv")
    sweep_figure(out, sweep)
    versus_n_figure(out, read(f"{out}/versus_n.csv"))
    modes_figure(out, sweep)
    gms_figure(out, read(f"{out}/gms.csv"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/critical-strain-2d")
