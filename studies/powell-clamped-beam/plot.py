#!/usr/bin/env python3
"""Post-processing of powell-clamped-beam: the finite-element reference (../common/impact_fe.py, DOLFINx), the errors of
every SPH run against it, Powell's statements and the figures. Usage: plot.py RESULTS_DIR (reads runs.csv,
signals.csv, snapshots.csv and summary.json; writes fe_runs.csv, fe_signals.csv, fe_errors.csv, errors.csv, shape.csv,
signals.png, positions_<t>.png, pareto.png and adds the FE, error and statement keys to summary.json).

Error norms (README.md), each over the records t <= t_stop of the SPH run, FE interpolated linearly in time:
  e_defl   RMS_t (d - d_fe(A)) / max_t |d_fe(A)|, d the y displacement of A, the bottom mid-span particle (Fig. 4.14)
  e_ke     RMS_t (KE - KE_fe) / KE(0)
  e_p      RMS_t (p_A - p_fe(A)) / max_t |p_fe(A)|
  e_speed  RMS_t (|v_A| - |v_fe(A)|) / v0
  e_x      RMS over the particles of |x - x_fe(X)| / dx at a snapshot time (snapshot resolution only)
The FE reference is the linear model (Powell's "linear elastic material model", as in the other two problems) on the
finest mesh; its own error is the same norms between the coarser meshes and the finest (fe_errors.csv); Saint
Venant-Kirchhoff (finite strain) on the middle mesh is the model sensitivity, with the smallest cell-mean det F of
each FE run (an SVK element that inverts has left the model's range)."""
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
from impact_post import (SHARE, CLUMP, LABEL, Problem, common_figures, common_summary, evaluate, g,  # noqa: E402
                         order_summary, pct, status_text, verdict_summary, write_csv, write_summary)
from plot_common import num  # noqa: E402

FORMS = ["sph", "ncsph", "ssph", "tl", "tl-svk"]


def main(out):
    summary = json.load(open(os.path.join(out, "summary.json")))
    L, H, section, v0 = (num(summary[k]) for k in ("length", "height", "section", "speed"))

    def velocity(X):
        w = np.zeros_like(X)
        w[:, 1] = np.where(np.abs(X[:, 0] - 0.5 * L) < 0.5 * section, -v0, 0.0)  # the loaded section [§4.3]
        return w
    problem = Problem("load", FORMS, "defl", "deflection at A", lambda s: s["deflection"],
                      lambda r, k: r["displacement"][:, k, 1], velocity, clamp=num(summary["clamp"]))
    ke0 = 0.5 * 7.8 * v0 * v0 * section * H
    ctx = evaluate(problem, out, summary, ke0)
    shape = {}
    for f in FORMS:
        s = ctx["sr"][(f, "load", ctx["dx"])]
        shape[f] = {"defl_min": float(s["deflection"].min()), "t_last": float(s["t"][-1]),
                    **order_summary(ctx["order"][(f, "load", ctx["dx"])])}
    write_csv(os.path.join(out, "shape.csv"), ["formulation"] + list(shape["sph"].keys()),
              [[f, *v.values()] for f, v in shape.items()])
    d = ctx["fe"][ctx["ref_key"]]["displacement"][:, ctx["a"], 1]
    common_figures(problem, ctx, out, summary, "Clamped beam under a transient load",
                   "Powell Figs. 4.15-4.18; Fig. 4.14 in signals.png", "y displacement at A (cm)", ke0,
                   (2 * d.min(), max(2 * d.max(), -0.5 * d.min())))
    common_summary(problem, ctx, summary)
    summary["fe_defl_min"], summary["fe_defl_end"] = g(float(d.min())), g(float(d[-1]))
    statements(summary, ctx["runs"], ctx["err"], shape, ctx["times"])
    verdict_summary(out, summary)
    write_summary(out, summary)


def statements(summary, runs, err, shape, times):
    """Powell's statements of §4.3 against the runs at the snapshot resolution: one table row each."""
    dx = num(summary["snapshot_spacing"])
    run = {r["formulation"]: r for r in runs if num(r["dx"]) == dx}
    done = {f: run[f]["status"] == "completed" for f in FORMS}
    e = {f: err[(f, dx)] for f in FORMS}
    t_last = times[-1]

    def failed(f):
        v = shape[f]
        return not done[f] or v["clumped_max"] > SHARE or v["fragments_max"] > 1

    def evidence(f):
        v = shape[f]
        return (f"e_defl {g(e[f]['e_defl'])}; clumped up to {pct(v['clumped_max'])}, fragments (bonds < 1.5 dx) up "
                f"to {v['fragments_max']}" + ("" if done[f] else f"; {status_text(run[f])}"))

    rows = [
        ("the displacements of S-SPH, TL-SPH and FE are in close agreement",
         done["ssph"] and done["tl"]
         and max(e["ssph"]["e_defl"], e["tl"]["e_defl"]) < min([e[f]["e_defl"] for f in ("sph", "ncsph") if done[f]],
                                                                default=math.inf),
         "e_defl (a stopped run's up to its stop): " + ", ".join(f"{LABEL[f]} {g(e[f]['e_defl'])}" for f in FORMS)),
        ("basic SPH has failed due to tensile instability", failed("sph"), evidence("sph")),
        ("NCSPH is close to failure: it completes, intact, with some particles clumped",
         done["ncsph"] and shape["ncsph"]["fragments_max"] == 1 and shape["ncsph"]["clumped_max"] > 0,
         evidence("ncsph")),
        ("S-SPH's particle distribution agrees closely with FE's (Figs. 4.17, 4.18)",
         done["ssph"] and not failed("ssph") and e["ssph"][f"e_x_{t_last:g}"] < 1,
         f"RMS |x − x_FE| / dx at {t_last:g} us: " + ", ".join(f"{LABEL[f]} {g(e[f][f'e_x_{t_last:g}'])}"
                                                               for f in FORMS) + "; S-SPH: " + evidence("ssph")),
    ]
    summary["statements_table"] = "\n".join(f"| §4.3 | {text} | {'yes' if ok else '**no**'} | {ev} |"
                                             for text, ok, ev in rows)
    summary["statements_holding"] = f"{sum(ok for _, ok, _ in rows)} of {len(rows)}"
    summary["clump"] = str(CLUMP)
    summary["clumped_share"] = f"{100 * SHARE:g} %"


if __name__ == "__main__":
    main(sys.argv[1])
