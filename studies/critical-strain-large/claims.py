"""Headline claims of critical-strain-large (results/critical-strain-large/), run by tests/scripts/claims_test.py.

summary.md is written by benchmarks/lattice_lobpcg_report.py (no summary.md.in); its typed exponents are parsed and
compared with results.csv. Timing claims are ratios within one run and fitted exponents, never seconds: issue 13's
60 s / 4 GB target is an absolute and is not a claim here."""
import math

from claims import approx, check, one, select


def _slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def _default(r, threads=None):
    rows = select(r.csv("results.csv"), variant="default", status="successful")
    return sorted([x for x in rows if threads is None or x["threads"] == threads], key=lambda x: x["n"])


def claim_routes_agree(r):
    """The matrix-free block LOBPCG's e_crit agrees with the direct PETSc shift-invert values (n = 64-256) and with
    SciPy's eigsh shift-invert on the exported matrices (n = 32-256, same run) to 2e-12 relative (issue 13 asks 1e-8),
    every eigsh value certified by Sylvester's inertia (no eigenvalue above lambda (1 + 1e-9), 2 above lambda
    (1 - 1e-9): the top mode and its x <-> y image); 1 and 2 threads give the same e_crit to 5e-15 (the operator
    products are the same bits for any thread count, tests/jacobian/matrix_free_storage_test.cpp; FFTW_MEASURE picks
    the DST plans by timing in each process, which can move the last digit, as at n = 256 here)."""
    worst = 0.0
    for x in _default(r):
        if not math.isnan(x["rel_diff_reference"]):
            check(x["rel_diff_reference"] <= 2e-12, f"{x.where()}: {x['rel_diff_reference']:.3g} from the direct value")
            worst = max(worst, x["rel_diff_reference"])
        check(x["residual"] <= x["tol"], f"{x.where()}: residual {x['residual']:.3g} above tol {x['tol']:g}")
    check(len([x for x in _default(r) if not math.isnan(x["rel_diff_reference"])]) >= 6, "fewer than 6 checked runs")
    for one_t in _default(r, 1):
        two = one(r.csv("results.csv"), variant="default", n=one_t["n"], threads=2)
        check(abs(one_t["e_crit"] / two["e_crit"] - 1) <= 5e-15, f"{two.where()}: e_crit {two['e_crit']!r} on 2 "
                                                                   f"threads, {one_t['e_crit']!r} on 1")
    sc = r.csv("scipy_eigsh.csv")
    for x in sc:
        check(x["status"] == "successful", f"{x.where()}: eigsh {x['status']}")
        # the e_crit columns carry 15 significant digits: their ratio resolves a difference to ~2e-15
        approx(x["rel_diff"], abs(x["e_crit_lobpcg"] / x["e_crit_eigsh"] - 1), f"{x.where()} rel_diff", rel=0.01,
               abs_=2e-15)
        check(x["rel_diff"] <= 2e-12, f"{x.where()}: LOBPCG vs eigsh {x['rel_diff']:.3g}")
        check(x["eigs_above_upper"] == 0 and x["eigs_above_lower"] == 2,
              f"{x.where()}: inertia {x['eigs_above_upper']} / {x['eigs_above_lower']}")
    check(len(sc) >= 4, f"scipy_eigsh.csv has {len(sc)} rows")
    return f"direct {worst:.2g}, eigsh {max(x['rel_diff'] for x in sc):.2g} relative; 1 thread ~ 2 threads"


def claim_steps_independent_of_n(r):
    """The preconditioned block LOBPCG takes 37-39 block steps for n = 64-1000 on either thread count (a 15x larger
    lattice side, 244x the DOFs), against 15 089 steps of the unpreconditioned block-size-1 LOBPCG at n = 128
    (results/critical-strain-petsc/results.csv); A0 and A1 products = 4 (steps + 1) for block 4."""
    rows = _default(r)
    its = [x["iterations"] for x in rows]
    check(37 <= min(its) and max(its) <= 39, f"block steps {its}")
    check(min(x["n"] for x in rows) <= 64 and max(x["n"] for x in rows) >= 1000, "n range shrank")
    for x in rows:
        check(x["a0_products"] == x["a1_products"] == 4 * (x["iterations"] + 1),
              f"{x.where()}: {x['a0_products']} products for {x['iterations']} steps")
    plain = one(r.other("critical-strain-petsc").csv("results.csv"), method="lobpcg(hand-written;unpreconditioned)",
                n=128)
    check(plain["iterations"] == 15089, f"{plain.where()}: {plain['iterations']} steps, summary.md says 15 089")
    check(plain["iterations"] > 300 * max(its), "unpreconditioned steps not >> preconditioned")
    return f"{min(its)}-{max(its)} block steps for n = {rows[0]['n']}-{rows[-1]['n']}; unpreconditioned " \
           f"{plain['iterations']} at n = 128"


def claim_cost_linear_in_dofs(r):
    """Cost exponents (least squares of log wall time on log DOFs, n = 128-1000): solve, total and linearisation all in
    N^0.80-1.05 on 1 and on 2 threads (issue 13: total <= N^1.2), as summary.md types them (2 decimals); peak RSS is
    the same on 1 and 2 threads up to the second thread's stack and transform buffers (<= 3 MB + 40 bytes per site) and 0.40 kB per DOF at n = 1000 (by-offset storage; per pair 0.86, the
    Storage section); 2 threads are 1.3-2x faster than 1 at n >= 256 (2 is the ideal on 2 cores; 1.46-1.80x in the
    run of 2026-12-07 after the tall-block kernels, at load 1.3-1.9 before the cases; 1.3-1.6x in the run before).
    SciPy's eigsh, in contrast, grows like N^1.6-1.9 (n >= 64; 1.72 in the run of 2026-12-06, 1.82 in that of
    2026-12-07) and takes 3x-200x the LOBPCG's time, the ratio growing with n."""
    out = []
    for th in (1, 2):
        rows = [x for x in _default(r, th) if x["n"] >= 128]
        dofs = [x["dofs"] for x in rows]
        fit = {c: _slope(dofs, [x[c] for x in rows]) for c in ("solve_s", "total_s", "linearisation_s")}
        for c, p in fit.items():
            check(0.80 <= p <= 1.05, f"{th} thread(s): {c} ~ N^{p:.3f}")
        m = [float(v) for v in r.stated(rf"\*\*Cost exponent\*\* \({th} thread\(s\), .*?: (solve N\^[\d.]+, total "
                                        rf"N\^[\d.]+, linearisation N\^[\d.]+)", convert=False)
             .replace("solve N^", "").replace(" total N^", "").replace(" linearisation N^", "").split(",")]
        for (c, p), s in zip(fit.items(), m):
            approx(s, p, f"summary.md {th} thread(s) {c} exponent", abs_=0.0051)
        out.append(f"{th} thread(s): total N^{fit['total_s']:.2f}")
    for a, b in zip(_default(r, 1), _default(r, 2)):
        check(a["n"] == b["n"], f"{b.where()}: 1- and 2-thread rows out of step")
        # the second thread adds its stack (a few MB) and its transform buffers: the complex n x n field of the
        # sine-transform preconditioner and FFTW's, up to 40 bytes per lattice site
        extra = b["peak_rss_MB"] - a["peak_rss_MB"]
        check(-0.03 * a["peak_rss_MB"] <= extra <= 3.0 + 40e-6 * a["n"] ** 2,
              f"{b.where()}: peak RSS on 2 threads {b['peak_rss_MB']} MB, on 1 {a['peak_rss_MB']} MB")
        if a["n"] >= 256:
            s = a["total_s"] / b["total_s"]
            check(1.3 <= s <= 2.0, f"n = {a['n']}: 2 threads {s:.3g}x faster than 1")
    top = _default(r, 1)[-1]
    approx(top["peak_rss_MB"] * 1e3 / top["dofs"], 0.40, f"{top.where()} kB per DOF", abs_=0.02)
    pp = one(r.csv("results.csv"), variant="--storage per-pair", n=top["n"], threads=1)
    approx(pp["peak_rss_MB"] * 1e3 / pp["dofs"], 0.86, f"{pp.where()} kB per DOF", abs_=0.02)
    sc = sorted(r.csv("scipy_eigsh.csv"), key=lambda x: x["n"])
    big = [x for x in sc if x["n"] >= 64]
    e = _slope([x["dofs"] for x in big], [x["eigsh_s"] for x in big])
    check(1.6 <= e <= 1.9, f"eigsh time ~ N^{e:.3f}")
    approx(r.stated(r"\*\*eigsh cost\*\* .*?: time N\^([\d.]+)"), e, "summary.md eigsh exponent", abs_=0.0051)
    ratios = [1 / x["ratio_lobpcg_eigsh"] for x in sc]
    check(all(a < b for a, b in zip(ratios, ratios[1:])) and 2.5 <= ratios[0] and ratios[-1] <= 200,
          f"eigsh / LOBPCG time {ratios}")
    return "; ".join(out) + f"; eigsh N^{e:.2f}, {ratios[0]:.2g}-{ratios[-1]:.3g}x the LOBPCG"


def claim_storage_by_offset_against_per_pair(r):
    """G and H by lattice offset against per pair, in the same run (n = 256 on 1 thread, 1000 on 1 and 2 threads): the
    same e_crit to 5e-15 relative (FFTW_MEASURE's plans: see claim_variants), the linearisation 17x smaller (61 against 1035 MB at n = 1000), peak RSS 2.0-2.2x
    lower, and the products inside the solve 1.5-6x faster (1.8-2.8x in the first run of 2026-12-07; 2.7-3.2x once
    the by-offset sweeps got their AVX2 clones, which the per-pair route has not: core/simd_dispatch.hpp, up to 2x on
    the sweeps); the total wall time moves less (1.0-2x) because the
    products are the smallest of the solve's three parts (DST preconditioner, dense block algebra), as summary.md
    states."""
    rows = r.csv("results.csv")
    pp = [x for x in rows if x["variant"] == "--storage per-pair"]
    check(len(pp) == 3, f"{len(pp)} per-pair rows")
    for p in pp:
        o = one(rows, variant="default", n=p["n"], threads=p["threads"])
        check(p["storage"] == "per-pair" and o["storage"] == "by-offset", f"{p.where()}: storages {p['storage']}, "
                                                                          f"{o['storage']}")
        check(abs(p["e_crit"] / o["e_crit"] - 1) <= 5e-15, f"{p.where()}: e_crit {p['e_crit']!r} vs {o['e_crit']!r}")
        lin = p["linearisation_MB"] / o["linearisation_MB"]
        check(16 <= lin <= 18, f"{p.where()}: linearisation memory ratio {lin:.3g}")
        peak = p["peak_rss_MB"] / o["peak_rss_MB"]
        check(1.9 <= peak <= 2.3, f"{p.where()}: peak RSS ratio {peak:.3g}")
        prod = p["solve_products_s"] / o["solve_products_s"]
        check(1.5 <= prod <= 6, f"{p.where()}: products in the solve {prod:.3g}x")
        approx(r.stated(rf"\*\*n = {p['n']}, {p['threads']} thread\(s\)\*\*: per pair / by offset = .*?, ([\d.]+) "
                        rf"\(products in the solve\)"), prod, f"summary.md products ratio {p.where()}", abs_=0.0051)
        tot = p["total_s"] / o["total_s"]
        check(1.0 <= tot <= 2, f"{p.where()}: total {tot:.3g}x")
    return "by offset: same e_crit, 17x less linearisation memory, ~2x less peak, products 1.5-6x faster"


def claim_variants(r):
    """Variants at n = 1000 (2 threads): block 2, a random start, tol 1e-7 and estimated FFTW plans give the default's
    e_crit to 5e-15 relative (the last two digits: FFTW_MEASURE chooses plans by timing them, and the default's own 1-
    and 2-thread rows differ by 3.1e-15 in the run of 2026-12-07); block 2 without noise stops at a different eigenvalue 8.1e-4 relative above the default's e_crit
    (a smaller lambda: the symmetric start misses the top mode); block 2 needs 2.5-3x the default's 37 steps."""
    rows = r.csv("results.csv")
    ref = one(rows, variant="default", n=1000, threads=2)
    for v in ("--block 2", "--random", "--tol 1e-7", "--no-measure"):
        x = one(rows, variant=v, n=1000)
        check(x["status"] == "successful" and abs(x["e_crit"] / ref["e_crit"] - 1) <= 5e-15,
              f"{x.where()}: {v} e_crit {x['e_crit']!r}")
    nz = one(rows, variant="--block 2 --noise 0", n=1000)
    d = nz["e_crit"] / ref["e_crit"] - 1
    approx(d, 8.1e-4, f"{nz.where()} relative difference from the default", abs_=0.05e-4)
    b2 = one(rows, variant="--block 2", n=1000)
    s = b2["iterations"] / ref["iterations"]
    check(2.5 <= s <= 3, f"{b2.where()}: block 2 takes {s:.3g}x the default's steps")
    return f"4 variants = default; noise 0 +{d:.2g}; block 2 {b2['iterations']} steps"
