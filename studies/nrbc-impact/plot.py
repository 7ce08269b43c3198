#!/usr/bin/env python3
"""Plots of the surface-impact study (Powell 2012 ch. 2 §3.2(c), Figs. 2.20-2.23): v_y at the surface probes of the
reference and of the narrow truncations, the difference (the waves the absorbing sides send back) with lines at the
Rayleigh and P speeds, and the cost plot (error at the probes against CPU time) of absorbing and free truncations.
Usage: plot.py RESULTS_DIR (reads runs.csv, speeds.csv, series/<tag>.csv, summary.json)."""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402

PROBES = [f"s{k}" for k in range(1, 10)]
X = [0.1 * k + 0.01 for k in range(1, 10)]


def series(out, name):
    rows = read(os.path.join(out, "series", name + ".csv"))
    t = [num(r["t"]) for r in rows]
    return t, {p: [num(r["vy_" + p]) for r in rows] for p in PROBES}


def waterfall(out, summary):
    c_r, c_p = num(summary["c_r"]), num(summary["c_p"])
    t, ref = series(out, "reference_free_v0.1")
    runs = [("narrow_P_v0.1", "P"), ("narrow_M_v0.1", "M"), ("narrow_traction_v0.1", "viscous traction")]
    fig, axes = plt.subplots(1, 1 + len(runs), figsize=(20, 7), sharey=True)
    scale = 0.1 / 0.004  # cm per (cm/us): the incident surface wave ~0.004 cm/us spans 0.1 cm
    ax = axes[0]
    for p, x in zip(PROBES[3:], X[3:]):  # beyond the patch (|x| < 0.3)
        ax.plot(t, [x + scale * v for v in ref[p]], "k", lw=0.8)
    ax.plot([0, (0.91 - 0.3) / c_r], [0.3, 0.91], "r--", lw=0.8, label=f"c_r = {c_r:.4f} from the patch edge")
    ax.set_ylim(0.3, 1.05)
    decorate(ax, "t (us)", "probe x (cm); trace = x + v_y x 25", "reference: v_y at the surface probes")
    for ax, (tag, label) in zip(axes[1:], runs):
        t2, run = series(out, tag)
        for p, x in zip(PROBES[3:8], X[3:8]):
            d = [a - b for a, b in zip(run[p], ref[p])]
            ax.plot(t2, [x + 10 * scale * v for v in d], "b", lw=0.8)
        # The incident Rayleigh wave reaches the side x = 1 at about t1 and comes back at c_r (red) or c_p (grey).
        t1 = (1.0 - 0.3) / c_r
        ax.plot([t1, t1 + (1 - 0.41) / c_r], [1.0, 0.41], "r--", lw=0.8, label="back at c_r from the side")
        ax.plot([(1.0 - 0.3) / c_p, (1.0 - 0.3) / c_p + 0.59 / c_p], [1.0, 0.41], "0.5", ls=":", lw=0.8,
                label="back at c_p (P hitting the side)")
        decorate(ax, "t (us)", title=f"narrow, {label}: (v_y - v_y,ref) x 10", loc="lower left")
    save(fig, os.path.join(out, "surface_waves.png"))


def cost(out):
    rows = [r for r in read(os.path.join(out, "runs.csv")) if num(r["v_patch"]) == 0.1 and r["run"] != "reference"]
    fig, ax = plt.subplots(figsize=(8, 6))
    for kind, style in (("absorbing (P, M, traction)", "o"), ("free truncation", "s")):
        pts = [r for r in rows if (r["boundary"] == "free") == (kind == "free truncation")
               and "shallow" not in r["run"]]
        ax.loglog([num(r["cpu_seconds"]) for r in pts], [100 * max(num(r["error_surface"]), 1e-4) for r in pts],
                  style, label=kind)
        for r in pts:
            ax.annotate(f"{r['run']} {r['boundary']}", (num(r["cpu_seconds"]), 100 * max(num(r["error_surface"]), 1e-4)),
                        fontsize=7, xytext=(3, 3), textcoords="offset points")
    decorate(ax, "CPU seconds of the run (one thread)",
             "largest error at the surface probes s4-s9 (% of the probe's peak |v|)",
             "cost of a non-reflecting boundary: 2 cm deep truncations, t <= t_end")
    save(fig, os.path.join(out, "cost.png"))


def main(out):
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    waterfall(out, summary)
    cost(out)


if __name__ == "__main__":
    main(sys.argv[1])
