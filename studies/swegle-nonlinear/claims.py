"""Headline claims of swegle-nonlinear (results/swegle-nonlinear/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, md_table, select, verdict_class

PC, LF = "predictor-corrector", "leapfrog"


def _smallest_kick(runs):
    v0 = min(x["v0"] for x in runs)
    return [x for x in runs if x["v0"] == v0]


def claim_verdicts_follow_the_rules(r):
    """Every verdict in runs.csv is the class of its two rates (gamma_linear_class, gamma_map_class) against the
    floor ln(onset) / (2 t_end); one floor for the study."""
    floor = math.log(r.num("onset")) / (2 * r.num("t_end"))
    approx(r.num("floor"), floor, "detection floor", rel=2e-3)
    runs = r.csv("runs.csv")
    for x in runs:
        approx(x["floor"], floor, f"{x.where()} floor", rel=1e-5)
        want = verdict_class(x["gamma_linear_class"], x["gamma_map_class"], x["floor"])
        check(x["verdict"] == want, f"{x.where()}: verdict {x['verdict']}, the rules give {want}")
    return f"{len(runs)} runs"


def claim_leapfrog_adds_no_growth(r):
    """The staggered leap-frog below its limit is neutral on a neutral spectrum: no run of it is class I, and its
    map reproduces J's growth where J grows (U rows: gamma_M within 1 % of gamma_J)."""
    rows = select(r.csv("runs.csv"), integrator=LF)
    check(all(x["verdict"] in ("S", "U") for x in rows), "a leap-frog run of class I or B")
    for x in rows:
        if x["verdict"] == "U":
            approx(x["gamma_map_class"], x["gamma_linear_class"], f"{x.where()} leap-frog map against J", rel=0.01)
    return f"{len(rows)} leap-frog runs, classes {sorted({x['verdict'] for x in rows})}"


def claim_semi_discrete_growth_is_measured(r):
    """Where J grows (U), the smallest kick's runs grow at gamma_J with both integrators and at dt/2: the measured
    rate within 2 % of gamma_linear_class."""
    n = 0
    for x in _smallest_kick(r.csv("runs.csv")):
        if x["verdict"] != "U":
            continue
        check(x["grew"] == 1, f"{x.where()}: a class-U run that did not grow")
        approx(x["gamma_measured"], x["gamma_linear_class"], f"{x.where()} measured against gamma_J", rel=0.02)
        n += 1
    check(n >= 10, f"only {n} class-U runs at the smallest kick")
    return f"{n} class-U runs grow at gamma_J (2 %)"


def claim_integrator_growth_falls_with_dt(r):
    """Where only the predictor-corrector's map grows (I at dt), the map's rate falls by the dt^3 law at dt/2 (ratio 8
    as dt -> 0; 7.6-8.5 here, the higher orders of omega dt and the uncorrected positions' dt^3/4 Q J S J term under
    pre-stress: between 7 and 9 asserted), the dt/2 class is S, and no run at dt/2 or with the leap-frog grows."""
    runs = _smallest_kick(r.csv("runs.csv"))
    n = 0
    for x in runs:
        if x["integrator"] != PC or x["verdict"] != "I":
            continue
        same = [y for y in runs if y["formulation"] == x["formulation"] and y["xi"] == x["xi"]]
        half = [y for y in same if y["integrator"] == PC and y["dt"] < x["dt"]]
        lf = [y for y in same if y["integrator"] == LF]
        check(len(half) == 1 and len(lf) == 1, f"{x.where()}: dt/2 and leap-frog rows")
        ratio = x["gamma_map_class"] / half[0]["gamma_map_class"]
        check(7.0 <= ratio <= 9.0, f"{x.where()}: map rate falls {ratio:.3g}x at dt/2, not the dt^3 law")
        check(half[0]["verdict"] == "S" and half[0]["grew"] == 0, f"{half[0].where()}: dt/2 not S or grew")
        check(lf[0]["verdict"] == "S" and lf[0]["grew"] == 0, f"{lf[0].where()}: leap-frog not S or grew")
        n += 1
    check(n >= 3, f"only {n} class-I cases")
    return f"{n} class-I cases: S at dt/2 and with the leap-frog, no growth there"


def claim_verdict_lists_are_the_classes(r):
    """The summary's lists name exactly the (formulation, xi) of each class with the predictor-corrector at dt."""
    runs = [x for x in _smallest_kick(r.csv("runs.csv")) if x["integrator"] == PC]
    dt = max(x["dt"] for x in runs)
    at_dt = [x for x in runs if x["dt"] == dt]
    for key, classes in (("semi_list", ("U", "B")), ("integrator_list", ("I",)), ("stable_list", ("S",))):
        want = sorted(f"`{x['formulation']}` ξ = {x['xi']:.2f}" for x in at_dt if x["verdict"] in classes)
        got = sorted(line[2:].split(":")[0] for line in r.key(key).splitlines() if line.startswith("- `"))
        check(got == want, f"{key} names {got}, runs.csv gives {want}")
    return "semi, integrator and stable lists match runs.csv"


def claim_dt_table_is_runs_csv(r):
    """The time-step table's map rates and classes are the runs.csv rows at dt and dt/2."""
    runs = [x for x in _smallest_kick(r.csv("runs.csv")) if x["integrator"] == PC]
    dt = max(x["dt"] for x in runs)
    for row in md_table(r.key("dt_table")):
        form, xi = row[0].replace("**", ""), float(row[1])
        for col, pick in ((5, lambda x: x["dt"] == dt), (6, lambda x: x["dt"] < dt)):
            x = [y for y in runs if y["formulation"] == form and y["xi"] == xi and pick(y)]
            check(len(x) == 1, f"dt_table {form} {xi}: {len(x)} rows")
            rate, letter = row[col].split()
            check(letter == x[0]["verdict"], f"{x[0].where()}: class {x[0]['verdict']}, table {row[col]}")
            approx(float(rate), x[0]["gamma_map_class"], f"{x[0].where()} gamma_M in the table", rel=0.01)
    return "dt table matches runs.csv"
