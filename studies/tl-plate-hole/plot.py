#!/usr/bin/env python3
"""Plots of the plate-with-a-hole study (issue 11, Ismail 2009 §5.4.4): particles coloured by the stress, the
sigma_xx profile along theta = 90 deg and the hoop stress around the hole against Kirsch, and the resolution study.
Usage: plot.py RESULTS_DIR (reads cases.csv, particles_<tag>.csv, profile_<tag>.csv, ring_<tag>.csv)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402


def kirsch_xx(y):
    return 1 + 0.5 / y**2 + 1.5 / y**4


def scatter(ax, out, tag, column, title, label):
    rows = read(os.path.join(out, f"particles_{tag}.csv"))
    x = [num(r["x"]) for r in rows]
    y = [num(r["y"]) for r in rows]
    c = [num(r[column]) for r in rows]
    n = len(rows)
    sc = ax.scatter(x, y, c=c, s=max(1, 120000 / n), cmap="viridis", marker="s", linewidths=0)
    t = [i * math.pi / 200 for i in range(101)]
    ax.plot([math.cos(a) for a in t], [math.sin(a) for a in t], "w-", lw=0.8)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x / a")
    ax.set_ylabel("y / a")
    plt.colorbar(sc, ax=ax, label=label)


def main(out):
    cases = read(os.path.join(out, "cases.csv"))
    lin = [r for r in cases if r["tag"].startswith("linear") and num(r["w_over_a"]) == 5 and "lumped" not in r["tag"]]
    finest = lin[-1]["tag"]
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5))
    scatter(axes[0], out, finest, "sigma_xx_over_S", f"{finest}: sigma_xx / S (Hooke, S/E = 1e-3)", "sigma_xx / S")
    ismail = [r for r in cases if r["tag"].startswith("ismail-nh")]
    if ismail:
        tag = ismail[-1]["tag"]
        scatter(axes[1], out, tag, "principal_over_S", f"{tag}: max principal Cauchy stress / S (S = 5 MPa)",
                "sigma_1 / S")
    save(fig, os.path.join(out, "particles.png"))

    fig, axes = plt.subplots(1, 3, figsize=(17, 4.8))
    ax = axes[0]
    ys = [1 + 4 * i / 400 for i in range(401)]
    ax.plot(ys, [kirsch_xx(y) for y in ys], "k-", lw=1.5, label="Kirsch (infinite plate), x = 0")
    for r in lin + [c for c in cases if c["tag"].startswith("linear") and c not in lin]:
        p = read(os.path.join(out, f"profile_{r['tag']}.csv"))
        ax.plot([num(q["y_over_a"]) for q in p], [num(q["sigma_xx_over_S"]) for q in p], ".-", ms=4, lw=0.8,
                label=f"SPH a/dx = {r['a_over_dx']}, W/a = {r['w_over_a']}" + (", lumped load" if "lumped" in r["tag"] else ""))
    ax.set_xlim(1, 5)
    decorate(ax, "y / a", "sigma_xx / S", "profile along theta = 90 deg", legend=7)
    ax = axes[1]
    th = [90 * i / 200 for i in range(201)]
    ax.plot(th, [1 - 2 * math.cos(2 * math.radians(t)) for t in th], "k-", lw=1.5, label="Kirsch at r = a")
    for r in lin:
        p = read(os.path.join(out, f"ring_{r['tag']}.csv"))
        p.sort(key=lambda q: num(q["theta_deg"]))
        ax.plot([num(q["theta_deg"]) for q in p], [num(q["hoop_over_S"]) for q in p], ".", ms=5,
                label=f"SPH a/dx = {r['a_over_dx']} (a <= r < a + dx)")
    decorate(ax, "theta (deg, from the load axis)", "hoop stress / S", "hoop stress of the first ring of particles",
             legend=7)
    ax = axes[2]
    dx = [1 / num(r["a_over_dx"]) for r in lin]
    hw = num(lin[0]["heywood_over_S"])
    ax.loglog(dx, [abs(num(r["edge_over_S"]) - hw) for r in lin], "o-", label="|edge value - Heywood (W/a = 5)|")
    ax.loglog(dx, [abs(num(r["peak_hoop_over_S"]) - num(r["kirsch_at_peak"])) for r in lin], "s-",
              label="|peak particle - Kirsch at that particle|")
    ax.loglog(dx, [abs(num(lin[0]["edge_over_S"]) - hw) * (d / dx[0]) for d in dx], "k:", label="slope 1")
    decorate(ax, "dx / a", "error / S", "resolution", legend=7)
    save(fig, os.path.join(out, "profiles.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-plate-hole")
