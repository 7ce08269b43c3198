#!/usr/bin/env python3
"""Plots of the CSM3 hourglass study: the fundamental and the softest zigzag modes of the beam at rest (c_HG = 0;
whole beam coloured by |phi| and a zoom with arrows), the lift of the softest zigzag eigenvalue and the shift of the
fundamental against c_HG, and the tip displacement u_y(A)(t) of the gravity runs against c_HG.
Also writes mode_energy.csv (each shape mode's energy share in u_x and per grid row).
Usage: plot.py RESULTS_DIR (reads modes.csv, lift.csv, runs.csv, tip_<run>.csv)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, ordered, plt, read, save  # noqa: E402

FORMS = ["plain", "ncsph-variational"]
REF_UY = (-63.607e-3, 65.160e-3)


def modes_plot(out):
    rows = read(os.path.join(out, "modes.csv"))
    for n in ordered(rows, "across"):
        sel = [r for r in rows if r["across"] == n]
        panels = [(f, rank) for f in FORMS for rank in ordered([r for r in sel if r["form"] == f], "rank")]
        fig, axes = plt.subplots(len(panels), 2, figsize=(17, 1.55 * len(panels) + 0.8), squeeze=False,
                                 gridspec_kw={"width_ratios": [3, 1]})
        for (form, rank), (ax, zx) in zip(panels, axes):
            m = [r for r in sel if r["form"] == form and r["rank"] == rank]
            x = [num(r["x"]) for r in m]
            y = [num(r["y"]) for r in m]
            px = [num(r["phi_x"]) for r in m]
            py = [num(r["phi_y"]) for r in m]
            mag = [math.hypot(a, b) for a, b in zip(px, py)]
            mu = num(m[0]["mu"])
            title = (f"{form}, {m[0]['kind']} (rank {rank}): mu = {mu:.4g} 1/s², f = {math.sqrt(max(mu, 0)) / (2 * math.pi):.3g}"
                     f" Hz, zigzag fraction {num(m[0]['zigzag']):.2f}")
            sc = ax.scatter(x, y, c=mag, s=6, cmap="viridis")
            ax.set_title(title, fontsize=8)
            ax.set_xlim(0.245, 0.605)
            ax.tick_params(labelsize=7)
            fig.colorbar(sc, ax=ax, pad=0.005, fraction=0.02)
            # zoom: 16 dx around the largest |phi|, arrows
            dx = min(abs(a - b) for a, b in zip(x, x[1:]) if abs(a - b) > 1e-12)
            xc = x[max(range(len(mag)), key=lambda k: mag[k])]
            keep = [k for k in range(len(x)) if abs(x[k] - xc) <= 8 * dx]
            zx.quiver([x[k] for k in keep], [y[k] for k in keep], [px[k] for k in keep], [py[k] for k in keep],
                      [mag[k] for k in keep], cmap="viridis", scale=None)
            zx.set_aspect("equal")
            zx.set_title(f"zoom at x = {xc:.3f} m (arrows: phi)", fontsize=8)
            zx.tick_params(labelsize=6)
        fig.suptitle(f"CSM3 beam, {n} particles across: the fundamental and the softest zigzag modes of A at rest "
                     "(c_HG = 0), colour |phi|")
        save(fig, os.path.join(out, f"modes_n{n}.png"), dpi=80)


def mode_energy(out):
    """mode_energy.csv: per shape mode of modes.csv, the share of |phi|^2 in u_x and per grid row (bottom to top)."""
    rows = read(os.path.join(out, "modes.csv"))
    groups = {}
    for r in rows:
        groups.setdefault((r["across"], r["form"], r["kind"], r["rank"]), []).append(r)
    with open(os.path.join(out, "mode_energy.csv"), "w") as f:
        f.write("across,form,kind,rank,ux_share,row_shares\n")
        for (n, form, kind, rank), m in groups.items():
            ex = sum(num(r["phi_x"]) ** 2 for r in m)
            total = ex + sum(num(r["phi_y"]) ** 2 for r in m)
            by_row = {}
            for r in m:
                key = round(num(r["y"]), 6)
                by_row[key] = by_row.get(key, 0) + (num(r["phi_x"]) ** 2 + num(r["phi_y"]) ** 2) / total
            shares = " ".join(f"{by_row[k]:.3f}" for k in sorted(by_row))
            f.write(f"{n},{form},{kind},{rank},{ex / total:.4f},{shares}\n")


def lift_plot(out):
    rows = read(os.path.join(out, "lift.csv"))
    fig, axes = plt.subplots(1, 3, figsize=(18, 5.2))
    styles = {"plain": "-", "ncsph-variational": "--"}
    colours = {"4": "C0", "8": "C3"}
    for n in ordered(rows, "across"):
        for form in FORMS:
            sel = [r for r in rows if r["across"] == n and r["form"] == form]
            lab = f"n{n} {form}"
            pos = [r for r in sel if num(r["hourglass"]) > 0]
            c = [num(r["hourglass"]) for r in pos]
            zig = [num(r["mu_zigzag_min"]) if r["zigzag_rank"] != "-1" else math.nan for r in pos]
            col = colours.get(n, "k")
            axes[0].loglog(c, zig, "o" + styles[form], color=col, label=f"{lab}: softest zigzag")
            axes[0].loglog(c, [num(r["mu_fundamental"]) for r in pos], "s" + styles[form], color=col, mfc="none",
                           label=f"{lab}: fundamental")
            z0 = [num(r["mu_zigzag_min"]) for r in sel if num(r["hourglass"]) == 0]
            if z0:
                axes[0].axhline(z0[0], color=col, ls=styles[form], lw=0.6)
            axes[1].semilogx(c, [100 * num(r["fundamental_shift_rel"]) for r in pos], "o" + styles[form], color=col,
                             label=lab)
            g = [num(r["growth_rate"]) for r in pos]
            if any(v == v for v in g):
                axes[2].semilogx(c, g, "o" + styles[form], color=col, label=lab)
    decorate(axes[0], "hourglass coefficient c_HG", "eigenvalue of A (1/s²)",
             "softest zigzag (filled) and fundamental (open); thin lines: zigzag at c_HG = 0", title_size=9, legend=6)
    axes[1].set_yscale("symlog", linthresh=0.1)
    decorate(axes[1], "c_HG", "shift of the fundamental eigenvalue (%)",
             "cost: the beam's fundamental (followed by eigenvector overlap)", title_size=9, legend=7)
    decorate(axes[2], "c_HG", "growth rate max Re sqrt(-mu) at rest (1/s)", "growth at rest (full spectra only)",
             title_size=9, legend=7)
    save(fig, os.path.join(out, "lift.png"), dpi=90)


def tip_plot(out):
    runs = read(os.path.join(out, "runs.csv"))
    groups = list(dict.fromkeys((r["across"], r["form"]) for r in runs))
    fig, axes = plt.subplots(len(groups), 1, figsize=(12, 3.3 * len(groups)), squeeze=False)
    for (n, form), ax in zip(groups, axes[:, 0]):
        mean, amp = REF_UY
        ax.axhspan(1e3 * (mean - amp), 1e3 * (mean + amp), color="0.88", zorder=0, label="reference mean ± amplitude")
        for r in [r for r in runs if r["across"] == n and r["form"] == form]:
            tip = read(os.path.join(out, f"tip_{r['run']}.csv"))
            ax.plot([num(t["t"]) for t in tip], [1e3 * num(t["uy_A"]) for t in tip], lw=0.9,
                    label=f"c_HG = {r['hourglass']}" + ("" if r["status"] == "completed" else " (stopped)"))
        decorate(ax, ylabel="u_y(A) (mm)", title=f"{n} across, {form}", title_size=9, legend=7, loc="lower right",
                 ncol=3)
    axes[-1, 0].set_xlabel("t (s)")
    save(fig, os.path.join(out, "tip.png"), dpi=90)


def main(out):
    modes_plot(out)
    mode_energy(out)
    lift_plot(out)
    tip_plot(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-csm3-hourglass")
