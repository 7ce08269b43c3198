#!/usr/bin/env python3
"""Plots for the speed-vs-error study: python3 plot.py DIR (reads DIR/*.csv, writes DIR/*.png)."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import num, plt, read, save  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "results/speed-vs-error"

runs = read(f"{out}/runs.csv")
forms = ["tl-plain", "tl-minus", "tl-corrected", "tl-plain-xsph", "ul-plain", "ul-minus-plus"]
colors = dict(zip(forms, ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown"]))
markers = {1.0: "o", 1.3: "s", 2.0: "^"}
kernels = sorted({r["kernel"] for r in runs})
fill = {k: (i == 0) for i, k in enumerate(kernels)}

# --- Pareto: L1 at t = 1.5 against wall seconds ---
fig, axes = plt.subplots(1, 2, figsize=(13, 5.2), sharey=True)
for ax, bnd in zip(axes, ["mirror", "none"]):
    for r in runs:
        if r["boundary"] != bnd or r["status"] != "completed":
            continue
        h = float(r["h_over_dx"])
        ax.loglog(num(r["total_s"]), num(r["l1_final"]), markers[h], color=colors[r["formulation"]],
                  mfc=colors[r["formulation"]] if fill[r["kernel"]] else "none", ms=5, alpha=0.8)
    pts = sorted((num(r["total_s"]), num(r["l1_final"])) for r in runs if r["status"] == "completed")
    front, best = [], math.inf
    for s, e in pts:
        if e < best:
            best = e
            front.append((s, e))
    ax.loglog([p[0] for p in front], [p[1] for p in front], "k--", lw=1, label="Pareto front (all runs)")
    ax.set_title(f"boundary: {bnd}")
    ax.set_xlabel("wall time: setup + stepping [s]")
    ax.grid(True, which="both", alpha=0.3)
axes[0].set_ylabel("L1 velocity error at t = 1.5 µs (relative to v0·L)")
handles = [plt.Line2D([], [], color=colors[f], marker="o", ls="", label=f) for f in forms]
handles += [plt.Line2D([], [], color="gray", marker=markers[h], ls="", label=f"h/Δx = {h}") for h in markers]
handles += [plt.Line2D([], [], color="gray", marker="o", ls="", mfc="gray" if fill[k] else "none", label=k)
            for k in kernels]
handles += [plt.Line2D([], [], color="k", ls="--", label="Pareto front")]
axes[1].legend(handles=handles, fontsize=8, loc="upper right", ncol=2)
fig.suptitle("1D velocity-jump bar: error vs cost (blown-up runs omitted)")
save(fig, f"{out}/pareto.png", dpi=130)

# --- Convergence: L1 against n ---
fig, axes = plt.subplots(2, len(kernels), figsize=(6.5 * len(kernels), 9), sharey=True, squeeze=False)
styles = {1.0: "-", 1.3: "--", 2.0: ":"}
for row, bnd in enumerate(["mirror", "none"]):
    for col, k in enumerate(kernels):
        ax = axes[row][col]
        for f in forms:
            if f == "ul-plain":
                continue
            for h in styles:
                sel = sorted((int(r["n"]), num(r["l1_final"])) for r in runs
                             if r["kernel"] == k and r["boundary"] == bnd and r["formulation"] == f
                             and float(r["h_over_dx"]) == h and r["status"] == "completed")
                if sel:
                    ax.loglog([s[0] for s in sel], [s[1] for s in sel], styles[h], marker=markers[h], ms=4,
                              color=colors[f], label=f"{f}, h/Δx={h}" if (row, col) == (0, 0) else None)
        n_ref = [100, 1600]
        ax.loglog(n_ref, [0.15 * (n / 100) ** -0.5 for n in n_ref], "k-", lw=0.8)
        ax.text(1600, 0.15 * 16 ** -0.5, " n^-1/2", fontsize=8)
        ax.set_title(f"{k}, boundary {bnd}")
        ax.set_xlabel("particles n")
        ax.grid(True, which="both", alpha=0.3)
    axes[row][0].set_ylabel("L1 at t = 1.5 µs")
axes[0][0].legend(fontsize=6.5, ncol=2)
fig.suptitle("Convergence at fixed h/Δx (ul-plain at v0 = 0.01 omitted: it blows up)")
save(fig, f"{out}/convergence.png", dpi=130)

# --- Error over time ---
hist = read(f"{out}/error_history.csv")
fig, axes = plt.subplots(1, 2, figsize=(13, 4.5), sharey=True)
for ax, bnd in zip(axes, ["mirror", "none"]):
    for f in forms:
        sel = [(num(r["t"]), num(r["l1"])) for r in hist if r["kernel"] == "cubic" and r["boundary"] == bnd
               and r["formulation"] == f and num(r["h_over_dx"]) == 1.3 and r["n"] == "400"]
        if sel:
            ax.semilogy([s[0] for s in sel], [s[1] for s in sel], color=colors[f], label=f)
    ax.set_title(f"cubic, h/Δx = 1.3, n = 400, boundary {bnd}")
    ax.set_xlabel("t [µs]")
    ax.grid(True, which="both", alpha=0.3)
axes[0].set_ylabel("L1 velocity error")
axes[0].legend(fontsize=8)
save(fig, f"{out}/error_vs_time.png", dpi=130)

# --- Velocity profiles at t = 1.5 ---
prof = read(f"{out}/profiles.csv")
fig, axes = plt.subplots(2, 2, figsize=(13, 8), sharex=True, sharey=True)
ex = [(num(r["x"]), num(r["v"])) for r in prof if r["formulation"] == "exact"]
for i, n in enumerate(["100", "400"]):
    for j, bnd in enumerate(["mirror", "none"]):
        ax = axes[i][j]
        ax.plot([e[0] for e in ex], [e[1] for e in ex], "k-", lw=1.5, label="exact")
        for f in ["tl-plain", "tl-corrected", "tl-plain-xsph", "ul-minus-plus"]:
            sel = [(num(r["x"]), num(r["v"])) for r in prof if r["formulation"] == f and r["n"] == n
                   and r["boundary"] == bnd]
            if sel:
                ax.plot([s[0] for s in sel], [s[1] for s in sel], ".-", ms=2, lw=0.7, color=colors[f], label=f)
        ax.set_title(f"n = {n}, boundary {bnd} (cubic, h/Δx = 1.3)")
        ax.grid(True, alpha=0.3)
        if i == 1:
            ax.set_xlabel("x [cm]")
        if j == 0:
            ax.set_ylabel("v at t = 1.5 µs [cm/µs] (scaled to v0 = 0.01)")
axes[0][0].legend(fontsize=8)
save(fig, f"{out}/profiles.png", dpi=130)
print(f"plot.py: wrote pareto.png, convergence.png, error_vs_time.png, profiles.png to {out}")
