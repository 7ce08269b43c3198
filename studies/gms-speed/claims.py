"""Headline claims of gms-speed (results/gms-speed/), run by tests/scripts/claims_test.py.

benchmark.md is written by benchmarks/gms_step_report.py from benchmark.json (no summary.md.in). Each benchmark is
taken at its fastest repetition, as the report and scripts/results_map.py take it. Only ratios within the one run are
asserted, never seconds: the 0.4 µs target of issue 10 is an absolute time and is not a claim here."""
import json

from claims import approx, check, md_table

SCENES = ("RingsSI", "Lattice99856", "Lattice1000000")
LOOPS = {"rows": "", "pairs": "/pairs"}


def _best(r):
    """{base name: fastest iteration run}, base name e.g. 'RunOneRate/RingsSI/pairs/skin:0.75'."""
    best = {}
    for b in json.loads(r.text("benchmark.json"))["benchmarks"]:
        if b.get("run_type") != "iteration" or b.get("error_occurred"):
            continue
        k = b["name"].split("/iterations")[0].split("/min_time")[0]
        if k not in best or b["real_time"] < best[k]["real_time"]:
            best[k] = b
    return best


def _get(best, name):
    check(name in best, f"results/gms-speed/benchmark.json: no benchmark {name}")
    return best[name]


def _run_us(best, name):
    """µs per particle-step of a whole run (all SI runs share the unit of their time_unit: ms)."""
    b = _get(best, name)
    check(b["time_unit"] == "ms", f"{name}: time unit {b['time_unit']}")
    return 1e3 * b["real_time"] / (b["particles"] * b["steps"])


RUNS = {("rows", 2, 0.5): "Run/RingsSI", ("pairs", 2, 0.5): "Run/RingsSI/pairs",
        ("rows", 1, 0.5): "RunOneRate/RingsSI", ("pairs", 1, 0.5): "RunOneRate/RingsSI/pairs",
        ("pairs", 1, 0.75): "RunOneRate/RingsSI/pairs/skin:0.75", ("pairs", 1, 1.0): "RunOneRate/RingsSI/pairs/skin:1"}


def claim_rings_run_speedups(r):
    """The whole 300-step SI rings run: the pair loop, which computes each pair once instead of twice, is at least
    1.5x faster than the row loop with 2 and with 1 rate evaluation per step (and at most 3x); reusing the corrector's
    rate (1 evaluation per step instead of 2) makes either loop 1.3-2x faster (2 would be the evaluations alone: the
    builds and the integration do not halve); so pairs with 1 evaluation (the default of `sphstab scene rings`) is
    2-6x the row loop with 2. The bands are the statements, not one machine's numbers (they were 1.8-2.2, 1.5-1.8
    and 3.2-3.6 on the machine of 2026-12-03; the ratios of each run are in benchmark.md's speed-up column, checked
    here against the best times)."""
    best = _best(r)
    us = {k: _run_us(best, name) for k, name in RUNS.items()}
    base = us[("rows", 2, 0.5)]
    for rates in (2, 1):
        s = us[("rows", rates, 0.5)] / us[("pairs", rates, 0.5)]
        check(1.5 <= s <= 3.0, f"{rates} evaluations: pairs {s:.3g}x rows")
    for loop in LOOPS:
        s = us[(loop, 2, 0.5)] / us[(loop, 1, 0.5)]
        check(1.3 <= s <= 2.0, f"{loop}: one rate evaluation {s:.3g}x faster than two")
    s = base / us[("pairs", 1, 0.5)]
    check(2.0 <= s <= 6.0, f"pairs, 1 evaluation: {s:.3g}x rows, 2 evaluations")
    table = [row for row in md_table(r.text("benchmark.md")) if len(row) == 9]
    check(len(table) == len(RUNS), f"benchmark.md rings table has {len(table)} rows, expected {len(RUNS)}")
    for row in table:
        key = (row[0], int(row[1]), float(row[2]))
        approx(float(row[8]), base / us[key], f"benchmark.md speed-up {key}", abs_=0.0051)
        check(int(row[5]) == int(_get(best, RUNS[key])["builds"]), f"benchmark.md builds {key}")
    return ", ".join(f"{k[0]}/{k[1]}/{k[2]:g}: {base / v:.2f}x" for k, v in us.items())


def claim_skin_sets_only_the_cost(r):
    """Skins 0.5, 0.75 and 1 dx (pairs loop, 1 evaluation; same end state, checked by the benchmark): a larger skin
    needs fewer builds (56 > 39 > 30 over 300 steps), and it saves at most the 0.5 dx run's share of rebuilds (its
    builds per step times one rebuild of the Verlet list, Rebuild/RingsSI/pairs, over its time per particle-step): a
    larger skin can at most save the builds it avoids, and pays for them with longer lists. Which skin is fastest
    depends on that balance (a larger one was, before the search's and the pair scalars' vector clones made rebuilds
    and list entries cheaper); the returned line says which it is in this run."""
    best = _best(r)
    skins = [("pairs", 1, s) for s in (0.5, 0.75, 1.0)]
    builds = [_get(best, RUNS[k])["builds"] for k in skins]
    check(builds[0] > builds[1] > builds[2], f"builds for skins 0.5/0.75/1: {builds}")
    us = [_run_us(best, RUNS[k]) for k in skins]
    run = _get(best, RUNS[skins[0]])
    reb = _get(best, "Rebuild/RingsSI/pairs")
    rebuild_share = (run["builds"] / run["steps"]) * 1e3 * reb["real_time"] / reb["particles"] / us[0]
    for k, u in zip(skins[1:], us[1:]):
        check(1 - u / us[0] < rebuild_share,
              f"skin {k[2]}: saves {100 * (1 - u / us[0]):.3g} % of the 0.5 dx run (its rebuilds: "
              f"{100 * rebuild_share:.3g} %)")
    fastest = min(skins, key=lambda k: _run_us(best, RUNS[k]))
    return f"builds {builds[0]:g}/{builds[1]:g}/{builds[2]:g}; 0.5 dx / larger skin {us[0] / us[1]:.3g}, " \
           f"{us[0] / us[2]:.3g}; rebuilds {100 * rebuild_share:.3g} % of the 0.5 dx run; fastest skin {fastest[2]:g} dx"


def claim_rate_evaluations_dominate_compute_bound(r):
    """Split (µs per particle, recomputed from the best times): the two rate evaluations are 80-100 % of the
    fixed-list step in every scene and loop (integration the rest; up to 105 % accepted, because the step and the
    evaluations are timed apart, each the best of its repetitions, and the integration is a few per cent), and the fixed-list step takes at least 6x its
    bandwidth bound (model bytes over the best triad of the run; 6-16x on a machine of 13.8 GB/s, 17-71x on one of
    36 GB/s): the step is compute-bound; the pair loop's evaluation is
    faster than the row loop's in every scene. benchmark.md's split table is these numbers."""
    best = _best(r)
    bw = max(_get(best, n)["bytes_per_second"] for n in ("Triad", "TriadAgain"))
    table = {(row[0], row[1]): row for row in md_table(r.text("benchmark.md")) if len(row) == 11}
    share, bound, rate = [], [], {}
    for scene in SCENES:
        for loop, suf in LOOPS.items():
            fix = _get(best, f"StepFixedList/{scene}{suf}")
            rb = _get(best, f"Rate/{scene}{suf}")
            n = fix["particles"]
            fix_us = 1e3 * fix["real_time"] / (n * fix["steps"])
            rate_us = 1e3 * rb["real_time"] / (n * rb["evaluations"])
            bound_us = 1e6 * fix["model_bytes"] / bw / n
            rate[(scene, loop)] = rate_us
            share.append(2 * rate_us / fix_us)
            bound.append(fix_us / bound_us)
            check(0.80 <= share[-1] <= 1.05, f"{scene} {loop}: 2 evaluations {100 * share[-1]:.3g} % of the step")
            check(bound[-1] >= 6, f"{scene} {loop}: fixed-list step {bound[-1]:.3g}x its bound")
            row = table[(scene, loop)]
            approx(float(row[4]), 2 * rate_us, f"benchmark.md {scene} {loop} 2 rate evaluations", rel=0.006)
            approx(float(row[6]), fix_us, f"benchmark.md {scene} {loop} fixed-list step", rel=0.006)
            approx(float(row[10]), fix_us / bound_us, f"benchmark.md {scene} {loop} step / bound", abs_=0.051)
        check(rate[(scene, "pairs")] < rate[(scene, "rows")], f"{scene}: pair-loop evaluation not faster")
    return f"2 evaluations {100 * min(share):.0f}-{100 * max(share):.0f} % of the step; step " \
           f"{min(bound):.3g}-{max(bound):.3g}x its bound"


def claim_sum_of_parts_understates_the_run(r):
    """The fixed-list step plus the builds per step (the largest over gms-rings' SI runs, also the benchmark run's
    56 / 300) times one rebuild understates the measured whole run for both loops, because the run's Verlet list
    (support + 0.5 dx skin) holds about 40 % more pairs per particle than the fixed list (34.3 against 24.6)."""
    best = _best(r)
    si = [x for x in r.other("gms-rings").csv("runs.csv") if x["units"] == "SI"]
    check(si, "results/gms-rings/runs.csv has no SI runs")
    per_step = max(x["neighbour_builds"] / x["steps"] for x in si)
    run = _get(best, "Run/RingsSI")
    approx(per_step, run["builds"] / run["steps"], "builds per step: gms-rings SI runs vs the benchmark's run",
           rel=0.01)
    out = []
    for loop, suf in LOOPS.items():
        fix = _get(best, f"StepFixedList/RingsSI{suf}")
        reb = _get(best, f"Rebuild/RingsSI{suf}")
        n = fix["particles"]
        estimate = 1e3 * fix["real_time"] / (n * fix["steps"]) + per_step * 1e3 * reb["real_time"] / n
        measured = _run_us(best, RUNS[(loop, 2, 0.5)])
        check(estimate < measured, f"{loop}: estimate {estimate:.3g} not below the measured run {measured:.3g}")
        more = reb["pairs_rebuilt"] / reb["pairs"]
        check(1.3 <= more <= 1.5, f"{loop}: Verlet list / fixed list pairs {more:.3g}")
        stated = r.stated(rf"- {loop}: the fixed-list step .*? = ([\d.]+) µs per particle-step, against ([\d.]+) µs",
                          text=r.text("benchmark.md"), where="benchmark.md", convert=False)
        approx(float(stated), estimate, f"benchmark.md {loop} estimate", rel=0.006)
        out.append(f"{loop} {estimate / measured:.2f} of the run")
    return f"estimate = {', '.join(out)}; Verlet list {more:.2f}x the fixed list's pairs"
