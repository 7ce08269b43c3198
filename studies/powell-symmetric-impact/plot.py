#!/usr/bin/env python3
"""Post-processing of powell-symmetric-impact: the finite-element reference (fe_reference.py, DOLFINx), the errors of
every SPH run against it, and the figures. Usage: plot.py RESULTS_DIR (reads runs.csv, signals.csv, snapshots.csv and
summary.json; writes fe_runs.csv, fe_signals.csv, errors.csv, fe_errors.csv, signals_<case>.png,
positions_<case>.png, pareto_<case>.png and adds the FE and error keys to summary.json).

Error norms (README.md), each over the records t <= t_stop of the SPH run, FE interpolated linearly in time:
  e_ke     RMS_t (KE - KE_fe) / KE(0)
  e_p      RMS_t (p_A - p_fe(A)) / max_t |p_fe(A)|
  e_speed  RMS_t (|v_A| - |v_fe(A)|) / v0
  e_x      RMS over the particles of |x - x_fe(X)| / dx at the case's figure time (snapshot resolution only)
The FE reference is the linear model on the finest mesh; its own error is the same norms between the two finest
meshes (fe_errors.csv)."""
import json
import math
import os
import sys
from collections import defaultdict

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
sys.path.insert(0, HERE)
from impact_post import CLUMP, GAP, SHARE, clumped_share, first_stop, rms, verdict_summary, write_csv  # noqa: E402
from plot_common import num, plt, read  # noqa: E402

FORMS = ["sph", "ncsph", "ssph", "tl"]
LABEL = {"sph": "basic SPH", "ncsph": "NCSPH", "ssph": "S-SPH", "tl": "TL-SPH", "fe": "FE (linear)",
         "fe-svk": "FE (SVK)"}
COLOUR = {"sph": "tab:red", "ncsph": "tab:orange", "ssph": "tab:blue", "tl": "tab:green", "fe": "k",
          "fe-svk": "0.5"}
FE_MESHES = (100, 200, 400)  # elements per side of the 1 x 1 block (h_e 0.01, 0.005, 0.0025 cm)
FE_SVK_MESH = 200
RECORD_DT = 0.01  # us, FE record interval


def run_fe(summary, runs, snaps):
    from fe_reference import fe_run
    t_end, v0 = num(summary["t_end"]), num(summary["speed"])
    points = sorted({(num(r["x_A"]), num(r["y_A"])) for r in runs})
    snap_dx = num(summary["snapshot_spacing"])
    fe = {}
    for case, sign in (("compression", 1.0), ("expansion", -1.0)):
        rows = [r for r in snaps if r["case"] == case and r["formulation"] == "tl" and num(r["dx"]) == snap_dx]
        times = sorted({round(num(r["t"]), 6) for r in rows})
        first = [r for r in rows if round(num(r["t"]), 6) == times[0]] if times else []
        xs = np.array([[num(r["x0"]), num(r["y0"])] for r in first]) if first else None
        for model, meshes in (("linear", FE_MESHES), ("svk", (FE_SVK_MESH,))):
            for n in meshes:
                r = fe_run(n, sign * v0, t_end, points, xs, times, model=model, record_dt=RECORD_DT)
                fe[(model, n, case)] = r
                print(f"  FE {model} n = {n} {case}: {r['dofs']} dofs, {r['steps']} steps, {r['seconds']:.1f} s",
                      flush=True)
    return fe, points


def errors_against(ref, points, t, ke, p, speed, t_stop, v0, ke0):
    """The three signal norms of one SPH run against one FE run (point A = points index)."""
    m = t <= t_stop + 1e-12
    t, ke, p, speed = t[m], ke[m], p[m], speed[m]
    k = points
    ke_fe = np.interp(t, ref["t"], ref["kinetic_energy"])
    p_fe = np.interp(t, ref["t"], ref["pressure"][:, k])
    s_fe = np.interp(t, ref["t"], ref["speed"][:, k])
    return (rms(ke - ke_fe) / ke0, rms(p - p_fe) / np.max(np.abs(ref["pressure"][:, k])), rms(speed - s_fe) / v0)


def main(out):
    summary = json.load(open(os.path.join(out, "summary.json")))
    runs, sig, snaps = (read(os.path.join(out, f)) for f in ("runs.csv", "signals.csv", "snapshots.csv"))
    v0 = num(summary["speed"])
    fe, points = run_fe(summary, runs, snaps)
    finest = FE_MESHES[-1]
    cases = ("compression", "expansion")
    write_csv(os.path.join(out, "fe_runs.csv"), ["model", "elements_per_side", "case", "dofs", "steps", "dt", "seconds"],
              [[m, str(n), c, str(r["dofs"]), str(r["steps"]), r["dt"], r["seconds"]] for (m, n, c), r in fe.items()])
    fe_rows = []
    for (m, n, c), r in fe.items():
        if n == finest or m == "svk":
            for i in range(0, len(r["t"]), 2):
                fe_rows.append([m, str(n), c, r["t"][i], r["kinetic_energy"][i]]
                               + [r["pressure"][i, k] for k in range(len(points))]
                               + [r["speed"][i, k] for k in range(len(points))])
    write_csv(os.path.join(out, "fe_signals.csv"),
              ["model", "elements_per_side", "case", "t", "kinetic_energy"]
              + [f"pressure_at_{x:g}_{y:g}" for x, y in points] + [f"speed_at_{x:g}_{y:g}" for x, y in points], fe_rows)

    series = defaultdict(lambda: defaultdict(list))
    for r in sig:
        s = series[(r["formulation"], r["case"], num(r["dx"]))]
        for key in ("t", "kinetic_energy", "pressure_A", "speed_A"):
            s[key].append(num(r[key]))
    ke0 = 0.5 * 7.8 * v0 * v0  # 1/2 rho v0^2 over the 1 x 1 block

    # FE's own error: each mesh against the finest, at the main resolution's point A, over [0, t_end].
    main_dx = num(summary["snapshot_spacing"])
    a_main = next(points.index((num(r["x_A"]), num(r["y_A"]))) for r in runs if num(r["dx"]) == main_dx)
    fe_err_rows, fe_err = [], {}
    for c in cases:
        ref = fe[("linear", finest, c)]
        for m, n in [("linear", n) for n in FE_MESHES[:-1]] + [("svk", FE_SVK_MESH)]:
            r = fe[(m, n, c)]
            e = errors_against(ref, a_main, r["t"], r["kinetic_energy"], r["pressure"][:, a_main],
                               r["speed"][:, a_main], math.inf, v0, ke0)
            fe_err[(m, n, c)] = e
            fe_err_rows.append([m, str(n), c, *e])
    write_csv(os.path.join(out, "fe_errors.csv"), ["model", "elements_per_side", "case", "e_ke", "e_p", "e_speed"],
              fe_err_rows)

    err_rows, err = [], {}
    for r in runs:
        f, c, dx = r["formulation"], r["case"], num(r["dx"])
        s = {k: np.asarray(v) for k, v in series[(f, c, dx)].items()}
        k = points.index((num(r["x_A"]), num(r["y_A"])))
        t_stop = num(r["t_stop"])
        e = errors_against(fe[("linear", finest, c)], k, s["t"], s["kinetic_energy"], s["pressure_A"], s["speed_A"],
                           t_stop, v0, ke0)
        e_svk = errors_against(fe[("svk", FE_SVK_MESH, c)], k, s["t"], s["kinetic_energy"], s["pressure_A"],
                               s["speed_A"], t_stop, v0, ke0)
        e_x = math.nan
        if dx == main_dx:
            rows = [q for q in snaps if q["formulation"] == f and q["case"] == c and num(q["dx"]) == dx]
            times = sorted({round(num(q["t"]), 6) for q in rows})
            ref_snaps = fe[("linear", finest, c)]["snapshots"]
            if times and times[0] in ref_snaps:
                first = [q for q in rows if round(num(q["t"]), 6) == times[0]]
                x = np.array([[num(q["x"]), num(q["y"])] for q in first])
                e_x = rms(np.linalg.norm(x - ref_snaps[times[0]][1], axis=1)) / dx
        err[(f, c, dx)] = (*e, e_x, *e_svk)
        err_rows.append([f, c, r["dx"], r["status"], r["t_stop"], r["cpu_seconds"], *e, e_x, *e_svk])
    write_csv(os.path.join(out, "errors.csv"), ["formulation", "case", "dx", "status", "t_stop", "cpu_seconds", "e_ke",
                                                "e_p", "e_speed", "e_x", "e_ke_svk", "e_p_svk", "e_speed_svk"], err_rows)
    plots(out, summary, runs, series, fe, points, snaps, err)
    shape = shape_measures(summary, runs, series, fe, snaps)
    write_csv(os.path.join(out, "shape.csv"), ["formulation", "case", "t", "clumped_share", "half_gap_over_dx",
                                               "ke_late_mean", "ke_late_range"],
              [[f, c, *v] for (f, c), v in shape.items()])
    extend_summary(out, summary, runs, err, fe, fe_err)
    statements(summary, runs, err, shape)
    verdict_summary(out, summary)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2, sort_keys=True)
        f.write("\n")


def plots(out, summary, runs, series, fe, points, snaps, err):
    main_dx = num(summary["snapshot_spacing"])
    finest = FE_MESHES[-1]
    for c in ("compression", "expansion"):
        fig, axes = plt.subplots(3, 1, figsize=(7, 9), sharex=True)
        a = next(points.index((num(r["x_A"]), num(r["y_A"]))) for r in runs if num(r["dx"]) == main_dx)
        for key, model, n in (("fe", "linear", finest), ("fe-svk", "svk", FE_SVK_MESH)):
            r = fe[(model, n, c)]
            for ax, y in zip(axes, (r["kinetic_energy"], r["pressure"][:, a], r["speed"][:, a])):
                ax.plot(r["t"], y, color=COLOUR[key], lw=1.6 if key == "fe" else 1.0, label=LABEL[key])
        for f in FORMS:
            s = series[(f, c, main_dx)]
            for ax, key in zip(axes, ("kinetic_energy", "pressure_A", "speed_A")):
                ax.plot(s["t"], s[key], color=COLOUR[f], lw=1.0, label=LABEL[f])
        axes[0].set_ylabel("global kinetic energy")
        axes[1].set_ylabel("pressure at A (Mbar)")
        axes[2].set_ylabel("|v| at A (cm/us)")
        axes[2].set_xlabel("t (us)")
        axes[0].set_ylim(0, 1.6 * 0.5 * 7.8 * num(summary["speed"]) ** 2)
        axes[1].set_ylim(-0.4, 0.4)
        axes[2].set_ylim(0, 0.15)
        axes[0].legend(fontsize=8, ncol=3)
        for ax in axes:
            ax.grid(True, alpha=0.3)
        fig.suptitle(f"Symmetric impact, initial {c} (dx = {main_dx:g} cm; Powell Fig. {'4.7' if c == 'compression' else '4.9'})")
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"signals_{c}.png"), dpi=90)
        plt.close(fig)

        rows = [q for q in snaps if q["case"] == c and num(q["dx"]) == main_dx]
        times = sorted({round(num(q["t"]), 6) for q in rows if q["formulation"] == "tl"})
        if not times:
            continue
        panels = FORMS + ["fe"]
        fig, axes = plt.subplots(1, len(panels), figsize=(3.3 * len(panels), 3.6), sharex=True, sharey=True)
        for ax, f in zip(axes, panels):
            if f == "fe":
                snap = fe[("linear", finest, c)]["snapshots"].get(times[0])
                if snap is None:
                    continue
                x, p, t = snap[1], snap[2], snap[0]
            else:
                q = [r for r in rows if r["formulation"] == f]
                tf = sorted({num(r["t"]) for r in q})
                if not tf:
                    ax.set_title(f"{LABEL[f]}: stopped before t = {times[0]:g}", fontsize=8)
                    continue
                q = [r for r in q if num(r["t"]) == tf[0]]
                x = np.array([[num(r["x"]), num(r["y"])] for r in q])
                p, t = np.array([num(r["pressure"]) for r in q]), tf[0]
            sc = ax.scatter(x[:, 0], x[:, 1], c=p, s=2, cmap="coolwarm", vmin=-0.3, vmax=0.3)
            ax.set_title(f"{LABEL[f]}, t = {t:.2f} us", fontsize=9)
            ax.set_aspect("equal")
        fig.colorbar(sc, ax=axes, shrink=0.8, label="pressure (Mbar)")
        fig.suptitle(f"Particle positions, initial {c} (Powell Fig. {'4.6' if c == 'compression' else '4.8'})")
        fig.savefig(os.path.join(out, f"positions_{c}.png"), dpi=90)
        plt.close(fig)

        fig, ax = plt.subplots(figsize=(6.5, 4.8))
        for f in FORMS:
            pts = sorted((num(r["cpu_seconds"]), err[(f, c, num(r["dx"]))][0], r["status"] == "completed")
                         for r in runs if r["formulation"] == f and r["case"] == c)
            ax.loglog([q[0] for q in pts], [q[1] for q in pts], "-", color=COLOUR[f], lw=1, label=LABEL[f])
            for cpu, e, ok in pts:
                ax.loglog(cpu, e, "o" if ok else "x", color=COLOUR[f], mfc=COLOUR[f] if ok else "none", ms=6)
        ax.set_xlabel("CPU seconds (one thread)")
        ax.set_ylabel("e_ke: RMS kinetic-energy error / KE(0)")
        ax.set_title(f"Speed against error, initial {c} (x: the run stopped)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"pareto_{c}.png"), dpi=90)
        plt.close(fig)


def extend_summary(out, summary, runs, err, fe, fe_err):
    g = lambda v: "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.3g}"  # noqa: E731
    finest = FE_MESHES[-1]
    dxs = sorted({num(r["dx"]) for r in runs})
    for c in ("compression", "expansion"):
        lines = []
        for f in FORMS:
            for dx in dxs:
                r = next(q for q in runs if q["formulation"] == f and q["case"] == c and num(q["dx"]) == dx)
                e = err[(f, c, dx)]
                status = "completed" if r["status"] == "completed" else f"{r['status']} at t = {num(r['t_stop']):.2f}"
                lines.append(f"| {LABEL[f]} | {dx:g} | {status} | {num(r['cpu_seconds']):.2f} | {g(e[0])} | {g(e[1])} | "
                             f"{g(e[2])} | {g(e[3])} | {g(e[4])} |")
        summary[f"table_{c}"] = "\n".join(lines)
        # Least error per CPU second among completed runs: the run with the least e_ke per formulation, and overall.
        best = min(((err[(r["formulation"], c, num(r["dx"]))][0], r) for r in runs
                    if r["case"] == c and r["status"] == "completed"), key=lambda q: q[0])
        summary[f"{c}_best"] = f"{LABEL[best[1]['formulation']]} at dx = {num(best[1]['dx']):g}"
        summary[f"{c}_best_e_ke"] = g(best[0])
        for f in FORMS:
            fr = [r for r in runs if r["formulation"] == f and r["case"] == c]
            failed = [r for r in fr if r["status"] != "completed"]
            summary[f"{c}_{f}_completed"] = f"{len(fr) - len(failed)} of {len(fr)}"
            summary[f"{c}_{f}_first_stop"] = first_stop(fr)
            fine = max(num(r["dx"]) for r in fr if num(r["dx"]) == min(dxs))
            summary[f"{c}_{f}_e_ke_finest"] = g(err[(f, c, fine)][0])
        for (m, n, cc), e in fe_err.items():
            if cc == c:
                summary[f"fe_{c}_{m}{n}_e_ke"] = g(e[0])
                summary[f"fe_{c}_{m}{n}_e_p"] = g(e[1])
                summary[f"fe_{c}_{m}{n}_e_speed"] = g(e[2])
    summary["fe_finest"] = str(finest)
    summary["fe_meshes"] = ", ".join(str(n) for n in FE_MESHES)
    summary["fe_seconds"] = f"{sum(r['seconds'] for r in fe.values()):.0f}"


LATE, OSCILLATES = 2 / 3, 0.1  # thresholds of the statement table (README.md), with impact_post's


def half_gap(x, x0):
    """Gap between the halves: the lowest top-half particle's y minus the highest bottom-half particle's y."""
    top = x0[:, 1] > 0.5
    return float(x[top, 1].min() - x[~top, 1].max())


def late_ke(t, ke, t_end):
    """Mean and range (max - min) of KE over the last third of [0, t_end], NaN for a run that stopped before it."""
    t, ke = np.asarray(t), np.asarray(ke)
    m = t >= LATE * t_end
    if not m.any() or t[-1] < t_end - 1e-9:
        return math.nan, math.nan
    return float(ke[m].mean()), float(ke[m].max() - ke[m].min())


def shape_measures(summary, runs, series, fe, snaps):
    """Per formulation (and FE) and case at the snapshot resolution and the case's figure time: the share of clumped
    particles (nearest neighbour < CLUMP dx), the gap between the halves / dx (1 at the start), and the late KE mean and
    range / KE(0)."""
    dx = num(summary["snapshot_spacing"])
    t_end, v0 = num(summary["t_end"]), num(summary["speed"])
    ke0 = 0.5 * 7.8 * v0 * v0
    out = {}
    for c in ("compression", "expansion"):
        rows = [q for q in snaps if q["case"] == c and num(q["dx"]) == dx]
        fig_t = min((num(q["t"]) for q in rows if q["formulation"] == "tl"), default=math.nan)
        for f in FORMS:
            q = [r for r in rows if r["formulation"] == f and abs(num(r["t"]) - fig_t) < 1e-9]
            x = np.array([[num(r["x"]), num(r["y"])] for r in q])
            x0 = np.array([[num(r["x0"]), num(r["y0"])] for r in q])
            lo, hi = (clumped_share(x, dx), half_gap(x, x0) / dx) if q else (math.nan, math.nan)
            s = series[(f, c, dx)]
            mean, rng = late_ke(s["t"], s["kinetic_energy"], t_end)
            out[(f, c)] = [fig_t, lo, hi, mean / ke0, rng / ke0]
        r = fe[("linear", FE_MESHES[-1], c)]
        snap = r["snapshots"].get(round(fig_t, 6))
        x0 = np.array([[num(q["x0"]), num(q["y0"])] for q in rows if q["formulation"] == "tl"
                       and abs(num(q["t"]) - fig_t) < 1e-9])
        lo, hi = (clumped_share(snap[1], dx), half_gap(snap[1], x0) / dx) if snap is not None else (math.nan, math.nan)
        mean, rng = late_ke(r["t"], r["kinetic_energy"], t_end)
        out[("fe", c)] = [fig_t, lo, hi, mean / ke0, rng / ke0]
    return out


def statements(summary, runs, err, shape):
    """Powell's statements of §4.1 against the runs at the snapshot resolution: one table row each."""
    dx = num(summary["snapshot_spacing"])
    e = {f: {c: err[(f, c, dx)][0] for c in ("compression", "expansion")} for f in FORMS}
    done = {(r["formulation"], r["case"]): r["status"] == "completed" for r in runs if num(r["dx"]) == dx}
    stop = {(r["formulation"], r["case"]): f"{r['status']} at t = {num(r['t_stop']):.2f} us" for r in runs
            if num(r["dx"]) == dx}

    def ordered(f, c):
        v = shape[(f, c)]
        return done[(f, c)] and v[1] <= SHARE and v[2] <= GAP

    def disordered(f, c):
        return not ordered(f, c)

    def oscillates(f, c):
        return shape[(f, c)][4] >= OSCILLATES

    def g(v):
        return "-" if math.isnan(v) else f"{v:.3g}"

    def nn(f, c):
        v = shape[(f, c)]
        return (f"clumped {100 * v[1]:.2g} %, half gap {g(v[2])} dx"
                + ("" if done.get((f, c), True) else f", {stop[(f, c)]}"))

    c, x = "compression", "expansion"
    rows = [
        ("4.1.1", "TL-SPH and S-SPH are more closely aligned with FE than basic SPH or NCSPH",
         max(e["tl"][c], e["ssph"][c]) < min(e["sph"][c], e["ncsph"][c]),
         f"e_ke: TL {g(e['tl'][c])}, S-SPH {g(e['ssph'][c])}, SPH {g(e['sph'][c])}, NCSPH {g(e['ncsph'][c])}"),
        ("4.1.1", "basic SPH: particle clumping and the beginnings of numerical fracture", disordered("sph", c),
         nn("sph", c)),
        ("4.1.1", "NCSPH, to a lesser degree, the beginnings of numerical fracture",
         disordered("ncsph", c) and done[("ncsph", c)], nn("ncsph", c)),
        ("4.1.1", "S-SPH remains stable", ordered("ssph", c), nn("ssph", c)),
        ("4.1.2", "basic SPH fails completely; its KE reaches a relatively steady state as the halves separate",
         done[("sph", x)] and not oscillates("sph", x) and shape[("sph", x)][2] > GAP,
         f"late KE range {g(shape[('sph', x)][4])} KE0, " + nn("sph", x)),
        ("4.1.2", "NCSPH fails completely", disordered("ncsph", x), nn("ncsph", x)),
        ("4.1.2", "FE, TL-SPH and S-SPH continue to oscillate",
         all(oscillates(f, x) for f in ("fe", "tl", "ssph")),
         "late KE range: " + ", ".join(f"{LABEL[f]} {g(shape[(f, x)][4])} KE0" for f in ("fe", "tl", "ssph"))),
        ("4.1.2", "close correspondence between TL-SPH and S-SPH, agreeing in outline with FE", ordered("ssph", x) and
         e["ssph"][x] < min(e["sph"][x], e["ncsph"][x]),
         f"e_ke: S-SPH {g(e['ssph'][x])}, TL {g(e['tl'][x])}, SPH {g(e['sph'][x])}; " + nn("ssph", x)),
    ]
    summary["statements_table"] = "\n".join(f"| §{s} | {text} | {'yes' if ok else '**no**'} | {ev} |"
                                             for s, text, ok, ev in rows)
    summary["statements_holding"] = f"{sum(ok for _, _, ok, _ in rows)} of {len(rows)}"
    summary["clump"], summary["gap"], summary["oscillates"] = str(CLUMP), str(GAP), str(OSCILLATES)
    summary["clumped_share"] = f"{100 * SHARE:g} %"


if __name__ == "__main__":
    main(sys.argv[1])
