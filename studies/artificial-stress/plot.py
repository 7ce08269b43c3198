"""Plots of the artificial-stress study: results/artificial-stress/artificial_stress.png."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]


def load(name):
    with open(os.path.join(out, name)) as f:
        rows = list(csv.DictReader(f))
    by = {}
    for r in rows:
        by.setdefault(r["lattice"], []).append(r)
    return by


def col(rows, key, clip=None):
    v = [float(r[key]) for r in rows]
    if clip is not None:
        v = [x if math.isfinite(x) else float("nan") for x in v]
    return v


th = load("thresholds.csv")
bs = load("by_sign.csv")
lw = load("long_wave.csv")
sq, fc = th["square"], th["face-centred"]
h_sq, h_fc = col(sq, "h_over_dp"), col(fc, "h_over_dp")

fig, ax = plt.subplots(2, 2, figsize=(11, 8.5))

a = ax[0][0]
a.plot(h_sq, col(sq, "kappa_long", True), "C0-", label="square, longitudinal  $B_x/f_{xx}$")
a.plot(h_fc, col(fc, "kappa_long", True), "C1-", label="face-centred, longitudinal  $B_x/f_{xx}$")
a.plot(h_fc, col(fc, "kappa_trans", True), "C2-", label="face-centred, transverse  $B_y/f_{yy}$")
a.axhline(0.3, color="k", ls=":", lw=1, label=r"$\epsilon = 0.3$ (GMS)")
for h, k, c in ((1.0, 0.209, "C0"), (1.0, 0.143, "C1"), (1.0, 0.327, "C2")):
    a.plot([h], [k], "o", mfc="none", color=c)
a.set_xlabel("$h/\\Delta p$")
a.set_ylabel(r"critical coefficient $|R|\rho^2/|P-S|$")
a.set_title("(a) GMS coefficient $B/f$ (5.22), $k = \\pi/\\Delta p$, n = 4\n(circles: GMS values at h = dp)", fontsize=10)
a.set_ylim(0, 0.36)
a.legend(fontsize=8)
a.grid(alpha=0.3)

a = ax[0][1]
a.axhline(0, color="k", lw=0.8)
a.axvspan(1.2, 1.7, color="C0", alpha=0.08, label="GMS: square $B_y>0$ for 1.2 < h/dp < 1.7")
a.plot(col(bs["square"], "h_over_dp"), col(bs["square"], "By"), "C0-", label="square $B_y$")
a.plot(col(bs["face-centred"], "h_over_dp"), col(bs["face-centred"], "By"), "C1-", label="face-centred $B_y$")
a.axvline(1.4, color="C1", ls=":", lw=1, label="GMS: face-centred $B_y<0$ from 1.4")
a.set_xlabel("$h/\\Delta p$")
a.set_ylabel("$B_y\\ (1/\\Delta p^2)$")
a.set_title("(b) transverse lattice sum $B_y$\n($B_y < 0$: transverse mode unstable in compression)", fontsize=10)
allb = col(bs["square"], "By") + col(bs["face-centred"], "By")
a.set_ylim(min(allb) - 0.03, max(allb) + 0.08)
a.legend(fontsize=8)
a.grid(alpha=0.3)

a = ax[1][0]
styles = (("eps_crit_long_T0.1", "-", "T = 0.1"), ("eps_crit_long_T0.01", "--", "T = 0.01"))
for key, ls, lab in styles:
    a.plot(h_sq, col(sq, key, True), "C0" + ls, label="square long., " + lab)
    a.plot(h_fc, col(fc, key, True), "C1" + ls, label="face-centred long., " + lab)
for key, ls, lab in (("eps_crit_trans_T0.1", "-", "T = 0.1"), ("eps_crit_trans_T0.01", "--", "T = 0.01")):
    a.plot(h_fc, col(fc, key, True), "C2" + ls, label="face-centred trans., " + lab)
a.axhline(0.3, color="k", ls=":", lw=1)
a.set_xlabel("$h/\\Delta p$")
a.set_ylabel(r"critical $\epsilon$")
a.set_title("(c) critical $\\epsilon$ from the full (5.8)/(5.9)\nisotropic tension $\\sigma = T I$, $\\mu = 0.22$, K = 1 (square: A = 0, T-independent)", fontsize=10)
a.set_ylim(0, 0.36)
a.legend(fontsize=7, ncol=2)
a.grid(alpha=0.3)

a = ax[1][1]
a.axhline(0, color="k", lw=0.8)
for lat, c in (("square", "C0"), ("face-centred", "C1")):
    a.plot(col(lw[lat], "h_over_dp"), col(lw[lat], "moment_A_error"), c + "-", label=lat + r": $-A_x/k - 1$")
    a.plot(col(lw[lat], "h_over_dp"), col(lw[lat], "moment_B_error"), c + "--", label=lat + r": $B_x/k^2 - 1$")
a.set_xlabel("$h/\\Delta p$")
a.set_ylabel("relative error as $k \\to 0$")
a.set_title("(d) long-wave lattice moment errors at $k \\to 0$\n(GMS 5.10 takes them as 0)", fontsize=10)
a.legend(fontsize=8)
a.grid(alpha=0.3)

fig.tight_layout()
fig.savefig(os.path.join(out, "artificial_stress.png"), dpi=130)
print("wrote", os.path.join(out, "artificial_stress.png"))
