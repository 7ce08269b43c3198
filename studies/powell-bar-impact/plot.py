#!/usr/bin/env python3
"""Post-processing of powell-bar-impact: the finite-element reference (../common/impact_fe.py, DOLFINx), the errors of
every SPH run against it, Powell's statements and the figures. Usage: plot.py RESULTS_DIR (reads runs.csv,
signals.csv, snapshots.csv and summary.json; writes fe_runs.csv, fe_signals.csv, fe_errors.csv, errors.csv, shape.csv,
signals.png, positions_<t>.png, pareto.png and adds the FE, error and statement keys to summary.json).

Error norms (README.md), each over the records t <= t_stop of the SPH run, FE interpolated linearly in time:
  e_len    RMS_t (dL - dL_fe) / max_t |dL_fe|, dL = length(t) - length(0) (the change of the bar's length, Fig. 4.11)
  e_ke     RMS_t (KE - KE_fe) / KE(0)
  e_p      RMS_t (p_A - p_fe(A)) / max_t |p_fe(A)|
  e_speed  RMS_t (|v_A| - |v_fe(A)|) / v0
  e_x      RMS over the particles of |x - x_fe(X)| / dx at a snapshot time (snapshot resolution only)
The FE reference is the linear model on the finest mesh; its own error is the same norms between the coarser meshes
and the finest (fe_errors.csv); Saint Venant-Kirchhoff on the middle mesh is the model sensitivity."""
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
from impact_post import (GAP, SHARE, CLUMP, Problem, common_figures, common_summary, evaluate, g,  # noqa: E402
                         order_summary, pct, rms, status_text, verdict_summary, write_csv, write_summary)
from plot_common import num  # noqa: E402

FORMS = ["sph", "ncsph", "ssph", "tl"]
EARLY = 20.0  # us: Powell's "slight deviation from the TL-SPH solution, showing up after 20 us"
ONSET = (15.0, 25.0)  # us: "particle re-organisation which develops slowly from around that time" (20 us, +- 5)


def change(y):
    return y - y[0]


def main(out):
    summary = json.load(open(os.path.join(out, "summary.json")))
    L, H, split, v0 = (num(summary[k]) for k in ("length", "height", "split", "speed"))

    def velocity(X):
        w = np.zeros_like(X)
        w[:, 0] = np.where(X[:, 0] < split * L, v0, -v0)  # the left part moves right, into the rest
        return w
    problem = Problem("impact", FORMS, "len", "length change", lambda s: change(s["length"]),
                      lambda r, k: change(r["length"]), velocity)
    ke0 = 0.5 * 7.8 * v0 * v0 * L * H
    ctx = evaluate(problem, out, summary, ke0)
    sr, dx_main = ctx["sr"], ctx["dx"]
    # Particle order (order.csv) and the length change at the snapshot resolution.
    shape = {}
    tl = sr[("tl", "impact", dx_main)]
    scale = float(np.max(np.abs(change(tl["length"]))))
    for f in FORMS:
        s = sr[(f, "impact", dx_main)]
        row = {"dl_end": float(s["length"][-1] - s["length"][0]), "t_last": float(s["t"][-1])}
        row.update(order_summary(ctx["order"][(f, "impact", dx_main)]))
        for name, m in (("dev_early", s["t"] <= EARLY), ("dev_late", s["t"] > EARLY)):
            d = change(s["length"])[m] - np.interp(s["t"][m], tl["t"], change(tl["length"]))
            row[name] = rms(d) / scale if m.any() else math.nan
        shape[f] = row
    write_csv(os.path.join(out, "shape.csv"), ["formulation"] + list(shape["sph"].keys()),
              [[f, *v.values()] for f, v in shape.items()])
    fe_dl = change(ctx["fe"][ctx["ref_key"]]["length"])
    common_figures(problem, ctx, out, summary, "Asymmetrical bar impact", "Powell Fig. 4.12; Fig. 4.11 in signals.png",
                   "length change (cm)", ke0, (1.5 * fe_dl.min(), max(4 * fe_dl.max(), 0.1)))
    common_summary(problem, ctx, summary)
    summary["fe_dl_max"], summary["fe_dl_min"] = g(float(fe_dl.max())), g(float(fe_dl.min()))
    statements(summary, ctx["runs"], ctx["fe"], ctx["ref_key"], shape)
    verdict_summary(out, summary)
    write_summary(out, summary)


def statements(summary, runs, fe, ref_key, shape):
    """Powell's statements of §4.2 against the runs at the snapshot resolution: one table row each."""
    dx = num(summary["snapshot_spacing"])
    run = {r["formulation"]: r for r in runs if num(r["dx"]) == dx}
    done = {f: run[f]["status"] == "completed" for f in FORMS}
    fe_dl = fe[ref_key]["length"] - fe[ref_key]["length"][0]
    bound = float(fe_dl.max()) + GAP * dx  # the largest elastic elongation plus GAP spacings

    def expands(f):
        """Stopped, or ends longer than FE's largest length change by more than GAP dx."""
        return not done[f] or shape[f]["dl_end"] > bound

    def evidence(f):
        v = shape[f]
        return (f"dL at the end {g(v['dl_end'])} cm (bound {g(bound)}); fragments (bonds < 1.5 dx) up to "
                f"{v['fragments_max']}; clumped up to {pct(v['clumped_max'])}"
                + ("" if done[f] else f"; {status_text(run[f])}"))

    s = shape["ssph"]
    onset = s["clump_onset"]
    rows = [
        ("basic SPH fails and continues to expand", expands("sph"), evidence("sph")),
        ("NCSPH fails and continues to expand", expands("ncsph"), evidence("ncsph")),
        ("S-SPH remains stable (the bar neither expands nor breaks)",
         done["ssph"] and not expands("ssph") and s["fragments_max"] == 1, evidence("ssph")),
        (f"S-SPH deviates slightly from TL-SPH, showing up after {EARLY:g} us",
         done["ssph"] and s["dev_late"] > s["dev_early"],
         f"RMS length-change difference S-SPH − TL / max |dL_TL|: {g(s['dev_early'])} for t ≤ {EARLY:g}, "
         f"{g(s['dev_late'])} after"),
        (f"S-SPH's particles reorganise (clump) slowly from around {EARLY:g} us",
         ONSET[0] <= onset <= ONSET[1],
         f"clumped share first above {pct(SHARE)} at t = {g(onset)} us; {pct(s['clumped_end'])} at the end "
         f"(largest {pct(s['clumped_max'])})"),
    ]
    summary["statements_table"] = "\n".join(f"| §4.2 | {text} | {'yes' if ok else '**no**'} | {ev} |"
                                             for text, ok, ev in rows)
    summary["statements_holding"] = f"{sum(ok for _, ok, _ in rows)} of {len(rows)}"
    summary["clump"], summary["gap"] = str(CLUMP), str(GAP)
    summary["clumped_share"] = f"{100 * SHARE:g} %"
    summary["early"] = f"{EARLY:g}"
    summary["onset_window"] = f"{ONSET[0]:g}–{ONSET[1]:g}"


if __name__ == "__main__":
    main(sys.argv[1])
