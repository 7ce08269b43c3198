#!/usr/bin/env python3
"""Plots of the plastic-slab study (GMS 2001 §7.3): time series of every run (neck ratio, widths, fragments, kinetic
energy, with GMS's times marked), particle snapshots coloured by sigma_xx (GMS Figs. 8-10) and width profiles at the
events. Usage: plot.py RESULTS_DIR (reads runs.csv, series/<tag>.csv, frames.csv, profiles.csv and the VTK frames)."""
import os
import sys
from collections import defaultdict

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import frozen_modes, num, plt, read, read_vtp, save, time_series_panels  # noqa: E402

GMS_TIMES = {0.0: [(119, "GMS break (eps 0)")], 0.3: [(394, "GMS neck"), (542, "GMS break")]}


def style(run, dps):
    eps, dp = num(run["eps"]), num(run["dp"])
    colour = "C3" if eps == 0 else "C0"
    ls = ["-", "--", ":", "-."][sorted(dps).index(dp) % 4]
    return colour, ls, f"dp = {dp:g}, eps = {eps:g}"


def main(out):
    runs = read(os.path.join(out, "runs.csv"))
    dps = sorted({num(r["dp"]) for r in runs})
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    (a_ratio, a_width), (a_frag, a_ke) = axes
    for r in runs:
        colour, ls, label = style(r, dps)
        rows = read(os.path.join(out, "series", r["tag"] + ".csv"))
        t = [num(x["t"]) for x in rows]
        a_ratio.plot(t, [num(x["min_width"]) / num(x["median_width"]) for x in rows], color=colour, ls=ls, label=label)
        a_width.plot(t, [num(x["min_width"]) for x in rows], color=colour, ls=ls, label=label + ": narrowest")
        a_width.plot(t, [num(x["median_width"]) for x in rows], color=colour, ls=ls, lw=0.6, alpha=0.6,
                     label=label + ": median")
        a_frag.plot(t, [num(x["fragments"]) for x in rows], color=colour, ls=ls, label=label)
        a_ke.plot(t[1:], [num(x["kinetic"]) for x in rows[1:]], color=colour, ls=ls, label=label)  # KE(0) = 0
        for ax in (a_ratio, a_frag):
            tb = num(r["t_break"])
            if tb == tb:
                ax.axvline(tb, color=colour, ls=ls, lw=0.8)
    for eps, marks in GMS_TIMES.items():
        for tm, text in marks:
            for ax in axes.flat:
                ax.axvline(tm, color="0.5", lw=2, alpha=0.25)
            a_ratio.text(tm, 0.02, " " + text, rotation=90, fontsize=7, color="0.4", va="bottom")
    a_ratio.axhline(0.95, color="k", lw=0.8, ls="--", label="neck onset threshold 0.95")
    a_ratio.set(ylabel="narrowest / median width (inner window)", ylim=(0, 1.05))
    a_width.set(ylabel="width (cm), inner window")
    a_frag.set(ylabel="fragments (bonds < 1.5 dp)")
    a_ke.set(ylabel="kinetic energy (t >= 1)", yscale="log")
    time_series_panels(fig, axes, "Plastic slab in tension (GMS 2001 §7.3); coloured verticals: detected break "
                       "(1.5 dp bonds); grey: GMS's times", os.path.join(out, "timeseries.png"), legend=6)

    # Snapshots: per run, a regular frame before the events, the neck onset, the break and the final frame.
    frames = defaultdict(list)
    for f in read(os.path.join(out, "frames.csv")):
        frames[f["tag"]].append(f)
    picks = {}
    for r in runs:
        fs = frames.get(r["tag"], [])
        if not fs:
            continue
        by_kind = {}
        for f in fs:
            by_kind.setdefault(f["kind"], f)
        chosen = []
        events = [by_kind[k] for k in ("neck", "break", "separation") if k in by_kind]
        t_first = min([num(f["t"]) for f in events], default=num(fs[-1]["t"]))
        regular = [f for f in fs if f["kind"] == "regular" and 0 < num(f["t"]) < t_first]
        if regular:
            chosen.append(regular[len(regular) // 2])
        chosen += [f for f in events if f["kind"] != "separation"]
        chosen.append([f for f in fs if f["kind"] in ("final", "regular")][-1])
        picks[r["tag"]] = chosen[:4]
    if picks:
        ncol = max(len(v) for v in picks.values())
        tags = [r["tag"] for r in runs if r["tag"] in picks]
        fig, axes = plt.subplots(len(tags), ncol, figsize=(4.6 * ncol, 1.45 * len(tags) + 0.9), squeeze=False,
                                 layout="constrained")
        lim = 0.06
        sc = None
        for row, tag in enumerate(tags):
            frames_xy = [read_vtp(os.path.join(out, f["file"]), ["sigma_xx", "driven"]) for f in picks[tag]]
            xmax = max(max(abs(v) for v in x) for x, _, _ in frames_xy) + 0.05  # one window per row
            dp = num(next(r for r in runs if r["tag"] == tag)["dp"])
            size = 6.0 * (dp / 0.04) ** 2  # marker area ~ dp^2
            for col, (f, (x, y, d)) in enumerate(zip(picks[tag], frames_xy)):
                ax = axes[row][col]
                free = [i for i in range(len(x)) if d["driven"][i] == 0]
                drv = [i for i in range(len(x)) if d["driven"][i] != 0]
                ax.scatter([x[i] for i in drv], [y[i] for i in drv], c="0.3", s=size, linewidths=0)
                sc = ax.scatter([x[i] for i in free], [y[i] for i in free], c=[d["sigma_xx"][i] for i in free],
                                s=size, cmap="coolwarm", vmin=-lim, vmax=lim, linewidths=0)
                ax.set_aspect("equal")
                ax.set_xlim(-xmax, xmax)
                ax.set_ylim(-0.6, 0.6)
                ax.set_xticks([])
                ax.set_yticks([])
                ax.set_title(f"{tag}, {f['kind']}, t = {num(f['t']):.0f}", fontsize=8)
            for col in range(len(picks[tag]), ncol):
                axes[row][col].axis("off")
        fig.colorbar(sc, ax=axes, shrink=0.9, label="sigma_xx (rho0 c0^2), saturates at +-%g; driven zones grey" % lim)
        fig.suptitle("Slab particles coloured by sigma_xx = -P + S_xx (GMS Figs. 8-10)")
        fig.savefig(os.path.join(out, "snapshots.png"), dpi=110)
        plt.close(fig)

    # Width profiles at the events.
    prof = defaultdict(lambda: defaultdict(lambda: ([], [])))
    for p in read(os.path.join(out, "profiles.csv")):
        if p["kind"] in ("neck", "break-before", "final"):
            xs, ws = prof[p["tag"]][(p["kind"], num(p["t"]))]
            xs.append(num(p["x"]))
            ws.append(num(p["width"]))
    if prof:
        tags = [r["tag"] for r in runs if r["tag"] in prof]
        fig, axes = plt.subplots(len(tags), 1, figsize=(9, 2.3 * len(tags)), squeeze=False, sharex=True)
        for row, tag in enumerate(tags):
            ax = axes[row][0]
            for (kind, t), (xs, ws) in sorted(prof[tag].items(), key=lambda kv: kv[0][1]):
                ax.plot(xs, ws, ".-", ms=2, lw=0.8, label=f"{kind}, t = {t:.0f}")
            ax.set_ylabel("width (cm)")
            ax.set_title(tag, fontsize=9)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=7)
        axes[-1][0].set_xlabel("x (cm), between the driven zones")
        save(fig, os.path.join(out, "profiles.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/gms-slab")
    frozen_modes(sys.argv[1] if len(sys.argv) > 1 else "results/gms-slab", "Plastic slab, eps = 0 run at the spectrum's dp: linearised spectra")
