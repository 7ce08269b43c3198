#!/usr/bin/env python3
"""Turns the json of rate_form_step_benchmark into a markdown report (µs per particle-step, route ratios, bandwidth).

/usr/bin/time -v build/bin/rate_form_step_benchmark --benchmark_out=results/rate-form-speed/benchmark.json \
    --benchmark_out_format=json
python3 benchmarks/relative_executable.py results/rate-form-speed/benchmark.json   (no machine path in the json)
python3 benchmarks/rate_form_step_report.py results/rate-form-speed/benchmark.json results/rate-form-speed/benchmark.md \
    [PEAK_RSS_MB]   (optional, "Maximum resident set size" of /usr/bin/time -v, in MB)
    [--before results/rate-form-speed/benchmark_before.json]   (optional: an earlier run to compare the library with)
    [--before-label TEXT]   (what that earlier run measured; the default describes benchmark_before.json)

Every sentence of the report is either computed from the json(s) or describes the routes' code.
"""
import argparse
import json
import os
import statistics

ROUTES = ["Fused", "FusedPrealloc", "FusedOnePass", "FusedOnePassCubic", "FusedHalfPairs", "Operator", "OperatorSpMV",
          "Rebuild", "LibraryBefore", "Gms", "GmsBefore"]
# The library before (its reference copy) and after the row pipeline, in the same run: (label, before, after).
BEFORE_AFTER = [("plain SPH", "LibraryBefore", "Fused"), ("GMS", "GmsBefore", "Gms")]
UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
BEFORE_LABEL = ("the run committed with the benchmark in bc182c6 (results/rate-form-speed/benchmark.json of that "
                "commit), whose library allocated its per-pair scratch r, ∇W, W, r² on every call (the algorithm "
                "FusedPrealloc copies, without the allocation)")


def load(path):
    """Best (least CPU time per iteration) repetition of every benchmark, keyed by (route, N, h) or the triad name;
    the CPU times of all repetitions under the same key; the context; the errors."""
    data = json.load(open(path))
    best, reps = {}, {}
    for b in data["benchmarks"]:
        if b.get("run_type") != "iteration" or b.get("error_occurred"):
            continue
        parts = b["run_name"].split("/")
        b["cpu_s"] = b["cpu_time"] * UNIT[b["time_unit"]]
        b["real_s"] = b["real_time"] * UNIT[b["time_unit"]]
        key = parts[0] if parts[0].startswith("Triad") else (parts[0], int(parts[1][2:]), float(parts[2][2:]))
        reps.setdefault(key, []).append(b["cpu_s"])
        if key not in best or b["cpu_s"] < best[key]["cpu_s"]:
            best[key] = b
    errors = [b["name"] + ": " + b.get("error_message", "") for b in data["benchmarks"] if b.get("error_occurred")]
    return best, reps, data.get("context", {}), errors


def fmt_range(values, fmt="{:.2f}", suffix=""):
    values = [v for v in values if v is not None]
    if not values:
        return "-"
    lo, hi = fmt.format(min(values)), fmt.format(max(values))
    return (lo if lo == hi else f"{lo}–{hi}") + suffix


def main(src, out, peak_mb=None, before=None, before_label=BEFORE_LABEL):
    best, reps, ctx, errors = load(src)
    triads = [best[k]["bytes_per_second"] for k in ("Triad", "TriadAgain") if k in best]
    triad = max(triads) if triads else float("nan")
    triad_bytes = best.get("Triad", {}).get("array_bytes", float("nan"))
    l3 = max((c.get("size", 0) for c in ctx.get("caches", []) if c.get("level") == 3), default=0)
    cases = sorted({(n, h) for (k) in best if isinstance(k, tuple) for (_, n, h) in [k]})
    ncases = len(cases)

    wall_ratio = max((b["real_s"] / b["cpu_s"] for b in best.values()), default=float("nan"))

    def get(route, n, h, key="cpu_s", src=best):
        b = src.get((route, n, h))
        return b.get(key) if b else None

    def us(route, n, h, src=best):  # µs per particle-step (per particle for the rebuild)
        t = get(route, n, h, src=src)
        return t / n * 1e6 if t else None

    def gbs(route, n, h):  # achieved bytes/s of the traffic model, CPU time
        t, m = get(route, n, h), get(route, n, h, "model_bytes")
        return m / t / 1e9 if t and m else None

    def ratio(a, b, n, h, src=best):
        ta, tb = get(a, n, h, src=src), get(b, n, h, src=src)
        return ta / tb if ta and tb else None

    def ratios(a, b):
        return [r for r in (ratio(a, b, n, h) for n, h in cases) if r is not None]

    def spread(route, n, h):  # worst / best repetition - 1
        t = reps.get((route, n, h))
        return max(t) / min(t) - 1 if t and len(t) > 1 else None

    def f(x, fmt="{:.3g}"):
        return "-" if x is None else fmt.format(x)

    # How the timing was repeated, from the json.
    rep_small = sorted({get(r, n, h, "repetitions") for r in ROUTES for n, h in cases if n <= 100000} - {None})
    rep_large = sorted({get(r, n, h, "repetitions") for r in ROUTES for n, h in cases if n > 100000} - {None})
    it_large = sorted({get(r, n, h, "iterations") for r in ROUTES for n, h in cases if n > 100000} - {None})
    how = f"{'/'.join(map(str, rep_small))} for N <= 1e5"
    if rep_large:
        how += f", {'/'.join(map(str, rep_large))} x {'/'.join(map(str, it_large))} iterations at larger N"
    load_txt = ", ".join(f"{x:.1f}" for x in ctx.get("load_avg", []))
    pairs_per = {}
    for n, h in cases:
        p = get("Fused", n, h, "pairs")
        if p:
            pairs_per.setdefault(h, set()).add(round(p / n))
    pairs_txt = ", ".join(f"{'/'.join(map(str, sorted(v)))}{' pairs per particle' if i == 0 else ''} at h = {h:g} dx"
                          for i, (h, v) in enumerate(sorted(pairs_per.items())))

    L = ["# Rate-form SPH step: fused pair loop vs operator matrices", "",
         "Generated by `benchmarks/rate_form_step_report.py` from `benchmark.json` "
         f"(`{ctx.get('executable', '?')}`, {ctx.get('date', '')}, {ctx.get('num_cpus', '?')} CPUs at "
         f"{ctx.get('mhz_per_cpu', '?')} MHz, load average at start {load_txt}). Single thread. Times are CPU times "
         "(user + system: page faults count), so time spent waiting for a core does not count, though other jobs "
         "still share the L3 cache and memory bandwidth; best of the repetitions "
         f"({how}); wall time / CPU time was {wall_ratio:.2f}× at most.", "",
         "**Case.** Periodic square lattice n × n, dx = 1, cubic spline (support 2h), steel (E = 2.1, ν = 0.3, "
         "ρ0 = 7.8) at volume strain 1.02, plain SPH (no XSPH, viscosity or artificial stress), continuity by "
         "summation. One particle-step = one evaluation of F(y) per particle on a randomly perturbed state "
         "(displacements 1e-2 dx, velocities 1e-2 c0, densities 1e-2 ρ, deviators 1e-2 K). Neighbour list radius 2h: "
         f"{pairs_txt} (ordered, self excluded).", "",
         "**Routes.** *Fused*: `RateFormScheme<2>::rate` (the library: scratch kept between calls in a workspace the "
         "scheme owns, no per-pair arrays for these plain forms; r, |r|² of one neighbour row gathered into short row "
         "arrays, |r| and the cubic spline's (dW/dr)/r computed over the row two pairs at a time (SSE2), then the "
         "row's sums on unpacked per-particle arrays with σ/ρ² computed once per particle). *FusedPrealloc*: the reference copy of "
         "the library's old algorithm (before commit 01c0a1c: per-pair arrays r, ∇W, W, r² for every stored pair, "
         "then the pair loop) with its buffers kept between calls, which the old library did not do. *FusedOnePass*: "
         "one pass, ∇W where it is used, no per-pair arrays, no W, the particle data packed into one 64 B record with "
         "σ/ρ² precomputed. *FusedOnePassCubic*: the same with the cubic spline's (dW/dr)/r written out. "
         "*FusedHalfPairs*: that, visiting each unordered pair once and scattering to both particles. *Operator*: G^x, "
         "G^y re-assembled at the current positions into fixed storage (`assemble_operators_into`), then one sparse × "
         "(N × 7) product per axis and pointwise work. *OperatorSpMV*: the products alone on an assembled G. "
         "*Rebuild*: `find_neighbours` (µs per particle). Every route was checked against `RateFormScheme::rate` on "
         "the perturbed state, both continuity forms, before timing (limit 1e-12 relative per state block)."]
    checks = [get(r, n, h, "check") for r in ROUTES[1:7] for (n, h) in cases]
    checks = [c for c in checks if c is not None]
    if checks:
        pre = [get("FusedPrealloc", n, h, "check") for n, h in cases]
        pre = [c for c in pre if c is not None]
        L.append(f"Largest difference found: {max(checks):.1e}"
                 + (f"; FusedPrealloc's: {max(pre):.1e}" + (" (bitwise equal to the library)" if max(pre) == 0 else "")
                    if pre else "") + ".")
    if errors:
        L += ["", "**Errors:** " + "; ".join(errors)]

    L += ["", "## µs per particle-step (CPU)", "",
          "| N | h/dx | Fused | Operator | Fused/Operator | FusedPrealloc | Fused/FusedPrealloc | FusedOnePass | "
          "FusedOnePassCubic | FusedHalfPairs | OperatorSpMV | Rebuild |", "|---" * 12 + "|"]
    for n, h in cases:
        L.append(f"| {n} | {h:g} | {f(us('Fused', n, h))} | {f(us('Operator', n, h))} | "
                 f"{f(ratio('Fused', 'Operator', n, h), '{:.2f}')} | {f(us('FusedPrealloc', n, h))} | "
                 f"{f(ratio('Fused', 'FusedPrealloc', n, h), '{:.2f}')} | "
                 + " | ".join(f(us(r, n, h)) for r in ["FusedOnePass", "FusedOnePassCubic", "FusedHalfPairs",
                                                      "OperatorSpMV", "Rebuild"]) + " |")
    sp = [s for s in (spread(r, n, h) for r in ROUTES for n, h in cases) if s is not None]
    if sp:
        L += ["", f"Run-to-run noise: the repetitions of one benchmark differ by {100 * statistics.median(sp):.0f} % "
              f"(median over all benchmarks) and {100 * max(sp):.0f} % at most (CPU time, worst / best − 1)."]

    nm, hm = max(cases)
    e = get("Fused", nm, hm, "pairs")
    if e:
        e += nm
        rss = ""
        if peak_mb:
            total = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 1e9
            rss = f"; peak RSS of the whole run {peak_mb / 1e3:.2f} GB (of {total:.0f} GB)"
        L += ["", f"**Memory** at N = {nm}, h = {hm:g} dx ({e / nm:.0f} stored entries per particle incl. self): "
              f"neighbour list {(4 * e + 8 * nm) / 1e6:.0f} MB; the library's kept scratch: per-particle arrays "
              f"(x, v, v̂, ρ, V, S, σ, σ/ρ², R) {184 * nm / 1e6:.0f} MB and one row's arrays (≈ {e / nm:.0f} "
              f"entries × 88 B), no per-pair arrays (with XSPH: a ring of the pairs of the rows not yet summed, a few "
              f"lattice rows); FusedPrealloc's kept per-pair arrays {48 * e / 1e6:.0f} MB (what "
              f"the old library allocated on every call) on top of the same per-particle arrays; G^x + G^y "
              f"{24 * e / 1e6:.0f} MB{rss}."]
    L += ["", "## Bandwidth against the STREAM triad", "",
          f"Triad a = b + s c on 3 arrays, {triad_bytes / 1e6:.0f} MB in all"
          + (f" ({triad_bytes / l3:.0f}× the {l3 / 2**20:.0f} MiB L3 cache)" if l3 else "") +
          f", bytes = 24 per element (2 reads + 1 write, write-allocate not counted): **{triad / 1e9:.1f} GB/s** (best "
          "of a measurement before and after the steps).", "",
          "Bytes per step are a minimal-traffic model (the counters `model_bytes`, `nl_bytes`; "
          "`benchmarks/rate_form_step_benchmark.cpp`, `traffic()`): every array read or written counted once per pass "
          "that touches it, gathered neighbour data assumed cached (lattice order keeps a row's neighbours within "
          "±3 lattice rows, ~0.7 MB at n = 1000). Neighbour list 8 B per row + 4 B per entry per pass (library: 1 "
          "pass, its pair loop re-reads the row's indices from cache; FusedPrealloc: 2 passes); library: no per-pair "
          "traffic (the row arrays stay in cache); FusedPrealloc's per-pair arrays r, ∇W (16 B), W, r² (8 B) "
          "written and ∇W read back = 64 B per entry; operator route: list read + `set_pattern`'s comparison of "
          "list and both G patterns + 2 × 8 B of values written in assembly, then 2 × 12 B per entry (index + value) in the "
          "products; per-particle arrays (state 64 B, unpacked copies, dydt) as listed in `traffic()`.", "",
          "| N | h/dx | route | bytes / particle-step | of which index structure | achieved GB/s | % of triad |",
          "|---|---|---|---|---|---|---|"]
    table_routes = ["Fused", "FusedPrealloc", "FusedOnePassCubic", "Operator", "OperatorSpMV"]
    for n, h in cases:
        for r in table_routes:
            g = gbs(r, n, h)
            if g is None:
                continue
            L.append(f"| {n} | {h:g} | {r} | {get(r, n, h, 'model_bytes') / n:.0f} | "
                     f"{get(r, n, h, 'nl_bytes') / n:.0f} | {g:.2f} | {100 * g * 1e9 / triad:.0f} % |")

    # Where the time goes: from the old algorithm (kept buffers) to the library, then each change to the library's
    # loop, as a speed-up factor per case.
    steps = [("FusedPrealloc", "Fused", "old algorithm → library"),
             ("Fused", "FusedOnePass", "library → packed one-pass loop"),
             ("FusedOnePass", "FusedOnePassCubic", "cubic ∇W written out"),
             ("FusedOnePassCubic", "FusedHalfPairs", "each pair once"),
             ("Fused", "FusedHalfPairs", "library → all three")]
    L += ["", "## Where the time goes", "",
          "Speed-up (time of the route before the arrow / time of the route after it; above 1 the later route is "
          "faster). *old algorithm → library*: FusedPrealloc / Fused, both with buffers kept between calls, i.e. "
          "what dropping the per-pair arrays gained"
          + (" (the old library's allocation is in the comparison of the two runs below)" if before else "") +
          ". The later columns are changes to the library's loop that the library does not have. Also the "
          "library's page faults (getrusage minor faults per step; 4 KiB each, zero-filled by the kernel) and system "
          "time. `perf stat` has no hardware counters on this VM, so the split is by timing and fault counts.", "",
          "| N | h/dx | " + " | ".join(label for _, _, label in steps) +
          " | library page faults / step | library system time / CPU time | Operator: assembly share |",
          "|---|---|" + "---|" * (len(steps) + 3)]
    for n, h in cases:
        rs = [ratio(a, b, n, h) for a, b, _ in steps]
        pf, sy, fu = get("Fused", n, h, "page_faults"), get("Fused", n, h, "system_s"), get("Fused", n, h)
        op, spmv = get("Operator", n, h), get("OperatorSpMV", n, h)
        L.append(f"| {n} | {h:g} | " + " | ".join(f(r, "{:.2f}×") for r in rs) +
                 f" | {f(pf, '{:.3g}')} | {f(sy / fu * 100 if sy is not None and fu else None, '{:.1f} %')} | "
                 f"{f((op - spmv) / op * 100 if op and spmv else None, '{:.0f} %')} |")

    # The library before and after, from two runs.
    if before:
        bbest, _, bctx, _ = load(before)
        bload = ", ".join(f"{x:.1f}" for x in bctx.get("load_avg", []))
        both = [(n, h) for n, h in cases if get("Fused", n, h, src=bbest) and get("Fused", n, h)]
        L += ["", "## The library before and after commit 01c0a1c (two runs)", "",
              f"*Before*: `{os.path.basename(before)}`, {before_label}; run {bctx.get('date', '?')}, load average at "
              f"start {bload}. *Now*: this run. Two runs under different load, so the routes whose code is the same in "
              "both (FusedPrealloc, Operator, OperatorSpMV) are listed as a control: their before / now ratio is the "
              "change of machine conditions (same code, another run).", "",
              "| N | h/dx | library before (µs) | library now (µs) | library before / now | page faults / step before "
              "→ now | system time share before → now | control: FusedPrealloc before / now | Operator before / now "
              "| OperatorSpMV before / now |", "|---|---|---|---|---|---|---|---|---|---|"]
        for n, h in both:
            fb, fn = get("Fused", n, h, src=bbest), get("Fused", n, h)
            pb, pn = get("Fused", n, h, "page_faults", src=bbest), get("Fused", n, h, "page_faults")
            sb, sn = get("Fused", n, h, "system_s", src=bbest), get("Fused", n, h, "system_s")
            ctrl = []
            for r in ["FusedPrealloc", "Operator", "OperatorSpMV"]:
                tb, tn = get(r, n, h, src=bbest), get(r, n, h)
                ctrl.append(f(tb / tn if tb and tn else None, "{:.2f}"))
            L.append(f"| {n} | {h:g} | {f(fb / n * 1e6)} | {f(fn / n * 1e6)} | {fb / fn:.2f}× | "
                     f"{f(pb)} → {f(pn)} | {f(100 * sb / fb if sb is not None else None, '{:.0f} %')} → "
                     f"{f(100 * sn / fn if sn is not None else None, '{:.1f} %')} | " + " | ".join(ctrl) + " |")
        lib = [get("Fused", n, h, src=bbest) / get("Fused", n, h) for n, h in both]
        controls = ["FusedPrealloc", "Operator", "OperatorSpMV"]

        def control_ratios(n, h):
            return [get(r, n, h, src=bbest) / get(r, n, h) for r in controls
                    if get(r, n, h, src=bbest) and get(r, n, h)]

        ctl = [c for n, h in both for c in control_ratios(n, h)]
        if lib and ctl:
            above = sum(1 for n, h in both if get("Fused", n, h, src=bbest) / get("Fused", n, h) >
                        max(control_ratios(n, h), default=float("inf")))
            L += ["", f"The library's before / now is {fmt_range(lib, suffix='×')}, the controls' {fmt_range(ctl)}; in "
                  f"{above} of {len(both)} cases the library's ratio exceeds every control's in the same case."]

    # The library before and after the row pipeline, in this run.
    ba = [(label, n, h, get(b, n, h), get(a, n, h), get(b, n, h, "check"), get(b, n, h, "values_compared"))
          for label, b, a in BEFORE_AFTER for n, h in cases]
    ba = [r for r in ba if r[3] and r[4]]
    if ba:
        L += ["", "## The library before and after its row pipeline (same run)", "",
              "*Before*: LibraryBefore, the reference copy of `RateFormScheme<2>::evaluate` as it was before the row "
              "pipeline (plain gradient, symmetric momentum, free particles): |r|, W and ∇W recomputed in every pass "
              "that reads them, σ_j/ρ_j² and f_ij^n per pair, R_i through `artificial_stress()`. *After*: the library "
              "(`RateFormScheme<2>::rate`). *plain SPH*: the case above (route Fused). *GMS*: the Gray–Monaghan–Swift "
              "configuration of the plate, rings and slab scenes: divergence continuity, XSPH 0.5, viscosity on "
              "compression (α 0.06, β 1.5), artificial stress 0.3 with n = 4, ρ0 = K = 1, μ = 0.22 at volume strain "
              "1.02, h = 1.5 dx. Before timing, the two were compared bit for bit (memcmp) on perturbed states of each "
              "lattice (plain and GMS options, both continuity forms each).", "",
              "| configuration | N | h/dx | before (µs per particle-evaluation) | after | before / after | values "
              "compared | values differing |", "|---|---|---|---|---|---|---|---|"]
        for label, n, h, tb, ta, chk, cmp in ba:
            L.append(f"| {label} | {n} | {h:g} | {tb / n * 1e6:.3g} | {ta / n * 1e6:.3g} | {tb / ta:.2f}× | "
                     f"{f(cmp, '{:.0f}')} | {f(chk, '{:.0f}')} |")
        for label, _, _ in BEFORE_AFTER:
            r = [tb / ta for lab, n, h, tb, ta, _, _ in ba if lab == label]
            if r:
                L.append(f"{'' if label == BEFORE_AFTER[0][0] else ' '}{label}: before / after "
                         f"{fmt_range(r, suffix='×')}.")
        L[-len(BEFORE_AFTER):] = ["", " ".join(x.strip() for x in L[-len(BEFORE_AFTER):])]

    # Reading.
    nmax = max(n for n, _ in cases)
    L += ["", "## Which route is faster, and why", ""]
    fo = [(n, h, ratio("Fused", "Operator", n, h)) for n, h in cases]
    fo = [x for x in fo if x[2] is not None]
    if fo:
        rng = fmt_range([r for *_, r in fo])

        def noisy(n, h, r):  # the difference is within the spread of the two routes' repetitions
            a, b = spread("Fused", n, h), spread("Operator", n, h)
            return a is not None and b is not None and max(r, 1 / r) - 1 <= max(a, b)

        clear = [(n, h, r) for n, h, r in fo if not noisy(n, h, r)]
        lib_wins = sum(1 for *_, r in clear if r < 1)
        faster = sum(1 for *_, r in fo if r < 1)
        if len(clear) == len(fo) and lib_wins in (0, len(clear)):
            who, other = (("library's fused loop", "operator route") if lib_wins else
                          ("operator route", "library's fused loop"))
            head = (f"**The {who} is faster than the {other} in every case, beyond the spread of the repetitions: "
                    f"Fused / Operator time {rng}.**")
        elif not clear:
            head = (f"**Neither route is measurably faster: Fused / Operator time is {rng} (the library faster in "
                    f"{faster} of {len(fo)} cases), and in every case the difference is within the spread of the two "
                    "routes' repetitions.**")
        else:
            head = (f"**Neither route is consistently faster: Fused / Operator time is {rng}, the library faster in "
                    f"{faster} of {len(fo)} cases; the difference exceeds the spread of the two routes' repetitions "
                    f"only at " + ", ".join(f"N = {n}, h = {h:g} dx ({'library' if r < 1 else 'operator route'} "
                                            f"faster)" for n, h, r in clear) + ".**")
        L.append(f"- {head} Both routes evaluate ∇W once per stored pair: the library uses "
                 "it at once in the row's sums, the operator route writes it into G in the assembly and reads it back "
                 "in two sparse products.")
    fp = ratios("Fused", "FusedPrealloc")
    pfs = [get("Fused", n, h, "page_faults") for n, h in cases]
    pfs = [p for p in pfs if p is not None]
    if fp:
        beyond = 0
        for n, h in cases:
            r, a, b = ratio("Fused", "FusedPrealloc", n, h), spread("Fused", n, h), spread("FusedPrealloc", n, h)
            beyond += r is not None and a is not None and b is not None and max(r, 1 / r) - 1 > max(a, b)
        L.append(f"- Against its old algorithm with the buffers kept (FusedPrealloc) the library's time is "
                 f"{fmt_range(fp)} (Fused / FusedPrealloc), faster in {sum(1 for r in fp if r < 1)} of {len(fp)} "
                 f"cases ({beyond} of them beyond the spread of the two routes' repetitions); the library no longer "
                 "writes r, ∇W, W, r² for every pair and reads ∇W back in a second pass (64 B per stored pair in the "
                 "traffic model). "
                 + (f"Library page faults per step: {fmt_range(pfs, '{:.3g}')}"
                    + (" (its scratch is kept between calls)." if max(pfs) < 10 else ".") if pfs else ""))
    for h in sorted({h for n, h in cases if n == nmax}):
        fu, pre, op, spmv = (get(r, nmax, h) for r in ["Fused", "FusedPrealloc", "Operator", "OperatorSpMV"])
        if None in (fu, pre, op, spmv):
            continue
        sys_s = get("Fused", nmax, h, "system_s")
        L.append(f"- N = {nmax}, h = {h:g} dx: library {fu:.3f} s per step ({1e3 * sys_s:.1f} ms of it system time), "
                 f"old algorithm with kept buffers {pre:.3f} s, operator route {op:.3f} s (Fused / Operator "
                 f"{fu / op:.2f}), of which {op - spmv:.3f} s ({100 * (op - spmv) / op:.0f} %) re-assembling G, i.e. "
                 f"the same per-pair kernel work, and {spmv:.3f} s in the products. The library's whole step is "
                 f"{fu / (op - spmv):.2f}× the operator route's assembly alone.")
    g = [(n, h, gbs("OperatorSpMV", n, h), gbs("FusedPrealloc", n, h), gbs("Fused", n, h)) for n, h in cases]
    g = [x for x in g if None not in x]
    if g:
        allpct = [100 * gbs(r, n, h) * 1e9 / triad for r in table_routes for n, h in cases if gbs(r, n, h)]
        bound = ("No route is memory-bandwidth-bound" if max(allpct) < 50 else
                 f"The busiest route reaches {max(allpct):.0f} % of the triad")
        cub = ratios("FusedOnePass", "FusedOnePassCubic")
        L.append(f"- {bound}. By the traffic model the library moves {fmt_range([x[4] for x in g], '{:.1f}')} GB/s "
                 f"({fmt_range([100 * x[4] * 1e9 / triad for x in g], '{:.0f}')} % of the triad), the old algorithm "
                 f"with kept buffers {fmt_range([x[3] for x in g], '{:.1f}')} GB/s, and the bare products "
                 f"{fmt_range([x[2] for x in g], '{:.1f}')} GB/s "
                 f"(≤ {100 * max(x[2] for x in g) * 1e9 / triad:.0f} %). "
                 "What the fused loops spend their time on is per-pair arithmetic: sqrt, the division (dW/dr)/r, and "
                 "`Kernel::d1`'s generic path (divisions by h, the family switch, |s| and sign handling), most of which "
                 "the written-out cubic gradient removes"
                 + (f" (FusedOnePass / FusedOnePassCubic {fmt_range(cub)})." if cub else "."))
    reb = [(ratio("Rebuild", "Fused", n, h), ratio("Rebuild", "FusedHalfPairs", n, h)) for n, h in cases]
    reb = [r for r in reb if None not in r]
    if reb:
        L.append(f"- A neighbour rebuild (`find_neighbours`, radius 2h) costs "
                 f"{fmt_range([r[0] for r in reb], '{:.1f}')} "
                 f"library steps and {fmt_range([r[1] for r in reb], '{:.1f}')} steps of the fastest loop "
                 "(FusedHalfPairs): how often the list is rebuilt (skin) matters as much as the step.")

    # What is left, with the gains measured above (range over the cases).
    shares = [100 * (get("Operator", n, h) - get("OperatorSpMV", n, h)) / get("Operator", n, h) for n, h in cases
              if get("Operator", n, h) and get("OperatorSpMV", n, h)]
    assembly = fmt_range(shares, "{:.0f}", " %") if shares else "most"

    def span(a, b):
        r = ratios(a, b)
        if not r:
            return "-"
        slower = sum(1 for x in r if x < 1)
        return fmt_range(r, suffix="×") + (f" (no gain in {slower} of {len(r)} cases)" if slower else "")

    L += ["", f"## What is left to gain in `RateFormScheme::evaluate` (measured here, range over the {ncases} cases)",
          "",
          "Commit 01c0a1c keeps the scratch between calls and drops the per-pair arrays of the plain forms: against "
          f"the old algorithm with kept buffers the library gained {span('FusedPrealloc', 'Fused')} (this run)"
          + (", against the old library see the comparison of the two runs above" if before else "") + ". Further "
          "changes, each measured on top of the previous one:", "",
          "1. Pack the per-particle data a neighbour contributes into one record (x, v, σ/ρ², V = m/ρ: one 64 B "
          "cache line) instead of the separate unpacked arrays, and use ∇W where it is computed instead of through "
          "the row arrays (the library already computes σ_j/ρ_j² once per particle and skips the zero pair matrix) "
          f"(Fused → FusedOnePass): {span('Fused', 'FusedOnePass')}.",
          "2. A fast kernel-gradient path: (dW/dr)/r per family with the constants (σ/h^(d+2)) precomputed, the "
          "family chosen once outside the pair loop (a functor/template argument), no |s|/sign handling for r ≥ 0 "
          "(the library has it for the cubic spline only, bitwise equal to `Kernel::d1`, so FusedOnePass, which "
          f"calls `Kernel::d1`, is the slower baseline here): {span('FusedOnePass', 'FusedOnePassCubic')}. The same "
          f"helper would speed up `assemble_operators` ({assembly} of the operator route).",
          "3. Visit each unordered pair once (g_ji = -g_ij; scatter to j): "
          f"{span('FusedOnePassCubic', 'FusedHalfPairs')}; "
          "only for the symmetric plain forms, and it blocks a simple gather-parallel loop, so lowest priority.",
          "", f"All three: {span('Fused', 'FusedHalfPairs')} over the library as it is."]
    open(out, "w").write("\n".join(L) + "\n")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("src")
    ap.add_argument("out")
    ap.add_argument("peak_mb", nargs="?", type=float)
    ap.add_argument("--before")
    ap.add_argument("--before-label", default=BEFORE_LABEL)
    a = ap.parse_args()
    main(a.src, a.out, a.peak_mb, a.before, a.before_label)
