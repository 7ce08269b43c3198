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
each FE run (an SVK element that inverts has left the model's range).

The sensitivities (README.md; sensitivity_runs.csv, sensitivity_signals.csv, sensitivity_snapshots.csv,
sensitivity_order.csv): S-SPH with the means of G ("ssph-g", case "load") and every formulation at half the load
(case "half-load"). Each run is measured against the FE runs at its own load, v0 of its runs.csv row: the study's FE
runs at Powell's load, new ones (the same meshes and models) at any other; the FE run's initial speed at A is written
beside the run's v0 (sensitivity.csv: fe_v0). Writes sensitivity.csv, sensitivity_fe_runs.csv,
sensitivity_fe_signals.csv and sensitivity_positions_<t>.png (t the last snapshot time)."""
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
import impact_fe  # noqa: E402
from impact_post import (FE_SPACINGS, FE_SVK_SPACING, RECORD_DT, SHARE, CLUMP, LABEL, Problem,  # noqa: E402
                         clumped_share, common_figures, common_summary, evaluate, g, order_series, order_summary, pct,
                         positions_figure, rms, series, signal_error, snapshot, status_text, verdict_summary,
                         write_csv, write_summary)
from plot_common import num, read  # noqa: E402

FORMS = ["sph", "ncsph", "ssph", "tl", "tl-svk"]
SENSITIVITY = {"load": "means of G", "half-load": "half load"}  # sensitivity_runs.csv's case -> its sensitivity
C_S = math.sqrt(impact_fe.MU / impact_fe.RHO)  # shear-wave speed, cm/us


def main(out):
    summary = json.load(open(os.path.join(out, "summary.json")))
    L, H, section, v0 = (num(summary[k]) for k in ("length", "height", "section", "speed"))

    def loaded(speed):
        """The initial velocity of the FE nodes at load `speed`: -speed in y on the loaded section [§4.3]."""
        def velocity(X):
            w = np.zeros_like(X)
            w[:, 1] = np.where(np.abs(X[:, 0] - 0.5 * L) < 0.5 * section, -speed, 0.0)
            return w
        return velocity
    problem = Problem("load", FORMS, "defl", "deflection at A", lambda s: s["deflection"],
                      lambda r, k: r["displacement"][:, k, 1], loaded(v0), clamp=num(summary["clamp"]))
    other = sorted({r["v0"] for r in read(os.path.join(out, "runs.csv")) if num(r["v0"]) != v0})
    if other:  # the study's runs are all at the load its FE reference is run at
        raise SystemExit(f"plot.py: runs.csv has loads {other}, the FE reference is at summary.json's {v0:g}")
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
    if os.path.exists(os.path.join(out, "sensitivity_runs.csv")):
        sensitivities(problem, ctx, out, summary, shape, loaded, lambda u: 0.5 * 7.8 * u * u * section * H)
    write_summary(out, summary)


def failed_run(status, order):
    """The statement table's failure: the run stopped, clumped beyond SHARE or broke into fragments."""
    return status != "completed" or order["clumped_max"] > SHARE or order["fragments_max"] > 1


def sensitivities(problem, ctx, out, summary, shape, loaded, ke0_at):
    """The two sensitivities against the FE runs at each run's own load: sensitivity.csv (the order measures, the
    failure verdict and the errors of every run), the FE runs (sensitivity_fe_runs.csv, sensitivity_fe_signals.csv),
    the table and keys of summary.md and sensitivity_positions_<t>.png."""
    runs = read(os.path.join(out, "sensitivity_runs.csv"))
    sr = series(read(os.path.join(out, "sensitivity_signals.csv")), ("kinetic_energy", "deflection"))
    snaps = read(os.path.join(out, "sensitivity_snapshots.csv"))
    order = order_series(read(os.path.join(out, "sensitivity_order.csv")))
    L, H, t_end, v_main = (num(summary[k]) for k in ("length", "height", "t_end", "speed"))
    dx_main, t_snap, points = ctx["dx"], ctx["times"][-1], ctx["points"]
    # The FE runs by load: Powell's are the study's own; every other load of sensitivity_runs.csv gets the same
    # meshes and models at its speed, with the TL run's particles at that load as the snapshot points.
    fe = {("linear", v_main): ctx["fe"][ctx["ref_key"]], ("svk", v_main): ctx["fe"][ctx["svk_key"]]}
    for v0 in sorted({num(r["v0"]) for r in runs} - {v_main}):
        first = next((snapshot(snaps, "tl", r["case"], num(r["dx"]), t_snap) for r in runs
                      if r["formulation"] == "tl" and num(r["v0"]) == v0), None)
        for model, he in (("linear", FE_SPACINGS[-1]), ("svk", FE_SVK_SPACING)):
            fe[(model, v0)] = impact_fe.fe_run(round(L / he), round(H / he), t_end, loaded(v0), points, (0, 0), (L, H),
                                               first[1] if first else None, [t_snap], model=model,
                                               clamp=problem.clamp, record_dt=RECORD_DT)
            print(f"  FE {model} h_e = {he:g}, v0 = {v0:g}: {fe[(model, v0)]['seconds']:.1f} s", flush=True)
    a = ctx["a"]

    def fe_clumped(r):  # the clumped share of FE's motion of the snapshot particles (dx_main) at t_snap
        snap = r["snapshots"].get(t_snap)
        return clumped_share(snap[1], dx_main) if snap is not None else math.nan
    write_csv(os.path.join(out, "sensitivity_fe_runs.csv"),
              ["model", "element_side", "v0", "dofs", "steps", "dt", "seconds", "j_min", "defl_min_A",
               f"clumped_share_{t_snap:g}"],
              [[m, r["h_e"], v, str(r["dofs"]), str(r["steps"]), r["dt"], r["seconds"], float(np.min(r["j_min"])),
                float(problem.fe_head(r, a).min()), fe_clumped(r)] for (m, v), r in fe.items()])
    xa, ya = points[a]
    write_csv(os.path.join(out, "sensitivity_fe_signals.csv"),
              ["model", "element_side", "v0", "t", "kinetic_energy", f"deflection_at_{xa:g}_{ya:g}"],
              [[m, r["h_e"], v, r["t"][i], r["kinetic_energy"][i], problem.fe_head(r, a)[i]]
               for (m, v), r in fe.items() for i in range(len(r["t"]))])
    e_x = f"e_x_{t_snap:g}"
    columns = ["sensitivity", "formulation", "case", "v0", "v0_over_cS", "dx", "status", "t_stop", "cpu_seconds",
               "fe_v0", "clumped_max", "clump_onset", "clumped_end", "fragments_max", "failed", "e_defl", "e_ke",
               "e_defl_svk", e_x]
    rows = []
    for r in runs:
        f, case, dx, v0, t_stop = r["formulation"], r["case"], num(r["dx"]), num(r["v0"]), num(r["t_stop"])
        lin, svk = fe[("linear", v0)], fe[("svk", v0)]  # the FE runs at this run's own load
        k = points.index((num(r["x_A"]), num(r["y_A"])))
        s = sr[(f, case, dx)]
        d_lin, d_svk = problem.fe_head(lin, k), problem.fe_head(svk, k)
        o = order_summary(order[(f, case, dx)])
        snap, fe_snap = snapshot(snaps, f, case, dx, t_snap), lin["snapshots"].get(t_snap)
        rows.append({"sensitivity": SENSITIVITY[case], "formulation": f, "case": case, "v0": v0,
                     "v0_over_cS": v0 / C_S, "dx": dx, "status": r["status"], "t_stop": t_stop,
                     "cpu_seconds": num(r["cpu_seconds"]), "fe_v0": float(lin["speed"][0, k]),
                     "clumped_max": o["clumped_max"], "clump_onset": o["clump_onset"], "clumped_end": o["clumped_end"],
                     "fragments_max": float(o["fragments_max"]),
                     "failed": "yes" if failed_run(r["status"], o) else "no",
                     "e_defl": signal_error(s["t"], s["deflection"], lin["t"], d_lin, t_stop, np.max(np.abs(d_lin))),
                     "e_ke": signal_error(s["t"], s["kinetic_energy"], lin["t"], lin["kinetic_energy"], t_stop,
                                          ke0_at(v0)),
                     "e_defl_svk": signal_error(s["t"], s["deflection"], svk["t"], d_svk, t_stop,
                                                np.max(np.abs(d_svk))),
                     e_x: (rms(np.linalg.norm(snap[2] - fe_snap[1], axis=1)) / dx
                           if snap is not None and fe_snap is not None and dx == dx_main else math.nan)})
    write_csv(os.path.join(out, "sensitivity.csv"), columns, [[q[c] for c in columns] for q in rows])

    # The table: the study's own runs at the snapshot resolution (Powell's configuration and load), then the
    # sensitivities' runs.
    def line(name, f, v0, dx, status, clumped, end, fragments, e_defl, ex, failed):
        return (f"| {name} | {LABEL[f]} | {v0:g} | {v0 / C_S:.2f} | {dx:g} | {status} | {pct(clumped)} | "
                f"{pct(end)} | {fragments} | {g(e_defl)} | {g(ex)} | {failed} |")
    lines = []
    for f in FORMS:
        r = next(q for q in ctx["runs"] if q["formulation"] == f and num(q["dx"]) == dx_main)
        e, v = ctx["err"][(f, dx_main)], shape[f]
        lines.append(line("none (the study's run)", f, v_main, dx_main, status_text(r), v["clumped_max"],
                          v["clumped_end"], v["fragments_max"], e["e_defl"], e[e_x],
                          "yes" if failed_run(r["status"], v) else "no"))
    for q, r in zip(rows, runs):
        lines.append(line(q["sensitivity"], q["formulation"], q["v0"], q["dx"], status_text(r), q["clumped_max"],
                          q["clumped_end"], int(q["fragments_max"]), q["e_defl"], q[e_x], q["failed"]))
    summary["sensitivity_table"] = "\n".join(lines)
    summary["sensitivity_snapshot_time"] = f"{t_snap:g}"
    summary["v0_over_cs"] = f"{v_main / C_S:.2f}"
    half = [q for q in rows if q["case"] == "half-load"]
    v_half = half[0]["v0"]
    summary["half_v0_over_cs"] = f"{v_half / C_S:.2f}"
    for verdict, key in (("no", "intact"), ("yes", "failed")):
        names = [LABEL[q["formulation"]] for q in half if q["failed"] == verdict]
        summary[f"half_load_{key}"] = ", ".join(names) if names else "none"
    ssph = next(q for q in half if q["formulation"] == "ssph")
    summary["half_load_ssph"] = "completes intact" if ssph["failed"] == "no" else "fails"
    summary["half_load_ssph_how"] = (("completes" if ssph["status"] == "completed" else f"stops ({ssph['status']})")
                                     + (", in one piece" if ssph["fragments_max"] == 1
                                        else f", in up to {int(ssph['fragments_max'])} fragments")
                                     + f", clumped up to {pct(ssph['clumped_max'])}")
    g_main = next(q for q in rows if q["case"] == "load" and q["dx"] == dx_main)
    summary["ssph_g_at_snapshot_spacing"] = "completes intact" if g_main["failed"] == "no" else "fails"
    # What each change does to S-SPH at dx_main (Powell's S-SPH -> the sensitivity's), and the cause it rules out.
    base = {**shape["ssph"], **ctx["err"][("ssph", dx_main)]}

    def change(q):
        return (f"clumped up to {pct(base['clumped_max'])} → {pct(q['clumped_max'])}, fragments up to "
                f"{base['fragments_max']} → {int(q['fragments_max'])}, e_defl {g(base['e_defl'])} → "
                f"{g(q['e_defl'])}, e_x at {t_snap:g} µs {g(base[e_x])} → {g(q[e_x])}")
    summary["ssph_means_of_g_change"] = change(g_main)
    summary["ssph_half_load_change"] = change(ssph)
    own = [r for r in ctx["runs"] if r["formulation"] == "ssph"]
    summary["ssph_stopped"] = f"{sum(r['status'] != 'completed' for r in own)} of {len(own)}"
    fails = {"with the means of G": g_main["failed"] == "yes", "at half the load": ssph["failed"] == "yes"}
    if all(fails.values()):
        summary["ssph_causes"] = ("S-SPH fails by the rule with either change: neither the means of (4.18) alone nor "
                                  "the load alone is why it fails here")
    elif any(fails.values()):
        summary["ssph_causes"] = ("S-SPH passes the rule only " + next(k for k, v in fails.items() if not v)
                                  + ": that change alone removes its failure here")
    else:
        summary["ssph_causes"] = "S-SPH passes the rule with either change: each alone removes its failure here"
    g_runs = [r for r in runs if r["case"] == "load"]
    summary["ssph_g_completed"] = f"{sum(r['status'] == 'completed' for r in g_runs)} of {len(g_runs)}"
    for m in ("linear", "svk"):
        r = fe[(m, v_half)]
        summary[f"fe_half_{m}_j_min"] = g(float(np.min(r["j_min"])))
        summary[f"fe_half_{m}_defl_min"] = g(float(problem.fe_head(r, a).min()))
    summary["fe_clumped_at_snapshot"] = pct(fe_clumped(fe[("linear", v_main)]))
    summary["fe_half_clumped_at_snapshot"] = pct(fe_clumped(fe[("linear", v_half)]))
    summary["fe_half_svk_spacing"] = f"{FE_SVK_SPACING:g}"
    panels = []  # basic SPH left out: its fragments would set every panel's window
    for f in FORMS[1:]:
        snap = snapshot(ctx["snaps"], f, "load", dx_main, t_snap)
        panels.append((f"{LABEL[f]}, v0 {v_main:g}", None if snap is None else (snap[0], snap[2], snap[3])))
    panels.append((f"FE (linear), v0 {v_main:g}", fe[("linear", v_main)]["snapshots"].get(t_snap)))
    for q in rows:
        if q["dx"] == dx_main and q["formulation"] != "sph":
            snap = snapshot(snaps, q["formulation"], q["case"], dx_main, t_snap)
            panels.append((f"{LABEL[q['formulation']]}, v0 {q['v0']:g}",
                           None if snap is None else (snap[0], snap[2], snap[3])))
    panels.append((f"FE (linear), v0 {v_half:g}", fe[("linear", v_half)]["snapshots"].get(t_snap)))
    positions_figure(os.path.join(out, f"sensitivity_positions_{t_snap:g}.png"),
                     f"Particle positions at t = {t_snap:g} us, Powell's load and the sensitivities (dx = {dx_main:g}; "
                     f"basic SPH in positions_{t_snap:g}.png)",
                     panels, 0.3, (9, 1.7))


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
