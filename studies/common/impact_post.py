"""Shared post-processing of Powell's impact studies (powell-bar-impact, powell-clamped-beam): reading the driver's CSVs
(common/impact.hpp), errors of a signal against the FE reference (impact_fe.py), the particle-order measures of the
statement tables, and the figures (signals, particle positions coloured by pressure, speed against error)."""
import math
import os
from collections import defaultdict

import numpy as np

from plot_common import num, plt

LABEL = {"sph": "basic SPH", "ncsph": "NCSPH", "ssph": "S-SPH", "tl": "TL-SPH", "tl-svk": "TL-SPH (SVK)",
         "fe": "FE", "fe-linear": "FE (linear)", "fe-svk": "FE (SVK)"}
COLOUR = {"sph": "tab:red", "ncsph": "tab:orange", "ssph": "tab:blue", "tl": "tab:green", "tl-svk": "tab:olive",
          "fe": "k", "fe-linear": "0.5", "fe-svk": "k"}
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
    """One row of panels (label, (t, x, p) or None); particles coloured by pressure in [-pmax, pmax]."""
    fig, axes = plt.subplots(len(panels), 1, figsize=(aspect_box[0], aspect_box[1] * len(panels)), sharex=True,
                             sharey=True)
    sc = None
    for ax, (label, snap) in zip(np.atleast_1d(axes), panels):
        if snap is None:
            ax.set_title(f"{label}: stopped before this time", fontsize=8)
            continue
        t, x, p = snap
        sc = ax.scatter(x[:, 0], x[:, 1], c=p, s=1, cmap="coolwarm", vmin=-pmax, vmax=pmax)
        ax.set_title(f"{label}, t = {t:.2f} us", fontsize=8)
        ax.set_aspect("equal")
    if sc is not None:
        fig.colorbar(sc, ax=axes, shrink=0.8, label="pressure (Mbar)")
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
