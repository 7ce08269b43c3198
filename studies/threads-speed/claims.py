"""Headline claims of threads-speed (results/threads-speed/), run by tests/scripts/claims_test.py. Only ratios of
runs in the one study run are asserted (speed-ups, throughput), never seconds; every value and verdict of the summary
is recomputed from runs.csv."""
from claims import approx, check, select

CASES = ("rings", "lattice")
MODES = ("adaptive", "adaptive-short-spin", "fixed", "fixed-short-spin", "fixed-libgomp-default")
TARGET = {"rings": 1.5, "lattice": 1.8}  # issue 35


def _best(rows, case, condition, threads, mode="adaptive"):
    mine = select(rows, case=case, condition=condition, threads=threads, mode=mode)
    check(mine, f"no runs of {case} {condition} {threads} thread(s) {mode}")
    return min(x["wall_s"] for x in mine)


def claim_every_configuration_ran_its_repetitions(r):
    """Each case has reps runs of one thread and of two threads in each mode, idle and busy, and reps pairs of
    side-by-side one-thread runs."""
    rows, reps = r.csv("runs.csv"), r.num("reps")
    for case in CASES:
        for condition in ("idle", "busy"):
            check(len(select(rows, case=case, condition=condition, threads=1)) == reps, f"{case} {condition}: 1 thread")
            for p in MODES:
                n = len(select(rows, case=case, condition=condition, threads=2, mode=p))
                check(n == reps, f"{case} {condition} {p}: {n} runs, expected {reps}")
        check(len(select(rows, case=case, condition="two-processes")) == 2 * reps, f"{case}: side-by-side pairs")
    return f"{len(rows)} runs, {reps} per configuration"


def claim_every_run_of_a_case_ends_in_the_same_bits(r):
    """All runs of a case (1 or 2 threads, any mode, idle or busy, alone or side by side) end in the same last
    record: threads change the time, not the result."""
    for case in CASES:
        digests = {x["final_row_digest"] for x in select(r.csv("runs.csv"), case=case)}
        check(len(digests) == 1, f"{case}: {len(digests)} different final records")
        check(r.key(f"{case}_same_bits") == "yes", f"{case}: summary says {r.key(f'{case}_same_bits')}")
    return "one final record per case"


def claim_speedups_throughput_and_verdicts_are_the_csv(r):
    """The summary's table (every mode), speed-ups, two-process throughput and verdicts (target when idle; never slower
    idle and busy) are recomputed from runs.csv at the fastest run of each configuration."""
    rows, found = r.csv("runs.csv"), []
    table = {(c[0], c[1], c[2]): c for c in (line.strip("| ").split(" | ") for line in r.key("table").splitlines())}
    for case in CASES:
        t1 = _best(rows, case, "idle", 1)
        pair = select(rows, case=case, condition="two-processes")
        pair_wall = min(max(x["wall_s"] for x in pair if x["rep"] == k) for k in {x["rep"] for x in pair})
        throughput = 2 * t1 / pair_wall
        approx(r.num(f"{case}_two_process_throughput"), throughput, f"{case} throughput", abs_=0.006)
        ups = {}
        for condition in ("idle", "busy"):
            one = _best(rows, case, condition, 1)
            for p in MODES:
                ups[(condition, p)] = one / _best(rows, case, condition, 2, p)
                cells = table.get((case, condition, p))
                check(cells is not None, f"table: no row {case} {condition} {p}")
                approx(float(cells[5].strip("*")), ups[(condition, p)], f"table {case} {condition} {p}", abs_=0.006)
                if condition == "idle":
                    approx(float(cells[6]), ups[(condition, p)] / throughput, f"table {case} {p} / throughput",
                           abs_=0.006)
            approx(r.num(f"{case}_{condition}_adaptive_speedup"), ups[(condition, "adaptive")],
                   f"{case} {condition} adaptive", abs_=0.006)
        met = ups[("idle", "adaptive")] >= TARGET[case]
        check(r.key(f"{case}_target_verdict") == ("met" if met else "not met"), f"{case}: target verdict")
        never = min(ups[("idle", "adaptive")], ups[("busy", "adaptive")]) >= 1.0
        check(r.key(f"{case}_never_slower") == ("met" if never else "not met"), f"{case}: never-slower verdict")
        found.append(f"{case} idle {ups[('idle', 'adaptive')]:.2f}x, busy {ups[('busy', 'adaptive')]:.2f}x")
    return "; ".join(found)


def claim_detection_floor_and_reach_are_the_csv(r):
    """The floor table (the one-thread runs' spread per condition, the adaptive two-thread change, and whether the
    change is beyond the spread) and whether each target lies within the machine's two-process throughput are
    recomputed from runs.csv."""
    rows, found = r.csv("runs.csv"), []
    table = {(c[0], c[1]): c for c in (line.strip("| ").split(" | ") for line in r.key("floor_table").splitlines())}
    for case in CASES:
        t1 = _best(rows, case, "idle", 1)
        pair = select(rows, case=case, condition="two-processes")
        throughput = 2 * t1 / min(max(x["wall_s"] for x in pair if x["rep"] == k) for k in {x["rep"] for x in pair})
        reach = "within" if TARGET[case] <= throughput else "above"
        check(r.key(f"{case}_target_reach") == reach, f"{case}: target reach {r.key(f'{case}_target_reach')}")
        for condition in ("idle", "busy"):
            ones = [x["wall_s"] for x in select(rows, case=case, condition=condition, threads=1)]
            spread = max(ones) / min(ones) - 1
            change = min(ones) / _best(rows, case, condition, 2) - 1
            cells = table.get((case, condition))
            check(cells is not None, f"floor table: no row {case} {condition}")
            approx(float(cells[2].rstrip(" %")), 100 * spread, f"{case} {condition} spread", abs_=0.051)
            approx(float(cells[3].rstrip(" %")), 100 * change, f"{case} {condition} change", abs_=0.051)
            word = ("faster" if change > 0 else "slower") if abs(change) > spread else "no difference beyond the spread"
            check(cells[4] == word, f"{case} {condition}: '{cells[4]}', expected '{word}'")
            found.append(f"{case} {condition} {100 * change:+.1f} % (spread {100 * spread:.1f} %): {word}")
        found.append(f"{case} target {reach} throughput {throughput:.2f}")
    return "; ".join(found)
