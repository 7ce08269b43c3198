#!/usr/bin/env python3
"""Plots of the colliding-rings study (GMS 2001 §7.2): time series of the GMS-unit runs (fragments per ring and of
the whole scene, kinetic energy, ring centre-of-mass velocities, closest distance between the rings) and particle
snapshots coloured by sigma_xx for both eps (GMS Figs. 6 and 7). Usage: plot.py RESULTS_DIR (reads runs.csv,
series/<tag>.csv and the VTK frames vtk/<tag>/*.vtp)."""
import glob
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import frozen_modes, num, plt, read, read_vtp, time_series_panels  # noqa: E402

STYLE = {0.0: ("C3", "eps = 0"), 0.3: ("C0", "eps = 0.3")}


def series(out, tag):
    rows = read(os.path.join(out, "series", tag + ".csv"))
    return {k: [num(r[k]) for r in rows] for k in rows[0]}


def main(out):
    runs = [r for r in read(os.path.join(out, "runs.csv")) if r["units"] == "GMS"]
    si_full = [r for r in read(os.path.join(out, "runs.csv")) if r["units"] == "SI" and os.path.isdir(
        os.path.join(out, "vtk", r["tag"]))]
    fig, axes = plt.subplots(2, 2, figsize=(12, 8), sharex=True)
    (a_frag, a_ke), (a_v, a_d) = axes
    for r in runs:
        eps = num(r["eps"])
        colour, label = STYLE.get(eps, ("k", f"eps = {eps:g}"))
        s = series(out, r["tag"])
        t = s["t"]
        a_frag.plot(t, [max(a, b) for a, b in zip(s["fragments_ring0"], s["fragments_ring1"])], color=colour,
                    label=label + ": fragments of the more broken ring")
        a_frag.plot(t, s["fragments"], color=colour, ls=":", label=label + ": fragments of the scene")
        a_ke.plot(t, [k / s["kinetic"][0] for k in s["kinetic"]], color=colour, label=label)
        a_v.plot(t, s["com_vx0"], color=colour, label=label + ": left ring")
        a_v.plot(t, s["com_vx1"], color=colour, ls="--", label=label + ": right ring")
        a_d.plot(t, s["ring_distance"], color=colour, label=label)
        h = num(r["h"])
        for tc in (num(r["contact_last"]),):
            if tc == tc:
                a_d.axvline(tc, color=colour, lw=0.6, ls="--")
    a_d.axhline(2 * h, color="k", lw=0.8, ls="--", label="2h (kernel support)")
    a_d.axhline(num(runs[0]["dp"]), color="k", lw=0.8, ls=":", label="dp")
    a_frag.set(ylabel="fragments (bonds < 1.5 dp)", yscale="log")
    a_ke.set(ylabel="kinetic energy / initial")
    a_v.set(ylabel="ring centre-of-mass v_x / c0")
    a_d.set(ylabel="closest distance between the rings (cm)", ylim=(0, 1.0))
    time_series_panels(fig, axes, "Colliding rings (GMS 2001 §7.2), mu = 0.22, dp = %s, +-0.059 c0; dashed verticals: "
                       "last contact" % runs[0]["dp"], os.path.join(out, "timeseries.png"), legend=7)

    # Snapshots: 5 frames per eps, evenly spread over the run, coloured by sigma_xx on one symmetric scale.
    shown = runs + si_full
    picks = {}
    for r in shown:
        files = sorted(glob.glob(os.path.join(out, "vtk", r["tag"], "*.vtp")))
        if files:
            idx = sorted({round(k * (len(files) - 1) / 4) for k in range(5)})
            picks[r["tag"]] = [files[i] for i in idx]
    if not picks:
        print("plot.py: no VTK frames, no snapshots.png")
        return
    ncol = max(len(v) for v in picks.values())
    fig, axes = plt.subplots(len(picks), ncol, figsize=(3.4 * ncol, 1.9 * len(picks) + 0.9), squeeze=False,
                             layout="constrained")
    lim = 0.02  # sigma_xx colour limit (rho0 c0^2 units); values beyond saturate
    sc = None
    for row, r in enumerate(r for r in shown if r["tag"] in picks):
        scale = 1.0 if r["units"] == "GMS" else 0.01  # SI lengths in m: plot in cm
        tscale = 1.0 if r["units"] == "GMS" else num(r["t_end"]) / (num(r["steps"]) * num(r["dt"]))
        frames = [read_vtp(f, ["sigma_xx"]) for f in picks[r["tag"]]]
        xmax = max(max(abs(v) for v in x) for x, _, _ in frames) / scale + 0.3  # one window per row
        ymax = max(max(abs(v) for v in y) for _, y, _ in frames) / scale + 0.3
        for col, (f, (x, y, d)) in enumerate(zip(picks[r["tag"]], frames)):
            sxx = d["sigma_xx"]
            if r["units"] == "SI":  # stress over rho0 c_s^2 = K
                k_si = 1e7 / (3 * (1 - 2 * 0.3975))
                sxx = [v / k_si for v in sxx]
            step = int(os.path.basename(f).rsplit("_", 1)[1].split(".")[0])
            ax = axes[row][col]
            sc = ax.scatter([v / scale for v in x], [v / scale for v in y], c=sxx, s=1.0, cmap="coolwarm",
                            vmin=-lim, vmax=lim, linewidths=0)
            ax.set_aspect("equal")
            ax.set_xlim(-xmax, xmax)
            ax.set_ylim(-ymax, ymax)
            ax.set_xticks([])
            ax.set_yticks([])
            ax.set_title(f"{r['tag']}, t = {step * num(r['dt']) * tscale:.0f}", fontsize=8)
        for col in range(len(picks[r["tag"]]), ncol):
            axes[row][col].axis("off")
    fig.colorbar(sc, ax=axes, shrink=0.9, label="sigma_xx / (rho0 c0^2), tension > 0 (saturates at +-%g)" % lim)
    fig.suptitle("Particles coloured by sigma_xx = -P + S_xx (GMS Figs. 6 and 7)")
    fig.savefig(os.path.join(out, "snapshots.png"), dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/gms-rings")
    frozen_modes(sys.argv[1] if len(sys.argv) > 1 else "results/gms-rings", "Colliding rings, eps = 0 collision at the spectrum's dp: linearised spectra")
