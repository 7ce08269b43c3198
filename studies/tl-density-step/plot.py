#!/usr/bin/env python3
"""Plots of the density-step study: stress and particle velocity at the reflection probe (x = 0.05 m) and the
transmission probe (x = 0.225 m) for each density ratio at the finest resolution, with the plateaus the impedance
formulas predict. Usage: plot.py RESULTS_DIR (reads coefficients.csv, probes_*.csv)."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from plot_common import decorate, num, plt, read, save  # noqa: E402


def main(out):
    coeff = read(os.path.join(out, "coefficients.csv"))
    n = max(int(r["n"]) for r in coeff)
    cases = [r for r in coeff if int(r["n"]) == n]
    fig, axes = plt.subplots(2, len(cases), figsize=(7 * len(cases), 8), squeeze=False)
    for col, c in enumerate(cases):
        ratio = c["ratio"]
        rows = read(os.path.join(out, f"probes_ratio{ratio}_n{n}.csv"))
        t = [num(r["t_us"]) for r in rows]
        s_in, v_in = num(c["incident_stress_kpa"]), num(c["incident_velocity"])
        ax = axes[0][col]
        ax.plot(t, [num(r["sigma_kpa_xr"]) for r in rows], label="x = 0.05 m (incident, then reflected)")
        ax.plot(t, [num(r["sigma_kpa_xt"]) for r in rows], label="x = 0.225 m (transmitted)")
        ax.axhline(s_in * num(c["R_stress_expected"]), color="C0", ls="--", lw=0.8, label="C_r x incident")
        ax.axhline(s_in * num(c["T_stress_expected"]), color="C1", ls="--", lw=0.8, label="C_t x incident")
        decorate(ax, "t (us)", "P11 (kPa)", f"rho2/rho1 = {ratio}, n = {n}: stress")
        ax = axes[1][col]
        ax.plot(t, [num(r["v_xr"]) for r in rows], label="x = 0.05 m")
        ax.plot(t, [num(r["v_xt"]) for r in rows], label="x = 0.225 m")
        ax.axhline(v_in * num(c["R_velocity_expected"]), color="C0", ls="--", lw=0.8, label="-C_r x incident")
        ax.axhline(v_in * num(c["T_velocity_expected"]), color="C1", ls="--", lw=0.8, label="2Z1/(Z1+Z2) x incident")
        decorate(ax, "t (us)", "v (m/s)", "particle velocity")
    save(fig, os.path.join(out, "tl_density_step.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/tl-density-step")
