#!/usr/bin/env python3
"""Plot of the rate-form critical-stress study: critical tension sigma0/M versus h/dx per kernel (1D bar), the
rate-form formulations beside the §3.3 plus and conservative forms (Powell Fig. 3.2 layout). Usage: plot.py
RESULTS_DIR (reads bar_1d.csv, writes critical_stress_1d.png)."""
import math
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read  # noqa: E402

STYLE = {"sph": ("C0", "-"), "sph-as": ("C1", "-"), "ncsph-anti": ("C2", "-"), "ssph": ("C3", "-"),
         "ssph-printed": ("C4", ":")}


def main(out):
    rows = [r for r in read(os.path.join(out, "bar_1d.csv")) if r["direction"] == "tension"]
    kernels = list(dict.fromkeys(r["kernel"] for r in rows))
    ncol = 3
    nrow = math.ceil((len(kernels) + 1) / ncol)  # one panel more for the legend
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.6 * ncol, 3.6 * nrow), sharey=True, squeeze=False)
    flat = [ax for row in axes for ax in row]
    for ax, kernel in zip(flat, kernels):
        series = defaultdict(lambda: ([], []))
        ref = defaultdict(lambda: ([], []))
        for r in rows:
            if r["kernel"] != kernel:
                continue
            h = num(r["h_over_dx"])
            s = series[r["formulation"]]
            s[0].append(h)
            s[1].append(num(r["stress_over_modulus"]))
            if r["formulation"] == "sph":
                for key in ("t_plus_33", "t_conservative_33"):
                    ref[key][0].append(h)
                    ref[key][1].append(num(r[key]))
        for key, label in (("t_plus_33", "§3.3 plus"), ("t_conservative_33", "§3.3 conservative (Fig. 3.2)")):
            ax.semilogy(*ref[key], color="0.5", ls="--" if "plus" in key else "-.", lw=1, label=label)
        for form, (colour, ls) in STYLE.items():
            h, t = series.get(form, ([], []))
            # inf (stable to the search limit) and 0 (unstable at zero load) are off the log axis
            pts = [(a, b) for a, b in zip(h, t) if math.isfinite(b) and b > 0]
            if pts:
                ax.semilogy(*zip(*pts), color=colour, ls=ls, lw=1.4, marker=".", ms=3, label="rate form " + form)
        stable = [f for f, (h, t) in series.items() if t and all(math.isinf(b) and b > 0 for b in t)]
        ax.set_title(f"{kernel}" + (f": {', '.join(stable)} stable (inf)" if stable else ""), fontsize=10)
        ax.set_xlabel("h / dx")
        ax.grid(True, which="both", alpha=0.3)
    for row in axes:
        row[0].set_ylabel("critical tension sigma0 / M")
    handles, labels = flat[0].get_legend_handles_labels()
    for ax in flat[len(kernels):]:
        ax.axis("off")
    flat[len(kernels)].legend(handles, labels, fontsize=9, loc="center")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "critical_stress_1d.png"), dpi=130)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/critical-stress-rate-form")
