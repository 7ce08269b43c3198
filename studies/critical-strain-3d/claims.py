"""Headline claims of critical-strain-3d (results/critical-strain-3d/), run by tests/scripts/claims_test.py.

summary.md is written by benchmarks/lattice_lobpcg_3d_report.py (no summary.md.in); its typed values are parsed and
compared with results.csv. Timing claims are ratios within the run and fitted exponents, never seconds."""
import math

from claims import approx, check, one, select


def _slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def _cases(r, threads=None):
    """The first run of every case (not the repeats), successful."""
    rows = [x for x in r.csv("results.csv") if x["variant"].startswith("--dim 3") and x["status"] == "successful"
            and "--storage" not in x["variant"]]
    return sorted([x for x in rows if threads is None or x["threads"] == threads], key=lambda x: x["n"])


def claim_agrees_with_the_direct_route(r):
    """The matrix-free block LOBPCG agrees with the engine's direct route (assembled by products, CHOLMOD + shifted
    Spectra) to <= 1.2e-12 relative at n = 8 and 11 (issue 13: 1e-8); every run converged (residual <= tol); 1 and 2
    threads, and the six repeats at n = 32, give the same e_crit bits."""
    rows = r.csv("results.csv")
    ref = [x for x in rows if "--direct-reference" in x["variant"]]
    check(sorted(x["n"] for x in ref) == [8, 11], f"direct references at n = {[x['n'] for x in ref]}")
    for x in ref:
        d = abs(x["e_crit"] / x["direct_reference_e_crit"] - 1)
        approx(x["rel_diff_reference"], d, f"{x.where()} rel_diff_reference", rel=0.05, abs_=5e-15)
        check(d <= 1.2e-12, f"{x.where()}: {d:.3g} from the direct route")
    approx(r.stated(r"\*\*Agreement with the direct route\*\*: <= ([\d.e+-]+) relative"),
           max(x["rel_diff_reference"] for x in ref), "summary.md agreement", rel=0.05)
    for x in rows:
        check(x["status"] == "successful" and x["residual"] <= x["tol"], f"{x.where()}: {x['status']}, residual "
                                                                          f"{x['residual']}")
    for a in _cases(r, 1):
        b = one(_cases(r, 2), n=a["n"])
        check(a["e_crit"] == b["e_crit"], f"{b.where()}: e_crit {b['e_crit']!r} on 2 threads, {a['e_crit']!r} on 1")
    base = one(_cases(r, 1), n=32)["e_crit"]
    reps = select(rows, variant="repeat")
    check(len(reps) == 6 and all(x["e_crit"] == base for x in reps), "repeats at n = 32 differ or are missing")
    return f"<= {max(x['rel_diff_reference'] for x in ref):.2g} from the direct route; threads and repeats bitwise"


def claim_steps_independent_of_n(r):
    """38-45 block steps for n = 16-100 (12 288 to 3 000 000 DOFs, 244x) on 1 and 2 threads, as summary.md states,
    close to the 2D lattices' 37-39 (results/critical-strain-large, inside the stated '2D: 36-40')."""
    its = [x["iterations"] for x in _cases(r) if x["n"] >= 16]
    check(38 <= min(its) and max(its) <= 45, f"block steps {its}")
    stated = r.stated(r"\*\*Steps independent of n\*\*: (\d+-\d+) block steps for n = 16-100", convert=False)
    check(stated == f"{min(its)}-{max(its)}", f"summary.md '{stated}', data {min(its)}-{max(its)}")
    d2 = [x["iterations"] for x in r.other("critical-strain-large").csv("results.csv") if x["variant"] == "default"]
    check(36 <= min(d2) and max(d2) <= 40, f"2D block steps {min(d2)}-{max(d2)}, summary.md says 36-40")
    return f"{min(its)}-{max(its)} block steps (2D {min(d2)}-{max(d2)})"


def claim_cost_exponents(r):
    """Least squares of log value on log DOFs (n >= 24: 24-64 on 1 thread, 24-100 on 2 threads): solve and total time
    ~ N^(0.80-1.10), peak memory ~ N^(0.80-0.95) (by offset the fixed per-process memory weighs at small n), the
    exponents summary.md types (2 decimals)."""
    out = []
    for th in (1, 2):
        rows = [x for x in _cases(r, th) if x["n"] >= 24]
        dofs = [x["dofs"] for x in rows]
        fit = {c: _slope(dofs, [x[c] for x in rows]) for c in ("solve_s", "total_s", "peak_rss_MB")}
        check(0.80 <= fit["solve_s"] <= 1.10 and 0.80 <= fit["total_s"] <= 1.10, f"{th} thread(s): {fit}")
        check(0.80 <= fit["peak_rss_MB"] <= 0.95, f"{th} thread(s): peak memory ~ N^{fit['peak_rss_MB']:.3f}")
        text = r.stated(rf"\*\*Cost exponents\*\* \({th} thread\(s\), least squares of log value on log DOFs, "
                        rf"n = 24-{rows[-1]['n']}\): (solve N\^[\d.]+, total N\^[\d.]+, peak memory N\^[\d.]+)",
                        convert=False)
        stated = [float(part.split("^")[1].rstrip(".")) for part in text.split(", ")]
        for (c, p), s in zip(fit.items(), stated):
            approx(s, p, f"summary.md {th} thread(s) {c} exponent", abs_=0.0051)
        out.append(f"{th} thread(s): total N^{fit['total_s']:.2f}, memory N^{fit['peak_rss_MB']:.2f}")
    return "; ".join(out)


def claim_memory_and_timing_spread(r):
    """Memory: by offset the linearisation holds 110-170 bytes per free particle for n >= 32 (the grids of x and sigma
    on the free box padded by 4 sites per side, and the free positions), falling with n to 119 bytes at 100^3, and
    100^3 peaks at 1.2 GB (issue 35: < 2 GB); per pair, in the same run, the linearisation is 40-55x larger and the
    peak RSS 5-6.5x higher at n = 32 and 64, with the same e_crit to 5e-15. Timing: this run was measured at a load
    average of 1.4-2.3 on the 2 cores (other agents' jobs); the four runs of n = 32 spread by max/min as summary.md
    states (1.03 on 1 thread, 1.52 on 2 in the run of 2026-12-07), and so does the 1 -> 2 thread speed-up at n = 64
    (1.34 then; 0.89 in the run before): single timings here are indicative only."""
    kbs = []
    for x in _cases(r, 2):
        if x["n"] >= 32:
            kbs.append(x["linearisation_MB"] * 1e6 / x["n"] ** 3)
            check(110 <= kbs[-1] <= 170, f"{x.where()}: linearisation {kbs[-1]:.3g} bytes per free particle")
    big = one(_cases(r, 2), n=100)
    check(big["peak_rss_MB"] < 2048, f"{big.where()}: peak {big['peak_rss_MB']} MB")
    approx(r.stated(r"peak RSS ([\d.]+) GB \(the linearisation"), big["peak_rss_MB"] / 1024, "summary.md peak GB",
           abs_=0.0051)
    approx(r.stated(r"\(the linearisation ([\d.]+) MB\)"), big["linearisation_MB"], "summary.md linearisation MB",
           abs_=0.51)
    rows = r.csv("results.csv")
    pp = [x for x in rows if "--storage per-pair" in x["variant"]]
    check(sorted(x["n"] for x in pp) == [32, 64], f"per-pair rows at n = {[x['n'] for x in pp]}")
    for p in pp:
        o = one(_cases(r, 2), n=p["n"])
        check(p["storage"] == "per-pair" and o["storage"] == "by-offset", f"{p.where()}: storages")
        check(abs(p["e_crit"] / o["e_crit"] - 1) <= 5e-15, f"{p.where()}: e_crit {p['e_crit']!r} vs {o['e_crit']!r}")
        lin, peak = p["linearisation_MB"] / o["linearisation_MB"], p["peak_rss_MB"] / o["peak_rss_MB"]
        check(40 <= lin <= 55 and 5 <= peak <= 6.5, f"{p.where()}: per pair / by offset memory {lin:.3g}, "
                                                    f"peak {peak:.3g}")
    spread = {}
    for th in (1, 2):
        t = [x["total_s"] for x in _cases(r, th) + select(rows, variant="repeat", threads=th) if x["n"] == 32]
        check(len(t) == 4, f"{len(t)} runs of n = 32 on {th} thread(s)")
        spread[th] = max(t) / min(t)
        approx(r.stated(rf"\*\*Repeatability\*\* \(n = 32, {th} thread\(s\), .*?\(max/min ([\d.]+)\)"), spread[th],
               f"summary.md spread on {th} thread(s)", abs_=0.0051)
    loads = [float(x["load_before"]) for x in rows]
    check(1.0 <= min(loads) and max(loads) <= 2.5, f"load {min(loads)}-{max(loads)}: the docstring's load is stale")
    a, b = one(_cases(r, 1), n=64), one(_cases(r, 2), n=64)
    s = a["total_s"] / b["total_s"]
    approx(r.stated(r"\*\*Threads\*\*: 1 -> 2 threads at n = 64: .*?\(speed-up ([\d.]+)\)"), s, "summary.md speed-up",
           abs_=0.0051)
    check(all(a > b for a, b in zip(kbs, kbs[1:])), f"bytes per free particle not falling with n: {kbs}")
    return f"linearisation {kbs[0]:.0f}-{kbs[-1]:.0f} bytes per particle; 100^3 peak {big['peak_rss_MB']:.0f} MB; " \
           f"spread {spread[1]:.2f} / {spread[2]:.2f}; speed-up at n = 64 {s:.2f}"
