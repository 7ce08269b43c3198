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
import impact_fe  # noqa: E402
from impact_post import (COLOUR, LABEL, SHARE, CLUMP, best_per_error, g, order_panel, order_series,  # noqa: E402
                         order_summary, pareto_figure, positions_figure, pct, rms, series, signal_error, snapshot,
                         first_stop, status_text, write_csv)
from plot_common import num, plt, read  # noqa: E402

FORMS = ["sph", "ncsph", "ssph", "tl", "tl-svk"]
FE_SPACINGS = (0.02, 0.01, 0.005)  # element sides h_e (cm): 200 x 20, 400 x 40, 800 x 80 elements
FE_SVK_SPACING = 0.01
RECORD_DT = 0.05  # us, FE record interval


def fe_key(model, he):
    return (model, he)


def run_fe(summary, runs, snaps):
    L, H, section, clamp, v0 = (num(summary[k]) for k in ("length", "height", "section", "clamp", "speed"))
    t_end, dx = num(summary["t_end"]), num(summary["snapshot_spacing"])
    points = sorted({(num(r["x_A"]), num(r["y_A"])) for r in runs})
    times = [float(t) for t in summary["snapshot_times"].split(", ")]
    first = snapshot(snaps, "tl", "load", dx, times[0])
    xs = first[1] if first else None

    def velocity(X):
        w = np.zeros_like(X)
        w[:, 1] = np.where(np.abs(X[:, 0] - 0.5 * L) < 0.5 * section, -v0, 0.0)  # the loaded section [§4.3]
        return w
    fe = {}
    for model, spacings in (("linear", FE_SPACINGS), ("svk", (FE_SVK_SPACING,))):
        for he in spacings:
            r = impact_fe.fe_run(round(L / he), round(H / he), t_end, velocity, points, (0, 0), (L, H), xs, times,
                                 model=model, clamp=clamp, record_dt=RECORD_DT)
            fe[fe_key(model, he)] = r
            print(f"  FE {model} h_e = {he:g}: {r['dofs']} dofs, {r['steps']} steps, {r['seconds']:.1f} s", flush=True)
    return fe, points


def main(out):
    summary = json.load(open(os.path.join(out, "summary.json")))
    runs, sig, snaps = (read(os.path.join(out, f)) for f in ("runs.csv", "signals.csv", "snapshots.csv"))
    section, v0 = num(summary["section"]), num(summary["speed"])
    dx_main = num(summary["snapshot_spacing"])
    times = [float(t) for t in summary["snapshot_times"].split(", ")]
    fe, points = run_fe(summary, runs, snaps)
    ref_key = fe_key("linear", FE_SPACINGS[-1])
    ref = fe[ref_key]
    ke0 = 0.5 * 7.8 * v0 * v0 * section * num(summary["height"])
    write_csv(os.path.join(out, "fe_runs.csv"), ["model", "element_side", "dofs", "steps", "dt", "seconds"],
              [[k[0], k[1], str(r["dofs"]), str(r["steps"]), r["dt"], r["seconds"]] for k, r in fe.items()])
    write_csv(os.path.join(out, "fe_signals.csv"), ["model", "element_side", "t", "kinetic_energy"]
              + [f"deflection_at_{x:g}_{y:g}" for x, y in points] + [f"pressure_at_{x:g}_{y:g}" for x, y in points]
              + [f"speed_at_{x:g}_{y:g}" for x, y in points],
              [[k[0], k[1], r["t"][i], r["kinetic_energy"][i]] + list(r["displacement"][i, :, 1])
               + list(r["pressure"][i]) + list(r["speed"][i])
               for k, r in fe.items() if k in (ref_key, fe_key("svk", FE_SVK_SPACING))
               for i in range(len(r["t"]))])

    a_main = next(points.index((num(r["x_A"]), num(r["y_A"]))) for r in runs if num(r["dx"]) == dx_main)

    def errors(t, ke, defl, p, speed, k, t_stop, against):
        d_fe = against["displacement"][:, k, 1]
        return {"e_defl": signal_error(t, defl, against["t"], d_fe, t_stop, float(np.max(np.abs(d_fe)))),
                "e_ke": signal_error(t, ke, against["t"], against["kinetic_energy"], t_stop, ke0),
                "e_p": signal_error(t, p, against["t"], against["pressure"][:, k], t_stop,
                                    float(np.max(np.abs(against["pressure"][:, k])))),
                "e_speed": signal_error(t, speed, against["t"], against["speed"][:, k], t_stop, v0)}

    fe_err = {k: errors(r["t"], r["kinetic_energy"], r["displacement"][:, a_main, 1], r["pressure"][:, a_main],
                        r["speed"][:, a_main], a_main, math.inf, ref) for k, r in fe.items() if k != ref_key}
    write_csv(os.path.join(out, "fe_errors.csv"), ["model", "element_side", "e_defl", "e_ke", "e_p", "e_speed"],
              [[k[0], k[1], *e.values()] for k, e in fe_err.items()])

    sr = series(sig, ("kinetic_energy", "deflection", "pressure_A", "speed_A"))
    err, err_rows = {}, []
    for r in runs:
        f, dx = r["formulation"], num(r["dx"])
        s = sr[(f, "load", dx)]
        k = points.index((num(r["x_A"]), num(r["y_A"])))
        args = (s["t"], s["kinetic_energy"], s["deflection"], s["pressure_A"], s["speed_A"], k, num(r["t_stop"]))
        e = errors(*args, ref)
        e["e_defl_svk"] = errors(*args, fe[fe_key("svk", FE_SVK_SPACING)])["e_defl"]
        for t in times:
            snap = snapshot(snaps, f, "load", dx, t) if dx == dx_main else None
            fe_snap = ref["snapshots"].get(t)
            e[f"e_x_{t:g}"] = (rms(np.linalg.norm(snap[2] - fe_snap[1], axis=1)) / dx
                               if snap is not None and fe_snap is not None else math.nan)
        err[(f, dx)] = e
        err_rows.append([f, r["dx"], r["status"], r["t_stop"], r["cpu_seconds"], *e.values()])
    write_csv(os.path.join(out, "errors.csv"), ["formulation", "dx", "status", "t_stop", "cpu_seconds"]
              + list(next(iter(err.values())).keys()), err_rows)

    order = order_series(read(os.path.join(out, "order.csv")))
    shape = {}
    for f in FORMS:
        s = sr[(f, "load", dx_main)]
        shape[f] = {"defl_min": float(s["deflection"].min()), "t_last": float(s["t"][-1]),
                    **order_summary(order[(f, "load", dx_main)])}
    write_csv(os.path.join(out, "shape.csv"), ["formulation"] + list(shape["sph"].keys()),
              [[f, *v.values()] for f, v in shape.items()])
    figures(out, summary, runs, sr, fe, ref_key, a_main, snaps, err, times, order)
    extend_summary(summary, runs, err, fe, fe_err, ref_key, a_main)
    statements(summary, runs, err, shape, times)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2, sort_keys=True)
        f.write("\n")


def figures(out, summary, runs, sr, fe, ref_key, a, snaps, err, times, order):
    dx = num(summary["snapshot_spacing"])
    fig, axes = plt.subplots(4, 1, figsize=(7, 11), sharex=True)
    for key, lab in ((ref_key, "fe-linear"), (fe_key("svk", FE_SVK_SPACING), "fe-svk")):
        r = fe[key]
        for ax, y in zip(axes, (r["displacement"][:, a, 1], r["kinetic_energy"], r["pressure"][:, a])):
            ax.plot(r["t"], y, color=COLOUR[lab], lw=1.6 if lab == "fe-linear" else 1.0, label=LABEL[lab])
    for f in FORMS:
        s = sr[(f, "load", dx)]
        for ax, y in zip(axes, (s["deflection"], s["kinetic_energy"], s["pressure_A"])):
            ax.plot(s["t"], y, color=COLOUR[f], lw=1.0, label=LABEL[f])
    axes[0].set_ylabel("y displacement at A (cm)")
    axes[1].set_ylabel("global kinetic energy")
    axes[2].set_ylabel("pressure at A (Mbar)")
    order_panel(axes[3], order, FORMS, dx, "load")
    axes[3].set_xlabel("t (us)")
    axes[1].set_ylim(0, 1.6 * 0.5 * 7.8 * num(summary["speed"]) ** 2 * num(summary["section"]) * num(summary["height"]))
    d = fe[ref_key]["displacement"][:, a, 1]
    axes[0].set_ylim(2 * d.min(), max(2 * d.max(), -0.5 * d.min()))
    axes[0].legend(fontsize=8, ncol=3)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"Clamped beam, transient load (dx = {dx:g} cm; Powell Fig. 4.14)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "signals.png"), dpi=90)
    plt.close(fig)
    for t in times:
        panels = []
        for f in FORMS:
            snap = snapshot(snaps, f, "load", dx, t)
            panels.append((LABEL[f], None if snap is None else (snap[0], snap[2], snap[3])))
        fs = fe[ref_key]["snapshots"].get(t)
        panels.append(("FE (linear)", fs))
        positions_figure(os.path.join(out, f"positions_{t:g}.png"),
                         f"Particle positions at t = {t:g} us (Powell Figs. 4.15-4.18)", panels, 0.3, (9, 1.8))
    pareto_figure(os.path.join(out, "pareto.png"), "Speed against error, clamped beam (x: the run stopped)", runs, FORMS,
                  lambda r: err[(r["formulation"], num(r["dx"]))]["e_defl"],
                  "e_defl: RMS deflection error / max |d_fe|")


def extend_summary(summary, runs, err, fe, fe_err, ref_key, a):
    dxs = sorted({num(r["dx"]) for r in runs})
    times = [float(t) for t in summary["snapshot_times"].split(", ")]
    lines = []
    for f in FORMS:
        for dx in dxs:
            r = next(q for q in runs if q["formulation"] == f and num(q["dx"]) == dx)
            e = err[(f, dx)]
            lines.append(f"| {LABEL[f]} | {dx:g} | {status_text(r)} | {num(r['cpu_seconds']):.2f} | {g(e['e_defl'])} | "
                         f"{g(e['e_ke'])} | {g(e['e_p'])} | {g(e['e_speed'])} | "
                         + " | ".join(g(e[f'e_x_{t:g}']) for t in times) + f" | {g(e['e_defl_svk'])} |")
    summary["table"] = "\n".join(lines)
    for key in ("e_defl", "e_ke"):
        e, r = best_per_error(runs, err, key)
        summary[f"best_{key}"] = f"{LABEL[r['formulation']]} at dx = {num(r['dx']):g}" if r else "none"
        summary[f"best_{key}_value"] = g(e)
    for f in FORMS:
        fr = [r for r in runs if r["formulation"] == f]
        failed = [r for r in fr if r["status"] != "completed"]
        key = f.replace("-", "_")
        summary[f"{key}_completed"] = f"{len(fr) - len(failed)} of {len(fr)}"
        summary[f"{key}_first_stop"] = first_stop(fr)
        summary[f"{key}_e_defl_finest"] = g(err[(f, dxs[0])]["e_defl"])
    for k, e in fe_err.items():
        for name, v in e.items():
            summary[f"fe_{k[0]}_{k[1]:g}_{name}".replace(".", "_")] = g(v)
    summary["fe_reference"] = f"linear, h_e = {FE_SPACINGS[-1]:g} cm"
    summary["fe_spacings"] = ", ".join(f"{h:g}" for h in FE_SPACINGS)
    summary["fe_svk_spacing"] = f"{FE_SVK_SPACING:g}"
    for k, r in fe.items():
        summary[f"fe_{k[0]}_{k[1]:g}_j_min".replace(".", "_")] = g(float(np.min(r["j_min"])))
    summary["fe_seconds"] = f"{sum(r['seconds'] for r in fe.values()):.0f}"
    d = fe[ref_key]["displacement"][:, a, 1]
    summary["fe_defl_min"] = g(float(d.min()))
    summary["fe_defl_end"] = g(float(d[-1]))


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
