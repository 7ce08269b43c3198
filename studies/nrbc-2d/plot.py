#!/usr/bin/env python3
"""Plots of the 2D square-compression study (Powell 2012 ch. 2 §3.2(a), Figs. 2.13-2.16): kinetic energy of the block
over KE0 against the large reference, and the deviation from it, for the centred (2.73), skewed (2.74) and
central-disc (2.76) fields (the disc at v0 = 0.01 and 0.05); P, M, Powell's and Higdon's H and the viscous traction
(2.75).
Usage: plot.py RESULTS_DIR (reads runs.csv and series/<tag>.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402


COLOURS = {"free": "tab:blue", "P": "tab:orange", "M": "tab:green", "H-Powell": "tab:red", "H-Higdon": "tab:purple",
           "traction": "tab:brown", "free-plain": "tab:olive"}


def tag(row):
    kind = "_" + row["field"]
    timing = "" if row["timing"] == "-" else "_" + row["timing"]
    return row["boundary"] + kind + timing


def main(out):
    rows = read(os.path.join(out, "runs.csv"))
    fields = {"centred": "centred (2.73)", "skewed": "skewed (2.74)", "disc": "central disc (2.76), v0 = 0.01",
              "disc_fast": "central disc, v0 = 0.05"}
    fig, axes = plt.subplots(2, 4, figsize=(22, 8), sharex=True)
    for col, field in enumerate(fields):
        a_ke, a_dev = axes[0][col], axes[1][col]
        for r in rows:
            if r["field"] != field:
                continue
            s = read(os.path.join(out, "series", tag(r) + ".csv"))
            t = [num(x["t"]) for x in s]
            ke = [num(x["ke_over_ke0"]) for x in s]
            label = r["boundary"] + ("" if r["timing"] == "-" else f" ({r['timing']} step)")
            style = (dict(color="k", ls="--", lw=1.5) if r["boundary"] == "reference"
                     else dict(color=COLOURS.get(r["boundary"], "0.3"), lw=1))
            if r["boundary"] == "reference-plain":
                style = dict(color="0.5", ls="--", lw=1.5)
            if r["timing"] == "half":
                style["ls"] = ":"
            a_ke.plot(t, ke, label=label, **style)
            if r["boundary"] not in ("reference", "reference-plain", "free", "free-plain"):
                a_dev.plot(t, [100 * (num(x["ke_over_ke0"]) - num(x["ke_ref_over_ke0"])) for x in s], label=label,
                           **style)
        a_ke.set_ylim(0, 1.2)
        decorate(a_ke, ylabel="KE of the block / KE0", title=fields[field])
        a_dev.axhline(0.25, color="0.5", lw=0.6, ls=":")
        a_dev.axhline(-0.25, color="0.5", lw=0.6, ls=":")
        decorate(a_dev, "t (us)", "(KE - KE_ref) / KE0  (%); traction: against reference-plain")
    save(fig, os.path.join(out, "kinetic_energy.png"))


if __name__ == "__main__":
    main(sys.argv[1])
