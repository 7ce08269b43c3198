"""Claims shared by the impact studies' claims.py (powell-bar-impact, powell-clamped-beam): each takes the study's
committed Results and the names of its signal and error columns."""
import bisect
import math

from claims import approx, check

LABEL = {"sph": "basic SPH", "ncsph": "NCSPH", "ssph": "S-SPH", "ssph-g": "S-SPH (means of G)", "tl": "TL-SPH",
         "tl-svk": "TL-SPH (SVK)"}


def completed_counts(r, forms):
    """summary '<form>_completed' = 'k of n' with k the runs of status 'completed' in runs.csv."""
    runs = r.csv("runs.csv")
    for f in forms:
        rows = [x for x in runs if x["formulation"] == f]
        want = f"{sum(x['status'] == 'completed' for x in rows)} of {len(rows)}"
        key = f"{f.replace('-', '_')}_completed"
        check(r.key(key) == want, f"{f}: summary '{r.key(key)}', runs.csv {want}")
    return f"{len(runs)} runs"


def first_stops(r, forms, case=None, key="{form}_first_stop"):
    """summary '<form>_first_stop' names the status and time of the run that stopped first in runs.csv ('none' when
    all completed)."""
    runs = r.csv("runs.csv")
    n = 0
    for f in forms:
        failed = [x for x in runs if x["formulation"] == f and x["status"] != "completed"
                  and (case is None or x["case"] == case)]
        first = min(failed, key=lambda x: x["t_stop"]) if failed else None
        want = f"{first['status']} at t = {first['t_stop']:.2f} us" if first else "none"
        k = key.format(form=f.replace("-", "_"), case=case)
        check(r.key(k) == want, f"{k}: summary '{r.key(k)}', runs.csv {want}")
        n += first is not None
    return f"{n} formulations with a stopped run"


def least_error_named(r, error):
    """summary 'best_<error>' names the completed run of least <error> in errors.csv, and its value."""
    done = [x for x in r.csv("errors.csv") if x["status"] == "completed" and not math.isnan(x[error])]
    best = min(done, key=lambda x: x[error])
    want = f"{LABEL[best['formulation']]} at dx = {best['dx']:g}"
    check(r.key(f"best_{error}") == want, f"summary names '{r.key(f'best_{error}')}', errors.csv {want}")
    approx(r.num(f"best_{error}_value"), best[error], f"least {error}", rel=5e-3)
    return f"{want}: {best[error]:.3g}"


def pareto_front_recomputed(r, error):
    """summary 'pareto_front' lists exactly the completed runs of errors.csv that no other completed run beats in
    both CPU seconds and <error>, cheapest first."""
    done = sorted((x for x in r.csv("errors.csv") if x["status"] == "completed"),
                  key=lambda x: (x["cpu_seconds"], x[error]))
    front, best = [], math.inf
    for x in done:
        if x[error] < best:
            front.append(f"{LABEL[x['formulation']]} dx {x['dx']:g} ({x['cpu_seconds']:.2g} s, {x[error]:.3g})")
            best = x[error]
    want = "; ".join(front)
    check(r.key("pareto_front") == want, f"summary '{r.key('pareto_front')}', errors.csv '{want}'")
    return f"{len(front)} runs on the front"


def fe_error_below_sph(r, error, model, sides):
    """The FE reference's own error (fe_errors.csv, the mesh `sides[1]` against the finest; a bound on the finest's
    own error for a converging mesh) is below every completed SPH run's (a run that stopped is measured over its
    shorter window only), and the coarser mesh `sides[0]` has the larger one."""
    fe = r.csv("fe_errors.csv")
    coarse, mid = (next(x[error] for x in fe if x["model"] == model and abs(x["element_side"] - s) < 1e-12)
                   for s in sides)
    least = min(x[error] for x in r.csv("errors.csv") if x["status"] == "completed" and not math.isnan(x[error]))
    check(mid < least, f"FE {model} h_e {sides[1]} {error} {mid} >= least SPH {error} {least}")
    check(coarse > mid, f"FE {error} does not decrease with the mesh: {sides[0]}: {coarse}, {sides[1]}: {mid}")
    return f"FE {mid:.3g} < SPH {least:.3g}"


def interp(ts, ys, t):
    """ys(t) by linear interpolation in the sorted ts, constant beyond the ends."""
    k = bisect.bisect_left(ts, t)
    if k == 0:
        return ys[0]
    if k >= len(ts):
        return ys[-1]
    w = (t - ts[k - 1]) / (ts[k] - ts[k - 1])
    return ys[k - 1] + w * (ys[k] - ys[k - 1])


def error_recomputed(r, error, signal, fe_model, fe_signal, change=False):
    """<error> of every run at the snapshot resolution, recomputed from signals.csv (column `signal`) and the FE
    reference's series in fe_signals.csv (column `fe_signal`, formatted with particle A's position), scaled by the
    FE series' largest magnitude, equals errors.csv's (to 1e-6). change: compare signal(t) - signal(0)."""
    dx = r.num("snapshot_spacing")
    runs = {x["formulation"]: x for x in r.csv("runs.csv") if abs(x["dx"] - dx) < 1e-12}
    sig = r.csv("signals.csv")
    fe = [q for q in r.csv("fe_signals.csv") if q["model"] == fe_model]
    side = min(q["element_side"] for q in fe)
    fe = [q for q in fe if q["element_side"] == side]
    n = 0
    for x in r.csv("errors.csv"):
        if abs(x["dx"] - dx) > 1e-12:
            continue
        a = runs[x["formulation"]]
        column = fe_signal.format(x=f"{a['x_A']:g}", y=f"{a['y_A']:g}")
        ts, ys = [q["t"] for q in fe], [q[column] for q in fe]
        if change:
            ys = [y - ys[0] for y in ys]
        s = [q for q in sig if q["formulation"] == x["formulation"] and abs(q["dx"] - dx) < 1e-12
             and q["t"] <= x["t_stop"] + 1e-12]
        y0 = s[0][signal] if change else 0.0
        e = math.sqrt(sum((q[signal] - y0 - interp(ts, ys, q["t"])) ** 2 for q in s) / len(s)) / max(map(abs, ys))
        approx(e, x[error], f"{x.where()} {error}", rel=1e-6)
        n += 1
    return f"{n} runs"


def mcm_time_step(r):
    """Every run's dt is TSSFAC h / c_P (rounded down to t_end / steps: within 1 %), h = 1.3 dx, c_P of steel."""
    cp = math.sqrt((2.1 * 0.3 / (1.3 * 0.4) + 2 * 2.1 / 2.6) / 7.8)
    tssfac = r.num("tssfac")
    for x in r.csv("runs.csv"):
        dt = tssfac * 1.3 * x["dx"] / cp
        check(dt / 1.01 <= x["dt"] <= dt * (1 + 1e-9), f"{x.where()}: dt {x['dt']}, TSSFAC h / c_P = {dt}")
    return f"c_P = {cp:.4f} cm/us"


def verdict_class(semi_discrete, map_growth, floor):
    """The class of growth/stability_verdict.hpp's rules, written again here: S, U, I or B."""
    if semi_discrete > floor:
        return "B" if map_growth - max(semi_discrete, 0.0) > floor else "U"
    return "I" if map_growth > floor else "S"


def verdicts_follow_csv(r):
    """Each verdict's class follows from its row's two rates and floor by the rules (recomputed), and the summary's
    table and class lists are verdicts.csv's."""
    rows = r.csv("verdicts.csv")
    check(rows, "verdicts.csv has no rows")
    keyed = {}
    for x in rows:
        if x["reached"] == 1 and x["class"] != "-":
            want = verdict_class(x["semi_discrete_growth"], x["map_growth"], x["floor"])
            check(x["class"] == want, f"{x['formulation']} {x['case']} t = {x['t_wanted']}: class {x['class']}, "
                  f"the rates give {want}")
            approx(x["integrator_excess"], x["map_growth"] - max(x["semi_discrete_growth"], 0.0),
                   "integrator excess", rel=1e-9, abs_=1e-12)
        keyed.setdefault((x["formulation"], x["case"]), []).append(x)
    lines = r.key("verdict_table").split("\n")
    check(len(lines) == len(keyed), f"verdict_table has {len(lines)} rows, verdicts.csv {len(keyed)} runs")
    for line, ((f, case), xs) in zip(lines, keyed.items()):
        cells = [c.strip() for c in line.strip("| ").split("|")]
        check(cells[:2] == [LABEL[f], case], f"verdict_table row '{line}' is not {LABEL[f]} {case}")
        for cell, x in zip(cells[2:], sorted(xs, key=lambda q: q["t_wanted"])):
            want = x["class"] if x["reached"] == 1 and x["class"] != "-" else ("not reached" if x["reached"] != 1
                                                                              else x["status"])
            check(cell.startswith(want), f"{LABEL[f]} {case} t = {x['t_wanted']}: summary '{cell}', csv {want}")
    for c, name in (("S", "stable"), ("U", "semi_discrete"), ("I", "integrator"), ("B", "both")):
        hits = [f"{LABEL[x['formulation']]} {x['case']} t = {x['t_wanted']:g}" for x in rows if x["class"] == c]
        want = "; ".join(hits) if hits else "none"
        check(r.key(f"verdict_{name}") == want, f"verdict_{name}: summary '{r.key(f'verdict_{name}')}', csv '{want}'")
    return f"{len(rows)} verdicts"
