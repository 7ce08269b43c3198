#!/usr/bin/env python3
"""Plots for the mean-polishing study: python3 plot.py RESULTS_DIR (reads tcrit.csv, momentum.csv, locality.csv).

tcrit_vs_h.png        T_crit (tension) vs h/dx, N = 30: rows = forms, columns = kernels, one line per correction;
                      "no critical load" (T_crit = inf) is drawn on the band at the top.
compression_vs_h.png  the same for the critical compression |T_crit^-|.
momentum_locality.png total force on a displaced periodic lattice, and the fill of Ghat and of the Jacobian.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import plt, read, save  # noqa: E402

KERNELS = ["cubic", "wendland-c2", "quintic"]
FORMS = [("uncorrected", "divergence"), ("plus", "divergence"), ("minus", "divergence"), ("conservative", "strain")]
CORRECTIONS = ["none", "minus", "shepard", "column-shepard", "ncsph", "local-polish", "local-polish+fig4.3",
               "local-polish+eq4.18", "mean-polish", "shepard-column-polish"]
STYLE = {c: dict(color=f"C{i}", marker="os^vDx+*<>"[i]) for i, c in enumerate(CORRECTIONS)}


def series(rows, n, kernel, correction, form, target, direction):
    """(h, |T_crit|) of the first criterion of each case, sorted by h."""
    seen, out = set(), []
    for r in rows:
        if int(r["N"]) != n or r["kernel"] != kernel or r["correction"] != correction or r["form"] != form:
            continue
        if r["direction"] != direction or r["corrected_operator"] not in (target, "-"):
            continue
        h = float(r["h_over_dx"])
        if h in seen:
            continue
        seen.add(h)
        out.append((h, abs(float(r["tcrit"]))))
    return sorted(out)


def tcrit_figure(rows, n, direction, path, ylabel):
    fig, axes = plt.subplots(len(FORMS), len(KERNELS), figsize=(13, 13), sharex=True, sharey=True)
    ceiling = 1e3  # T_crit = inf drawn here
    for i, (form, target) in enumerate(FORMS):
        for j, kernel in enumerate(KERNELS):
            ax = axes[i][j]
            for c in CORRECTIONS:
                pts = series(rows, n, kernel, c, form, target, direction)
                if not pts:
                    continue
                hs = [p[0] for p in pts]
                ts = [ceiling if math.isinf(p[1]) else max(p[1], 1e-8) for p in pts]
                ax.plot(hs, ts, lw=1, ms=4, label=c, **STYLE[c])
            ax.set_yscale("log")
            ax.set_ylim(1e-6, 3 * ceiling)
            ax.axhspan(0.5 * ceiling, 3 * ceiling, color="0.9", zorder=0)
            ax.text(1.02, ceiling, "none (inf)", fontsize=7, va="center")
            if i == 0:
                ax.set_title(kernel)
            if j == 0:
                ax.set_ylabel(f"{form} ({target})\n{ylabel}")
            if i == len(FORMS) - 1:
                ax.set_xlabel("h / dx")
            ax.grid(alpha=0.3)
    axes[0][len(KERNELS) - 1].legend(fontsize=7, loc="lower right")
    fig.suptitle(f"Critical {'tension' if direction == 'tension' else 'compression'} of the corrected 1D forms, "
                 f"N = {n}, fixed layers 3 supports (top band: no critical load)")
    save(fig, path, dpi=130, announce=True)


def momentum_locality(out):
    mom = read(f"{out}/momentum.csv")
    loc = read(f"{out}/locality.csv")
    fig, (a, b) = plt.subplots(1, 2, figsize=(14, 5))
    floor = 1e-17
    width = 0.2
    for k, (form, target) in enumerate(FORMS):
        vals = []
        for c in CORRECTIONS:
            t = "-" if c == "none" else target
            v = [float(r["total_force_relative"]) for r in mom
                 if r["correction"] == c and r["form"] == form and r["corrected_operator"] == t]
            vals.append(max(floor, max(v)) if v else floor)
        a.bar([i + (k - 1.5) * width for i in range(len(CORRECTIONS))], vals, width, label=f"{form} ({target})")
    a.set_yscale("log")
    a.axhline(1e-15, color="grey", ls="--", lw=0.8)
    a.set_xticks(range(len(CORRECTIONS)))
    a.set_xticklabels(CORRECTIONS, rotation=30, ha="right", fontsize=8)
    a.set_ylabel(r"$|\sum_i V_i a_i| / \sum_i V_i |a_i|$")
    a.set_title("Momentum: total force, periodic displaced lattice (dashed: round-off)")
    a.legend(fontsize=7)
    names = [r["correction"] for r in loc]
    x = range(len(names))
    b.bar([i - 0.3 for i in x], [int(r["Ghat_nonzero"]) for r in loc], 0.2, label="Ghat non-zeros")
    b.bar([i - 0.1 for i in x], [int(r["jacobian_nonzero_plus"]) for r in loc], 0.2, label="Jacobian non-zeros (plus)")
    b.bar([i + 0.1 for i in x], [int(r["jacobian_nonzero_conservative"]) for r in loc], 0.2,
          label="Jacobian non-zeros (conservative)")
    b.axhline(int(loc[0]["G_nonzero"]), color="k", ls=":", lw=1, label="G non-zeros")
    b.set_yscale("log")
    b.set_xticks(list(x))
    b.set_xticklabels(names, rotation=30, ha="right", fontsize=8)
    b.set_title("Locality (N = 30, cubic, h = 1.3 dx)")
    b.legend(fontsize=7)
    save(fig, f"{out}/momentum_locality.png", dpi=130, announce=True)


def main(out):
    rows = read(f"{out}/tcrit.csv")
    n = min(int(r["N"]) for r in rows)
    tcrit_figure(rows, n, "tension", f"{out}/tcrit_vs_h.png", "T_crit")
    tcrit_figure(rows, n, "compression", f"{out}/compression_vs_h.png", "|T_crit^-|")
    momentum_locality(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/mean-polishing")
