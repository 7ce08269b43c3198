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
