#!/usr/bin/env python3
"""Plots of the hourglass study: mode shapes (1D lines, 2D quivers) at c_HG = 0, the lift of the softest zigzag and
smooth eigenvalues against c_HG, the strain-operator symbol, the validation bar against c_HG and the noise runs.
Usage: plot.py RESULTS_DIR (reads modes.csv, lift.csv, symbol.csv, bar.csv, bar_probes.csv, noise.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, ordered, plt, read, save  # noqa: E402


def modes_plot(out):
    rows = read(os.path.join(out, "modes.csv"))
    configs = ordered(rows, "config")
    variants = ["plain-difference", "ncsph-difference"]
    for cfg in configs:
        sel = [r for r in rows if r["config"] == cfg]
        two_d = cfg.startswith("2d")
        fig, axes = plt.subplots(len(variants), 6, figsize=(20, 3.2 * len(variants) + (3 if two_d else 0)),
                                 squeeze=False)
        for vi, var in enumerate(variants):
            for rank in range(6):
                ax = axes[vi][rank]
                m = [r for r in sel if r["variant"] == var and int(r["rank"]) == rank]
                if not m:
                    ax.axis("off")
                    continue
                x = [num(r["x"]) for r in m]
                title = f"{var}\n#{rank}: mu = {num(m[0]['mu']):.3g}, zigzag {num(m[0]['zigzag']):.2f}"
                if two_d:
                    y = [num(r["y"]) for r in m]
                    ax.quiver(x, y, [num(r["phi_x"]) for r in m], [num(r["phi_y"]) for r in m], scale=None)
                    ax.set_aspect("equal")
                else:
                    ax.plot(x, [num(r["phi_x"]) for r in m], "o-", ms=3)
                    ax.axhline(0, color="0.7", lw=0.5)
                ax.set_title(title, fontsize=8)
                ax.tick_params(labelsize=7)
        fig.suptitle(f"{cfg}: the six softest eigenvectors of A = -da/du at u = 0 (c_HG = 0)")
        save(fig, os.path.join(out, f"modes_{cfg}.png"), dpi=90)


def lift_plot(out):
    rows = read(os.path.join(out, "lift.csv"))
    configs = ordered(rows, "config")
    fig, axes = plt.subplots(1, 3, figsize=(18, 5.5))
    for ax in axes:
        ax.set_prop_cycle(color=[plt.get_cmap("tab20")(i) for i in range(20)])
    for cfg in configs:
        for var, ls in (("plain-difference", "-"), ("ncsph-difference", "--"), ("plain-difference-full", ":")):
            if var.endswith("full") and not cfg.startswith("2d"):
                continue  # in 1D the full vector is the bond projection
            sel = [r for r in rows if r["config"] == cfg and r["variant"] == var and num(r["hourglass"]) > 0]
            c = [num(r["hourglass"]) for r in sel]
            line, = axes[0].loglog(c, [num(r["mu_zigzag_min"]) for r in sel], "o" + ls, label=f"{cfg} {var}")
            closed = [num(r["mu_closed_form"]) for r in sel]
            if all(v == v for v in closed):
                axes[0].loglog(c, closed, "x:", color=line.get_color(), ms=9)
            axes[1].semilogx(c, [100 * num(r["fundamental_shift_rel"]) for r in sel], "o" + ls, color=line.get_color(),
                             label=f"{cfg} {var}")
            axes[2].semilogx(c, [num(r["zigzag_below_smooth"]) for r in sel], "o" + ls, color=line.get_color())
    decorate(axes[0], "hourglass coefficient c_HG",
             "softest zigzag eigenvalue (E / rho dx^2); x: closed form / Bloch symbol", "lift of the hourglass modes",
             legend=6)
    decorate(axes[1], "c_HG", "shift of the fundamental eigenvalue (%)", "cost: the fundamental mode", legend=None)
    decorate(axes[2], "c_HG", "zigzag modes softer than the softest smooth mode", "spurious soft modes left",
             legend=None)
    save(fig, os.path.join(out, "lift.png"), dpi=100)


def symbol_plot(out):
    rows = read(os.path.join(out, "symbol.csv"))
    fig, ax = plt.subplots(figsize=(7, 5))
    for cfg in ordered(rows, "config"):
        for var in ordered([r for r in rows if r["config"] == cfg], "variant"):
            sel = [r for r in rows if r["config"] == cfg and r["variant"] == var]
            ax.plot([num(r["k_over_pi"]) for r in sel], [num(r["abs_K_symbol"]) for r in sel], "o-", ms=3,
                    label=f"{cfg} {var}")
    decorate(ax, "k dx / pi (along x)", "|symbol of the strain operator K^x|",
             "the strain operator's symbol vanishes at k = pi / dx", legend=6)
    save(fig, os.path.join(out, "symbol.png"), dpi=100)


def bar_plot(out):
    probes = read(os.path.join(out, "bar_probes.csv"))
    bar = read(os.path.join(out, "bar.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(15, 5.5))
    ax = axes[0]
    first = True
    for c in ordered(probes, "hourglass"):
        if num(c) not in (0, 0.1, 1):
            continue
        sel = [r for r in probes if r["hourglass"] == c]
        t = [num(r["t_us"]) for r in sel]
        if first:
            ax.plot(t, [num(r["sigma_exact_kpa_x0.1"]) for r in sel], "k-", lw=2, label="exact")
            first = False
        ax.plot(t, [num(r["sigma_sph_kpa_x0.1"]) for r in sel], label=f"c_HG = {c}")
    decorate(ax, "t (us)", "stress at x = 0.10 m (kPa)", "validation bar (Hooke 1D stress): probe at x = 0.10 m")
    ax = axes[1]
    c = [max(num(r["hourglass"]), 1e-3) for r in bar]
    for col, lab in (("max_error_kpa_x0.05", "max |error| x = 0.05"), ("max_error_kpa_x0.1", "max |error| x = 0.10"),
                     ("max_error_kpa_x0.15", "max |error| x = 0.15 (fixed end)")):
        ax.semilogx(c, [num(r[col]) for r in bar], "o-", label=lab)
    ax.semilogx(c, [abs(num(r["plateau_error_kpa_x0.1"])) for r in bar], "s--", label="|plateau error| x = 0.10")
    decorate(ax, "c_HG (0 plotted at 1e-3)", "kPa", "accuracy cost against the coefficient")
    save(fig, os.path.join(out, "bar.png"), dpi=100)


def noise_plot(out):
    rows = read(os.path.join(out, "noise.csv"))
    configs = ordered(rows, "config")
    fig, axes = plt.subplots(1, len(configs), figsize=(5 * len(configs), 4.5), squeeze=False)
    for ax, cfg in zip(axes[0], configs):
        for c in ordered([r for r in rows if r["config"] == cfg], "hourglass"):
            sel = [r for r in rows if r["config"] == cfg and r["hourglass"] == c]
            ax.plot([num(r["time"]) for r in sel], [num(r["zigzag_amplitude"]) for r in sel], label=f"c_HG = {c}")
        decorate(ax, "t (dx / c)", "zigzag amplitude (dx)", f"{cfg}: noisy initial velocity 1e-3 c", title_size=9)
    save(fig, os.path.join(out, "noise.png"), dpi=100)


def main(out):
    modes_plot(out)
    lift_plot(out)
    symbol_plot(out)
    bar_plot(out)
    noise_plot(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-hourglass")
