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
import impact_fe  # noqa: E402
from impact_post import (COLOUR, GAP, LABEL, SHARE, CLUMP, best_per_error, g, order_panel, order_series,  # noqa: E402
                         order_summary, pareto_figure, positions_figure, pct, rms, series, signal_error, snapshot,
                         first_stop, status_text, write_csv)
from plot_common import num, plt, read  # noqa: E402

FORMS = ["sph", "ncsph", "ssph", "tl"]
FE_SPACINGS = (0.02, 0.01, 0.005)  # element sides h_e (cm): 200 x 20, 400 x 40, 800 x 80 elements
FE_SVK_SPACING = 0.01
RECORD_DT = 0.05  # us, FE record interval
EARLY = 20.0  # us: Powell's "slight deviation from the TL-SPH solution, showing up after 20 us"
ONSET = (15.0, 25.0)  # us: "particle re-organisation which develops slowly from around that time" (20 us, +- 5)


def fe_key(model, he):
    return (model, he)


def run_fe(summary, runs, snaps):
    L, H, split, v0 = (num(summary[k]) for k in ("length", "height", "split", "speed"))
    t_end, dx = num(summary["t_end"]), num(summary["snapshot_spacing"])
    points = sorted({(num(r["x_A"]), num(r["y_A"])) for r in runs})
    times = [float(t) for t in summary["snapshot_times"].split(", ")]
    first = snapshot(snaps, "tl", "impact", dx, times[0])
    xs = first[1] if first else None

    def velocity(X):
        w = np.zeros_like(X)
        w[:, 0] = np.where(X[:, 0] < split * L, v0, -v0)  # the left part moves right, into the rest
        return w
    fe = {}
    for model, spacings in (("linear", FE_SPACINGS), ("svk", (FE_SVK_SPACING,))):
        for he in spacings:
            r = impact_fe.fe_run(round(L / he), round(H / he), t_end, velocity, points, (0, 0), (L, H), xs, times,
                                 model=model, record_dt=RECORD_DT)
            fe[fe_key(model, he)] = r
            print(f"  FE {model} h_e = {he:g}: {r['dofs']} dofs, {r['steps']} steps, {r['seconds']:.1f} s", flush=True)
    return fe, points


def main(out):
    summary = json.load(open(os.path.join(out, "summary.json")))
    runs, sig, snaps = (read(os.path.join(out, f)) for f in ("runs.csv", "signals.csv", "snapshots.csv"))
    L, H, v0, t_end = (num(summary[k]) for k in ("length", "height", "speed", "t_end"))
    dx_main = num(summary["snapshot_spacing"])
    times = [float(t) for t in summary["snapshot_times"].split(", ")]
    fe, points = run_fe(summary, runs, snaps)
    ref_key = fe_key("linear", FE_SPACINGS[-1])
    ref = fe[ref_key]
    ke0 = 0.5 * 7.8 * v0 * v0 * L * H
    dl = lambda r: r["length"] - r["length"][0]  # noqa: E731
    write_csv(os.path.join(out, "fe_runs.csv"), ["model", "element_side", "dofs", "steps", "dt", "seconds"],
              [[k[0], k[1], str(r["dofs"]), str(r["steps"]), r["dt"], r["seconds"]]
               for k, r in fe.items()])
    write_csv(os.path.join(out, "fe_signals.csv"), ["model", "element_side", "t", "kinetic_energy", "length"]
              + [f"pressure_at_{x:g}_{y:g}" for x, y in points] + [f"speed_at_{x:g}_{y:g}" for x, y in points],
              [[k[0], k[1], r["t"][i], r["kinetic_energy"][i], r["length"][i]]
               + list(r["pressure"][i]) + list(r["speed"][i])
               for k, r in fe.items() if k in (ref_key, fe_key("svk", FE_SVK_SPACING)) for i in range(len(r["t"]))])

    a_main = next(points.index((num(r["x_A"]), num(r["y_A"]))) for r in runs if num(r["dx"]) == dx_main)

    def errors(t, ke, length, p, speed, k, t_stop, against):
        scale_l = float(np.max(np.abs(dl(against))))
        return {"e_len": signal_error(t, length - length[0], against["t"], dl(against), t_stop, scale_l),
                "e_ke": signal_error(t, ke, against["t"], against["kinetic_energy"], t_stop, ke0),
                "e_p": signal_error(t, p, against["t"], against["pressure"][:, k], t_stop,
                                    float(np.max(np.abs(against["pressure"][:, k])))),
                "e_speed": signal_error(t, speed, against["t"], against["speed"][:, k], t_stop, v0)}

    fe_err = {k: errors(r["t"], r["kinetic_energy"], r["length"], r["pressure"][:, a_main], r["speed"][:, a_main],
                        a_main, math.inf, ref) for k, r in fe.items() if k != ref_key}
    write_csv(os.path.join(out, "fe_errors.csv"), ["model", "element_side", "e_len", "e_ke", "e_p", "e_speed"],
              [[k[0], k[1], *e.values()] for k, e in fe_err.items()])

    sr = series(sig, ("kinetic_energy", "length", "pressure_A", "speed_A"))
    err, err_rows = {}, []
    for r in runs:
        f, dx = r["formulation"], num(r["dx"])
        s = sr[(f, "impact", dx)]
        k = points.index((num(r["x_A"]), num(r["y_A"])))
        args = (s["t"], s["kinetic_energy"], s["length"], s["pressure_A"], s["speed_A"], k, num(r["t_stop"]))
        e = errors(*args, ref)
        e["e_len_svk"] = errors(*args, fe[fe_key("svk", FE_SVK_SPACING)])["e_len"]
        for t in times:
            snap = snapshot(snaps, f, "impact", dx, t) if dx == dx_main else None
            fe_snap = ref["snapshots"].get(t)
            e[f"e_x_{t:g}"] = (rms(np.linalg.norm(snap[2] - fe_snap[1], axis=1)) / dx
                               if snap is not None and fe_snap is not None else math.nan)
        err[(f, dx)] = e
        err_rows.append([f, r["dx"], r["status"], r["t_stop"], r["cpu_seconds"], *e.values()])
    write_csv(os.path.join(out, "errors.csv"), ["formulation", "dx", "status", "t_stop", "cpu_seconds"]
              + list(next(iter(err.values())).keys()), err_rows)

    # Particle order (order.csv) and the length change at the snapshot resolution.
    order = order_series(read(os.path.join(out, "order.csv")))
    shape = {}
    tl = sr[("tl", "impact", dx_main)]
    scale = float(np.max(np.abs(tl["length"] - tl["length"][0])))
    for f in FORMS:
        s = sr[(f, "impact", dx_main)]
        row = {"dl_end": float(s["length"][-1] - s["length"][0]), "t_last": float(s["t"][-1])}
        row.update(order_summary(order[(f, "impact", dx_main)]))
        for name, m in (("dev_early", s["t"] <= EARLY), ("dev_late", s["t"] > EARLY)):
            d = s["length"][m] - s["length"][0] - np.interp(s["t"][m], tl["t"], tl["length"] - tl["length"][0])
            row[name] = rms(d) / scale if m.any() else math.nan
        shape[f] = row
    write_csv(os.path.join(out, "shape.csv"), ["formulation"] + list(shape["sph"].keys()),
              [[f, *v.values()] for f, v in shape.items()])
    figures(out, summary, runs, sr, fe, ref_key, points, a_main, snaps, err, times, order)
    extend_summary(summary, runs, err, fe, fe_err, ref_key, shape, times)
    statements(summary, runs, err, fe, ref_key, shape, times)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2, sort_keys=True)
        f.write("\n")


def figures(out, summary, runs, sr, fe, ref_key, points, a, snaps, err, times, order):
    dx = num(summary["snapshot_spacing"])
    fig, axes = plt.subplots(4, 1, figsize=(7, 11), sharex=True)
    for key, lab in ((ref_key, "fe-linear"), (fe_key("svk", FE_SVK_SPACING), "fe-svk")):
        r = fe[key]
        for ax, y in zip(axes, (r["length"] - r["length"][0], r["kinetic_energy"], r["pressure"][:, a])):
            ax.plot(r["t"], y, color=COLOUR[lab], lw=1.6 if lab == "fe-linear" else 1.0, label=LABEL[lab])
    for f in FORMS:
        s = sr[(f, "impact", dx)]
        for ax, y in zip(axes, (s["length"] - s["length"][0], s["kinetic_energy"], s["pressure_A"])):
            ax.plot(s["t"], y, color=COLOUR[f], lw=1.0, label=LABEL[f])
    axes[0].set_ylabel("length change (cm)")
    axes[1].set_ylabel("global kinetic energy")
    axes[2].set_ylabel("pressure at A (Mbar)")
    order_panel(axes[3], order, FORMS, dx, "impact")
    axes[3].set_xlabel("t (us)")
    axes[1].set_ylim(0, 1.6 * 0.5 * 7.8 * num(summary["speed"]) ** 2 * num(summary["length"]) * num(summary["height"]))
    fe_dl = fe[ref_key]["length"] - fe[ref_key]["length"][0]
    axes[0].set_ylim(1.5 * fe_dl.min(), max(4 * fe_dl.max(), 0.1))
    axes[0].legend(fontsize=8, ncol=3)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"Asymmetrical bar impact (dx = {dx:g} cm; Powell Fig. 4.11)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "signals.png"), dpi=90)
    plt.close(fig)
    for t in times:
        panels = []
        for f in FORMS:
            snap = snapshot(snaps, f, "impact", dx, t)
            panels.append((LABEL[f], None if snap is None else (snap[0], snap[2], snap[3])))
        fs = fe[ref_key]["snapshots"].get(t)
        panels.append(("FE (linear)", None if fs is None else fs))
        positions_figure(os.path.join(out, f"positions_{t:g}.png"),
                         f"Particle positions at t = {t:g} us (Powell Fig. 4.12)", panels, 0.3, (9, 1.6))
    pareto_figure(os.path.join(out, "pareto.png"), "Speed against error, bar impact (x: the run stopped)", runs, FORMS,
                  lambda r: err[(r["formulation"], num(r["dx"]))]["e_len"],
                  "e_len: RMS length-change error / max |dL_fe|")


def extend_summary(summary, runs, err, fe, fe_err, ref_key, shape, times):
    dxs = sorted({num(r["dx"]) for r in runs})
    lines = []
    for f in FORMS:
        for dx in dxs:
            r = next(q for q in runs if q["formulation"] == f and num(q["dx"]) == dx)
            e = err[(f, dx)]
            lines.append(f"| {LABEL[f]} | {dx:g} | {status_text(r)} | {num(r['cpu_seconds']):.2f} | {g(e['e_len'])} | "
                         f"{g(e['e_ke'])} | {g(e['e_p'])} | {g(e['e_speed'])} | "
                         + " | ".join(g(e[f'e_x_{t:g}']) for t in times) + f" | {g(e['e_len_svk'])} |")
    summary["table"] = "\n".join(lines)
    for key in ("e_len", "e_ke"):
        e, r = best_per_error(runs, err, key)
        summary[f"best_{key}"] = f"{LABEL[r['formulation']]} at dx = {num(r['dx']):g}" if r else "none"
        summary[f"best_{key}_value"] = g(e)
    for f in FORMS:
        fr = [r for r in runs if r["formulation"] == f]
        failed = [r for r in fr if r["status"] != "completed"]
        summary[f"{f}_completed"] = f"{len(fr) - len(failed)} of {len(fr)}"
        summary[f"{f}_first_stop"] = first_stop(fr)
        summary[f"{f}_e_len_finest"] = g(err[(f, dxs[0])]["e_len"])
    for k, e in fe_err.items():
        for name, v in e.items():
            summary[f"fe_{k[0]}_{k[1]:g}_{name}".replace(".", "_")] = g(v)
    summary["fe_reference"] = f"linear, h_e = {FE_SPACINGS[-1]:g} cm"
    summary["fe_spacings"] = ", ".join(f"{h:g}" for h in FE_SPACINGS)
    summary["fe_svk_spacing"] = f"{FE_SVK_SPACING:g}"
    for k, r in fe.items():
        summary[f"fe_{k[0]}_{k[1]:g}_j_min".replace(".", "_")] = g(float(np.min(r["j_min"])))
    summary["fe_seconds"] = f"{sum(r['seconds'] for r in fe.values()):.0f}"
    summary["fe_dl_max"] = g(float(np.max(fe[ref_key]["length"] - fe[ref_key]["length"][0])))
    summary["fe_dl_min"] = g(float(np.min(fe[ref_key]["length"] - fe[ref_key]["length"][0])))


def statements(summary, runs, err, fe, ref_key, shape, times):
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
