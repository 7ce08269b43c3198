"""Helpers shared by the studies' plot.py and report.py scripts (import after adding studies/common to sys.path)."""
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    """Rows of a CSV file as dicts."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(x):
    """float(x), NaN for text that is not a number."""
    try:
        return float(x)
    except ValueError:
        return math.nan


def ordered(rows, key):
    """The distinct values of column `key` in order of first appearance."""
    out = []
    for r in rows:
        if r[key] not in out:
            out.append(r[key])
    return out


def decorate(ax, xlabel=None, ylabel=None, title=None, title_size=None, legend=8, **legend_kw):
    """Label one panel: its x label, y label and title (each left out when None; title_size: the title's font size,
    else matplotlib's default), then its legend at font size `legend` (None: no legend) with any further legend
    options legend_kw (loc, ncol, ...)."""
    if xlabel is not None:
        ax.set_xlabel(xlabel)
    if ylabel is not None:
        ax.set_ylabel(ylabel)
    if title is not None:
        ax.set_title(title, **({} if title_size is None else {"fontsize": title_size}))
    if legend is not None:
        ax.legend(fontsize=legend, **legend_kw)


def save(fig, path, dpi=110, announce=False):
    """Lay the figure out (tight_layout), write it to path at dpi and close it; announce: then print 'wrote PATH'."""
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    if announce:
        print(f"wrote {path}")


def loglog_slope(xs, ys):
    """Least-squares slope of log y against log x: the exponent p of a fit y ~ x^p."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def write_summary_md(out, lines):
    """Write the lines (joined with newlines, one at the end) to out/summary.md and print them."""
    with open(os.path.join(out, "summary.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


def growth_panels(ax1, ax2, lim, diagonal, xlabel1, ylabel1, ylabel2):
    """The Swegle studies' growth-rate axes, once the points are drawn: ax1 measured against linear gamma on log axes
    over lim x lim with the diagonal (labelled `diagonal`), ax2 gamma against xi on a log axis; grids and legends."""
    ax1.plot(lim, lim, "k--", lw=0.8, label=diagonal)
    ax1.set(xscale="log", yscale="log", xlim=lim, ylim=lim)
    ax1.set_xlabel(xlabel1)
    ax1.set_ylabel(ylabel1)
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=7)
    ax2.set_yscale("log")
    ax2.set_xlabel("xi = V/V0")
    ax2.set_ylabel(ylabel2)
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=7, ncol=2)


def xi_colour(xi, xis):
    """Colour of a volume strain xi: black at 1, blue for compression, red for tension (coolwarm)."""
    if abs(xi - 1) < 1e-12:
        return "k"
    cmap = plt.get_cmap("coolwarm")
    lo, hi = min(xis), max(xis)
    return cmap(0.5 + 0.5 * (xi - 1) / max(hi - 1, 1 - lo, 1e-12))


def read_vtp(path, names):
    """Points (lists x, y) and the named point-data arrays (first component, lists) of an ASCII .vtp file written by
    io/vtk.hpp's write_vtp."""
    import re

    with open(path) as f:
        text = f.read()

    def array(name):
        m = re.search(r'<DataArray[^>]*Name="%s"[^>]*NumberOfComponents="(\d+)"[^>]*>(.*?)</DataArray>' % re.escape(name),
                      text, re.S)
        if not m:
            raise KeyError(f"{path}: no DataArray '{name}'")
        k = int(m.group(1))
        v = [float(s) for s in m.group(2).split()]
        return [v[i::k] for i in range(k)]

    pts = array("Points")
    return pts[0], pts[1], {n: array(n)[0] for n in names}


def time_series_panels(fig, axes, suptitle, path, legend):
    """Finish the GMS studies' 2 x 2 time-series figure once its curves are drawn: a grid and a legend (font size
    `legend`) on every panel, the time label t (cm / c0) under the bottom row, the title suptitle; saved to path."""
    for ax in axes.flat:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=legend)
    for ax in axes[1]:
        ax.set_xlabel("t (cm / c0)")
    fig.suptitle(suptitle)
    save(fig, path)


def frozen_modes(out, title, path="frozen.png"):
    """One panel per row of out/frozen_spectrum.csv (common/gms.hpp frozen_spectra_along_run): the most unstable
    mode's velocity shape (arrows, |v| coloured; red cross: its largest velocity) at the state's particle positions,
    titled with the growth rate and the number of unstable eigenvalues. Returns False (and writes nothing) without the CSV."""
    spec_path = os.path.join(out, "frozen_spectrum.csv")
    if not os.path.exists(spec_path):
        return False
    rows = read(spec_path)
    ncol = 4
    nrow = (len(rows) + ncol - 1) // ncol
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 2.6 * nrow + 0.6), squeeze=False, layout="constrained")
    for k, r in enumerate(rows):
        ax = axes[k // ncol][k % ncol]
        eps = "0" if num(r["eps"]) == 0 else "%g" % num(r["eps"])
        visc = "visc" if num(r["viscosity"]) else "novisc"
        m = read(os.path.join(out, f"frozen_mode_{r['state']}_eps{eps}_{visc}.csv"))
        x = [num(q["x"]) for q in m]
        y = [num(q["y"]) for q in m]
        a = [math.hypot(num(q["vx"]), num(q["vy"])) for q in m]
        amax = max(a) or 1.0
        ax.scatter(x, y, c=[v / amax for v in a], s=2, cmap="viridis", linewidths=0)
        if int(num(r["unstable_eigenvalues"])) > 0:
            ax.plot([num(r["mode_peak_x"])], [num(r["mode_peak_y"])], "rx", ms=6)
        if num(r["growth_rate"]) > 0:
            ax.quiver(x, y, [num(q["vx"]) / amax for q in m], [num(q["vy"]) / amax for q in m], scale=30, width=0.002)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(f"t = {num(r['t']):.0f}, ε = {eps}, viscosity {'on' if visc == 'visc' else 'off'}: "
                     f"growth {num(r['growth_rate']):.3g}, {int(num(r['unstable_eigenvalues']))} unstable", fontsize=7)
    for k in range(len(rows), nrow * ncol):
        axes[k // ncol][k % ncol].axis("off")
    fig.suptitle(title + " (most unstable mode: arrows, |v| coloured; frozen states, velocities zeroed)", fontsize=9)
    fig.savefig(os.path.join(out, path), dpi=110)
    plt.close(fig)
    return True


def ke_panels(ke, runs, suptitle, path, mark_stops=False):
    """The Swegle studies' kinetic-energy figure (Powell Fig. 4.2 style): one log panel per formulation, one line per
    xi, from ke.csv (formulation, xi, t, kinetic) and runs.csv (formulation, xi, status, t_stop). A stopped run says
    where in its label (and with mark_stops an x at its last record). Returns (series, forms, xis, info): the
    (formulation, xi) -> (t, KE) lists, the formulations in order of appearance, the sorted xi and the runs by key."""
    from collections import defaultdict
    series = defaultdict(lambda: ([], []))
    for r in ke:
        s = series[(r["formulation"], num(r["xi"]))]
        s[0].append(num(r["t"]))
        s[1].append(num(r["kinetic"]))
    forms = list(dict.fromkeys(r["formulation"] for r in runs))
    xis = sorted({num(r["xi"]) for r in runs})
    info = {(r["formulation"], num(r["xi"])): r for r in runs}
    ncol = 3
    nrow = math.ceil(len(forms) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.0 * ncol, 3.6 * nrow), sharex=True, sharey=True, squeeze=False)
    for k, form in enumerate(forms):
        ax = axes[k // ncol][k % ncol]
        for xi in xis:
            t, e = series.get((form, xi), ([], []))
            if not t:
                continue
            r = info[(form, xi)]
            stopped = r["status"] != "completed"
            label = f"xi = {xi:g}" + (f" (stop {num(r['t_stop']):.3g})" if stopped else "")
            ax.semilogy(t, e, color=xi_colour(xi, xis), lw=1.2, label=label)
            if stopped and mark_stops:
                ax.plot(t[-1], e[-1], "x", color=xi_colour(xi, xis), ms=6)
        ax.set_title(form)
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    for k in range(len(forms), nrow * ncol):
        axes[k // ncol][k % ncol].axis("off")
    for row in axes:
        for ax in row:
            ax.tick_params(labelbottom=True)
    for ax in axes[-1]:
        ax.set_xlabel("t (us)")
    for row in axes:
        row[0].set_ylabel("kinetic energy (g cm^2/us^2 per cm)")
    fig.suptitle(suptitle)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return series, forms, xis, info
