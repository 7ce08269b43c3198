"""Shared post-processing of Powell's impact studies (powell-bar-impact, powell-clamped-beam): reading the driver's CSVs
(common/impact.hpp), errors of a signal against the FE reference (impact_fe.py), the particle-order measures of the
statement tables, and the figures (signals, particle positions coloured by pressure, speed against error)."""
import json
import math
import os
from collections import defaultdict

import numpy as np

from plot_common import num, plt, read

LABEL = {"sph": "basic SPH", "ncsph": "NCSPH", "ssph": "S-SPH", "ssph-g": "S-SPH (means of G)", "tl": "TL-SPH",
         "tl-svk": "TL-SPH (SVK)", "fe": "FE", "fe-linear": "FE (linear)", "fe-svk": "FE (SVK)"}
COLOUR = {"sph": "tab:red", "ncsph": "tab:orange", "ssph": "tab:blue", "ssph-g": "tab:purple", "tl": "tab:green",
          "tl-svk": "tab:olive", "fe": "k", "fe-linear": "0.5", "fe-svk": "k"}
CLUMP, SHARE, GAP = 0.5, 0.01, 2.0  # thresholds of the statement tables (README.md of each study)


def write_csv(path, header, rows):
    with open(path, "w") as f:
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(x if isinstance(x, str) else f"{x:.10g}" for x in r) + "\n")


def rms(x):
    x = np.asarray(x)
    return float(np.sqrt(np.mean(x * x))) if len(x) else math.nan


def g(v):
    """A number for a table: 3 significant digits, '-' for None or NaN."""
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:.3g}"


def pct(share):
    """A share as a percentage for a table, '-' for NaN (a run that stopped before the snapshot)."""
    return "-" if math.isnan(share) else f"{100 * share:.2g} %"


def series(signals, keys):
    """{(formulation, case, dx): {key: np.array}} from signals.csv rows."""
    s = defaultdict(lambda: defaultdict(list))
    for r in signals:
        d = s[(r["formulation"], r["case"], num(r["dx"]))]
        for k in ("t",) + tuple(keys):
            d[k].append(num(r[k]))
    return {k: {kk: np.asarray(vv) for kk, vv in v.items()} for k, v in s.items()}


def order_series(rows):
    """{(formulation, case, dx): {t, clumped_share, fragments, largest_fragment_share: np.array}} from order.csv."""
    return series(rows, ("clumped_share", "fragments", "largest_fragment_share"))


def order_summary(o, share=SHARE):
    """Of one run's order series: the largest clumped share, the first time it exceeds `share` (NaN: never), the
    largest fragment count and the last record's clumped share and fragments."""
    above = np.nonzero(o["clumped_share"] > share)[0]
    return {"clumped_max": float(o["clumped_share"].max()),
            "clump_onset": float(o["t"][above[0]]) if len(above) else math.nan,
            "fragments_max": int(o["fragments"].max()),
            "clumped_end": float(o["clumped_share"][-1]), "fragments_end": int(o["fragments"][-1]),
            "t_end": float(o["t"][-1])}


def order_panel(ax, order, forms, dx, case):
    """Clumped share (%) against time per formulation (the run's order.csv)."""
    for f in forms:
        o = order.get((f, case, dx))
        if o is not None:
            ax.plot(o["t"], 100 * o["clumped_share"], color=COLOUR[f], lw=1.0, label=LABEL[f])
    ax.set_ylabel(f"clumped (% with a neighbour < {CLUMP:g} dx)")


def signal_error(t, y, t_ref, y_ref, t_stop, scale):
    """RMS over the records t <= t_stop of y - y_ref (interpolated linearly in time), divided by scale."""
    t, y = np.asarray(t), np.asarray(y)
    m = t <= t_stop + 1e-12
    return rms(y[m] - np.interp(t[m], t_ref, y_ref)) / scale


def clumped_share(x, dx):
    """Share of the particles whose nearest neighbour is closer than CLUMP dx."""
    from scipy.spatial import cKDTree
    d, _ = cKDTree(x).query(x, k=2)
    return float(np.mean(d[:, 1] < CLUMP * dx))


def snapshot(snaps, form, case, dx, t):
    """(t, x0 (n x 2), x (n x 2), p (n)) of a run's snapshot nearest t (within 1e-6), or None."""
    rows = [q for q in snaps if q["formulation"] == form and q["case"] == case and num(q["dx"]) == dx
            and abs(num(q["t"]) - t) < 0.5]
    if not rows:
        return None
    tt = min({num(q["t"]) for q in rows}, key=lambda v: abs(v - t))
    rows = [q for q in rows if num(q["t"]) == tt]
    arr = lambda *k: np.array([[num(q[c]) for c in k] for q in rows])  # noqa: E731
    return tt, arr("x0", "y0"), arr("x", "y"), arr("pressure")[:, 0]


def positions_figure(path, title, panels, pmax, aspect_box):
    """One row per panel (label, (t, x, p) or None); particles coloured by pressure in [-pmax, pmax]. Every panel
    shows the same window, the bounding box of all the panels' particles (a run that flew apart widens it)."""
    shown = [snap for _, snap in panels if snap is not None]
    lo = np.min([snap[1].min(axis=0) for snap in shown], axis=0) if shown else np.zeros(2)
    hi = np.max([snap[1].max(axis=0) for snap in shown], axis=0) if shown else np.ones(2)
    pad = 0.05 * max(hi - lo)
    ncols = 2 if len(panels) > 3 else 1
    nrows = (len(panels) + ncols - 1) // ncols
    width = aspect_box[0] / ncols  # inches per panel
    aspect = (hi[1] - lo[1] + 2 * pad) / (hi[0] - lo[0] + 2 * pad)
    height = min(max(width * aspect, aspect_box[1]), 2 * width) + 0.5
    fig, axes = plt.subplots(nrows, ncols, figsize=(aspect_box[0] + 1.2, height * nrows), squeeze=False)
    for ax in axes.flat[len(panels):]:
        ax.set_axis_off()
    sc = None
    for ax, (label, snap) in zip(axes.flat, panels):
        if snap is None:
            ax.set_axis_off()
            ax.set_title(f"{label}: stopped before this time", fontsize=8)
            continue
        t, x, p = snap
        sc = ax.scatter(x[:, 0], x[:, 1], c=p, s=1, cmap="coolwarm", vmin=-pmax, vmax=pmax)
        ax.set_title(f"{label}, t = {t:.2f} us", fontsize=8)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
    if sc is not None:
        fig.colorbar(sc, ax=axes.ravel().tolist(), shrink=0.8, label="pressure (Mbar)")
    fig.suptitle(title)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def pareto_figure(path, title, runs, forms, error, ylabel):
    """Error against CPU seconds per formulation; error(run row) -> value; x marks a run that stopped."""
    fig, ax = plt.subplots(figsize=(6.5, 4.8))
    for f in forms:
        pts = sorted((num(r["cpu_seconds"]), error(r), r["status"] == "completed") for r in runs if r["formulation"] == f)
        pts = [q for q in pts if not math.isnan(q[1])]
        if not pts:
            continue
        ax.loglog([q[0] for q in pts], [q[1] for q in pts], "-", color=COLOUR[f], lw=1, label=LABEL[f])
        for cpu, e, ok in pts:
            ax.loglog(cpu, e, "o" if ok else "x", color=COLOUR[f], mfc=COLOUR[f] if ok else "none", ms=6)
    ax.set_xlabel("CPU seconds (one thread)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def best_per_error(runs, err, key):
    """The completed run with the least error `key` (err[(form, dx)][key]): (error, run row)."""
    done = [(err[(r["formulation"], num(r["dx"]))][key], r) for r in runs if r["status"] == "completed"]
    done = [q for q in done if not math.isnan(q[0])]
    return min(done, key=lambda q: q[0]) if done else (math.nan, None)


def first_stop(rows):
    """'<status> at t = <t> us' of the run among `rows` that stopped first, 'none' when every run completed."""
    failed = [r for r in rows if r["status"] != "completed"]
    if not failed:
        return "none"
    r = min(failed, key=lambda q: num(q["t_stop"]))
    return f"{r['status']} at t = {num(r['t_stop']):.2f} us"


def pareto_front(runs, err, key):
    """The completed runs no other completed run beats in both CPU seconds and error `key`, cheapest first, as
    'label dx (CPU s, error)' text: the fastest formulation for each attainable error."""
    pts = sorted(((num(r["cpu_seconds"]), err[(r["formulation"], num(r["dx"]))][key], r) for r in runs
                  if r["status"] == "completed"), key=lambda q: (q[0], q[1]))
    front, best = [], math.inf
    for cpu, e, r in pts:
        if e < best:
            front.append(f"{LABEL[r['formulation']]} dx {num(r['dx']):g} ({cpu:.2g} s, {e:.3g})")
            best = e
    return "; ".join(front) if front else "none"


def status_text(r):
    return "completed" if r["status"] == "completed" else f"{r['status']} at t = {num(r['t_stop']):.2f}"


def fe_own_errors(fe, finest_key, others, signal):
    """Each FE run in `others` against fe[finest_key] over the whole run: {key: RMS error of signal(run)} with the
    scale max |signal(finest)|."""
    ref = fe[finest_key]
    y_ref = signal(ref)
    scale = float(np.max(np.abs(y_ref)))
    return {k: signal_error(fe[k]["t"], signal(fe[k]), ref["t"], y_ref, math.inf, scale) for k in others}


def summary_path(out):
    return os.path.join(out, "summary.json")


# ---- The evaluation shared by the bar and beam studies: FE runs, errors, tables, figures -------------------------

FE_SPACINGS = (0.02, 0.01, 0.005)  # element sides h_e (cm) of the linear runs; the finest is the reference
FE_SVK_SPACING = 0.01  # the Saint Venant-Kirchhoff run (the model sensitivity)
RECORD_DT = 0.05  # us, FE record interval


class Problem:
    """What differs between the impact studies' evaluations: the case name, the formulations, the headline signal
    (name e.g. 'len', its SPH series and its FE series at point k) and the FE set-up (initial velocity, clamp)."""

    def __init__(self, case, forms, head, head_text, sph_head, fe_head, velocity, clamp=None):
        self.case, self.forms, self.head, self.head_text = case, forms, head, head_text
        self.sph_head, self.fe_head, self.velocity, self.clamp = sph_head, fe_head, velocity, clamp


def _times(summary):
    return [float(t) for t in summary["snapshot_times"].split(", ")]


def run_fe(problem, summary, runs, snaps):
    """The linear runs on FE_SPACINGS and the SVK run on FE_SVK_SPACING of the body length x height, with A of every
    resolution as the points and the TL run's particles as snapshot points. Returns ({(model, h_e): run}, points)."""
    import impact_fe
    L, H, t_end = (num(summary[k]) for k in ("length", "height", "t_end"))
    points = sorted({(num(r["x_A"]), num(r["y_A"])) for r in runs})
    times = _times(summary)
    first = snapshot(snaps, "tl", problem.case, num(summary["snapshot_spacing"]), times[0])
    fe = {}
    for model, spacings in (("linear", FE_SPACINGS), ("svk", (FE_SVK_SPACING,))):
        for he in spacings:
            r = impact_fe.fe_run(round(L / he), round(H / he), t_end, problem.velocity, points, (0, 0), (L, H),
                                 first[1] if first else None, times, model=model, clamp=problem.clamp,
                                 record_dt=RECORD_DT)
            fe[(model, he)] = r
            print(f"  FE {model} h_e = {he:g}: {r['dofs']} dofs, {r['steps']} steps, {r['seconds']:.1f} s", flush=True)
    return fe, points


def evaluate(problem, out, summary, ke0):
    """Runs FE, then the errors of every SPH run and of the coarser FE runs against the reference; writes fe_runs.csv,
    fe_signals.csv, fe_errors.csv and errors.csv. Returns the context the figures and summaries use."""
    runs, sig, snaps = (read(os.path.join(out, f)) for f in ("runs.csv", "signals.csv", "snapshots.csv"))
    v0, dx_main, times = num(summary["speed"]), num(summary["snapshot_spacing"]), _times(summary)
    fe, points = run_fe(problem, summary, runs, snaps)
    ref_key, svk_key = ("linear", FE_SPACINGS[-1]), ("svk", FE_SVK_SPACING)
    ref = fe[ref_key]
    write_csv(os.path.join(out, "fe_runs.csv"), ["model", "element_side", "dofs", "steps", "dt", "seconds", "j_min"],
              [[k[0], k[1], str(r["dofs"]), str(r["steps"]), r["dt"], r["seconds"], float(np.min(r["j_min"]))]
               for k, r in fe.items()])
    write_csv(os.path.join(out, "fe_signals.csv"), ["model", "element_side", "t", "kinetic_energy", "length"]
              + [f"{q}_at_{x:g}_{y:g}" for q in ("deflection", "pressure", "speed") for x, y in points],
              [[k[0], k[1], r["t"][i], r["kinetic_energy"][i], r["length"][i]] + list(r["displacement"][i, :, 1])
               + list(r["pressure"][i]) + list(r["speed"][i])
               for k, r in fe.items() if k in (ref_key, svk_key) for i in range(len(r["t"]))])
    a_main = next(points.index((num(r["x_A"]), num(r["y_A"]))) for r in runs if num(r["dx"]) == dx_main)
    e_head = f"e_{problem.head}"

    def errors(t, ke, head, p, speed, k, t_stop, against):
        h_fe = problem.fe_head(against, k)
        return {e_head: signal_error(t, head, against["t"], h_fe, t_stop, float(np.max(np.abs(h_fe)))),
                "e_ke": signal_error(t, ke, against["t"], against["kinetic_energy"], t_stop, ke0),
                "e_p": signal_error(t, p, against["t"], against["pressure"][:, k], t_stop,
                                    float(np.max(np.abs(against["pressure"][:, k])))),
                "e_speed": signal_error(t, speed, against["t"], against["speed"][:, k], t_stop, v0)}

    fe_err = {k: errors(r["t"], r["kinetic_energy"], problem.fe_head(r, a_main), r["pressure"][:, a_main],
                        r["speed"][:, a_main], a_main, math.inf, ref) for k, r in fe.items() if k != ref_key}
    write_csv(os.path.join(out, "fe_errors.csv"), ["model", "element_side", e_head, "e_ke", "e_p", "e_speed"],
              [[k[0], k[1], *e.values()] for k, e in fe_err.items()])
    sr = series(sig, [c for c in sig[0].keys() if c not in ("formulation", "case", "dx", "t")])
    err, rows = {}, []
    for r in runs:
        f, dx = r["formulation"], num(r["dx"])
        s = sr[(f, problem.case, dx)]
        k = points.index((num(r["x_A"]), num(r["y_A"])))
        args = (s["t"], s["kinetic_energy"], problem.sph_head(s), s["pressure_A"], s["speed_A"], k, num(r["t_stop"]))
        e = errors(*args, ref)
        e[f"{e_head}_svk"] = errors(*args, fe[svk_key])[e_head]
        for t in times:
            snap = snapshot(snaps, f, problem.case, dx, t) if dx == dx_main else None
            fe_snap = ref["snapshots"].get(t)
            e[f"e_x_{t:g}"] = (rms(np.linalg.norm(snap[2] - fe_snap[1], axis=1)) / dx
                               if snap is not None and fe_snap is not None else math.nan)
        err[(f, dx)] = e
        rows.append([f, r["dx"], r["status"], r["t_stop"], r["cpu_seconds"], *e.values()])
    write_csv(os.path.join(out, "errors.csv"), ["formulation", "dx", "status", "t_stop", "cpu_seconds"]
              + list(next(iter(err.values())).keys()), rows)
    order = order_series(read(os.path.join(out, "order.csv")))
    return {"runs": runs, "snaps": snaps, "fe": fe, "points": points, "ref_key": ref_key, "svk_key": svk_key,
            "a": a_main, "sr": sr, "err": err, "fe_err": fe_err, "times": times, "dx": dx_main, "order": order}


def common_summary(problem, ctx, summary):
    """The run table, the least-error runs, completion and first stops per formulation, FE's own errors and det F."""
    runs, err, fe, times, e_head = ctx["runs"], ctx["err"], ctx["fe"], ctx["times"], f"e_{problem.head}"
    dxs = sorted({num(r["dx"]) for r in runs})
    lines = []
    for f in problem.forms:
        for dx in dxs:
            r = next(q for q in runs if q["formulation"] == f and num(q["dx"]) == dx)
            e = err[(f, dx)]
            lines.append(f"| {LABEL[f]} | {dx:g} | {status_text(r)} | {num(r['cpu_seconds']):.2f} | {g(e[e_head])} | "
                         f"{g(e['e_ke'])} | {g(e['e_p'])} | {g(e['e_speed'])} | "
                         + " | ".join(g(e[f'e_x_{t:g}']) for t in times) + f" | {g(e[e_head + '_svk'])} |")
    summary["table"] = "\n".join(lines)
    for key in (e_head, "e_ke"):
        e, r = best_per_error(runs, err, key)
        summary[f"best_{key}"] = f"{LABEL[r['formulation']]} at dx = {num(r['dx']):g}" if r else "none"
        summary[f"best_{key}_value"] = g(e)
    summary["pareto_front"] = pareto_front(runs, err, e_head)
    for f in problem.forms:
        fr = [r for r in runs if r["formulation"] == f]
        key = f.replace("-", "_")
        summary[f"{key}_completed"] = f"{sum(r['status'] == 'completed' for r in fr)} of {len(fr)}"
        summary[f"{key}_first_stop"] = first_stop(fr)
        summary[f"{key}_{e_head}_finest"] = g(err[(f, dxs[0])][e_head])
    for k, e in ctx["fe_err"].items():
        for name, v in e.items():
            summary[f"fe_{k[0]}_{k[1]:g}_{name}".replace(".", "_")] = g(v)
    for k, r in fe.items():
        summary[f"fe_{k[0]}_{k[1]:g}_j_min".replace(".", "_")] = g(float(np.min(r["j_min"])))
    summary["fe_reference"] = f"linear, h_e = {FE_SPACINGS[-1]:g} cm"
    summary["fe_spacings"] = ", ".join(f"{h:g}" for h in FE_SPACINGS)
    summary["fe_svk_spacing"] = f"{FE_SVK_SPACING:g}"
    summary["fe_seconds"] = f"{sum(r['seconds'] for r in fe.values()):.0f}"


def common_figures(problem, ctx, out, summary, title, positions_title, head_label, ke0, head_ylim):
    """signals.png (the headline signal, global KE, pressure at A, clumped share), positions_<t>.png, pareto.png."""
    dx, a, fe, sr = ctx["dx"], ctx["a"], ctx["fe"], ctx["sr"]
    fig, axes = plt.subplots(4, 1, figsize=(7, 11), sharex=True)
    for key, lab in ((ctx["ref_key"], "fe-linear"), (ctx["svk_key"], "fe-svk")):
        r = fe[key]
        for ax, y in zip(axes, (problem.fe_head(r, a), r["kinetic_energy"], r["pressure"][:, a])):
            ax.plot(r["t"], y, color=COLOUR[lab], lw=1.6 if lab == "fe-linear" else 1.0, label=LABEL[lab])
    for f in problem.forms:
        s = sr[(f, problem.case, dx)]
        for ax, y in zip(axes, (problem.sph_head(s), s["kinetic_energy"], s["pressure_A"])):
            ax.plot(s["t"], y, color=COLOUR[f], lw=1.0, label=LABEL[f])
    axes[0].set_ylabel(head_label)
    axes[1].set_ylabel("global kinetic energy")
    axes[2].set_ylabel("pressure at A (Mbar)")
    order_panel(axes[3], ctx["order"], problem.forms, dx, problem.case)
    axes[3].set_xlabel("t (us)")
    axes[0].set_ylim(*head_ylim)
    axes[1].set_ylim(0, 1.6 * ke0)
    axes[0].legend(fontsize=8, ncol=3)
    for ax in axes:
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"{title} (dx = {dx:g} cm)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "signals.png"), dpi=90)
    plt.close(fig)
    for t in ctx["times"]:
        panels = []
        for f in problem.forms:
            snap = snapshot(ctx["snaps"], f, problem.case, dx, t)
            panels.append((LABEL[f], None if snap is None else (snap[0], snap[2], snap[3])))
        panels.append(("FE (linear)", fe[ctx["ref_key"]]["snapshots"].get(t)))
        positions_figure(os.path.join(out, f"positions_{t:g}.png"), f"Particle positions at t = {t:g} us "
                         f"({positions_title})", panels, 0.3, (9, 1.7))
    pareto_figure(os.path.join(out, "pareto.png"), f"Speed against error, {title.lower()} (x: the run stopped)",
                  ctx["runs"], problem.forms, lambda r: ctx["err"][(r["formulation"], num(r["dx"]))][f"e_{problem.head}"],
                  f"e_{problem.head}: RMS error of the {head_label} / its FE maximum")


def verdict_text(r):
    """'U (2.54 / 2.14)': the class and gamma_J / gamma_M (1/us) of one verdicts.csv row; else why there is none."""
    if r["reached"] != "1":
        return f"not reached (the run stopped before {num(r['t_wanted']):g} us)"
    if r["class"] == "-":
        return f"{r['status']}: {r['reason']}"
    return f"{r['class']} ({g(num(r['semi_discrete_growth']))} / {g(num(r['map_growth']))})"


def verdict_summary(out, summary):
    """The verdict table of verdicts.csv (one row per formulation and case: the initial state's verdict and the
    mid-run one's, each the class and gamma_J / gamma_M in 1/us), its floor(s) and resolution, and the runs of each
    class."""
    rows = read(os.path.join(out, "verdicts.csv"))
    keys = list(dict.fromkeys((r["formulation"], r["case"]) for r in rows))
    lines = []
    for f, case in keys:
        mine = sorted((r for r in rows if (r["formulation"], r["case"]) == (f, case)), key=lambda r: num(r["t_wanted"]))
        cells = [f"{verdict_text(r)} at t = {num(r['t_wanted']):g}" for r in mine]
        lines.append(f"| {LABEL[f]} | {case} | " + " | ".join(cells) + " |")
    summary["verdict_table"] = "\n".join(lines)
    summary["verdict_spacing"] = ", ".join(sorted({f"{num(r['dx']):g}" for r in rows}))
    summary["verdict_floor"] = ", ".join(sorted({g(num(r["floor"])) for r in rows if r["reached"] == "1"}))
    for c, name in (("S", "stable"), ("U", "semi_discrete"), ("I", "integrator"), ("B", "both")):
        hits = [f"{LABEL[r['formulation']]} {r['case']} t = {num(r['t_wanted']):g}" for r in rows if r["class"] == c]
        summary[f"verdict_{name}"] = "; ".join(hits) if hits else "none"


def write_summary(out, summary):
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2, sort_keys=True)
        f.write("\n")
