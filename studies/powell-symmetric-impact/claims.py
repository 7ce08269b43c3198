"""Headline claims of powell-symmetric-impact (results/powell-symmetric-impact/), run by tests/scripts/claims_test.py."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import impact_claims as ic  # noqa: E402
from claims import approx, check  # noqa: E402

FORMS = ("sph", "ncsph", "ssph", "tl")
LABEL = {"sph": "basic SPH", "ncsph": "NCSPH", "ssph": "S-SPH", "tl": "TL-SPH"}


def claim_completed_counts_follow_runs_csv(r):
    """The headline's 'completed k of n' per formulation and case is the count of status 'completed' in runs.csv."""
    runs = r.csv("runs.csv")
    for case in ("compression", "expansion"):
        for f in FORMS:
            rows = [x for x in runs if x["formulation"] == f and x["case"] == case]
            done = sum(x["status"] == "completed" for x in rows)
            want = f"{done} of {len(rows)}"
            check(r.key(f"{case}_{f}_completed") == want, f"{case} {f}: summary "
                  f"'{r.key(f'{case}_{f}_completed')}', runs.csv {want}")
    return f"{len(runs)} runs"


def claim_first_stops_follow_runs_csv(r):
    """Each formulation's 'first stop' per case is the status and time of its run that stopped first (runs.csv)."""
    return ", ".join(ic.first_stops(r, FORMS, case, "{case}_{form}_first_stop")
                     for case in ("compression", "expansion"))


def claim_least_error_is_the_named_run(r):
    """'Least e_ke among the completed runs' names the completed run of least e_ke in errors.csv, per case."""
    errors = r.csv("errors.csv")
    for case in ("compression", "expansion"):
        done = [x for x in errors if x["case"] == case and x["status"] == "completed"]
        best = min(done, key=lambda x: x["e_ke"])
        want = f"{LABEL[best['formulation']]} at dx = {best['dx']:g}"
        check(r.key(f"{case}_best") == want, f"{case}: summary names '{r.key(f'{case}_best')}', errors.csv {want}")
        approx(r.num(f"{case}_best_e_ke"), best["e_ke"], f"{case} least e_ke", rel=5e-3)
    return "compression and expansion"


def claim_fe_error_is_below_every_sph_difference(r):
    """The FE reference's own kinetic-energy error (200² against 400², which bounds the 400² error for a converging
    mesh) is smaller than every SPH run's e_ke: the differences judged are not FE's."""
    fe = r.csv("fe_errors.csv")
    errors = r.csv("errors.csv")
    worst_fe = max(x["e_ke"] for x in fe if x["model"] == "linear" and x["elements_per_side"] == 200)
    least_sph = min(x["e_ke"] for x in errors)
    check(worst_fe < least_sph, f"FE 200² e_ke {worst_fe} >= least SPH e_ke {least_sph}")
    coarse = max(x["e_ke"] for x in fe if x["model"] == "linear" and x["elements_per_side"] == 100)
    check(coarse > worst_fe, f"FE e_ke does not decrease with the mesh: 100² {coarse}, 200² {worst_fe}")
    return f"FE {worst_fe:.3g} < SPH {least_sph:.3g}"


def claim_kinetic_energy_error_recomputed(r):
    """e_ke of every run at the snapshot resolution, recomputed here from signals.csv and the FE reference's own
    series in fe_signals.csv (every second FE record: agreement to 1 %), equals errors.csv's."""
    dx = r.num("snapshot_spacing")
    v0 = r.num("speed")
    ke0 = 0.5 * 7.8 * v0 * v0
    finest = int(r.key("fe_finest"))
    sig = r.csv("signals.csv")
    n = 0
    for x in r.csv("errors.csv"):
        if abs(x["dx"] - dx) > 1e-12:
            continue
        fe = [q for q in r.csv("fe_signals.csv") if q["model"] == "linear" and q["elements_per_side"] == finest
              and q["case"] == x["case"]]
        ts, ys = [q["t"] for q in fe], [q["kinetic_energy"] for q in fe]
        s = [q for q in sig if q["formulation"] == x["formulation"] and q["case"] == x["case"]
             and abs(q["dx"] - dx) < 1e-12 and q["t"] <= x["t_stop"] + 1e-12]
        e = math.sqrt(sum((q["kinetic_energy"] - ic.interp(ts, ys, q["t"])) ** 2 for q in s) / len(s)) / ke0
        approx(e, x["e_ke"], f"{x.where()} e_ke", rel=1e-2)
        n += 1
    return f"{n} runs"


def claim_rate_form_runs_are_mcms_configuration(r):
    """Every run's dt is TSSFAC h / c_P (rounded down to t_end / steps: within 1 %), h = 1.3 dx, c_P of steel."""
    return ic.mcm_time_step(r)


def claim_verdict_classes_follow_their_rates(r):
    """Each stability verdict's class (S/U/I/B) follows from its two growth rates and the floor in verdicts.csv, and
    the summary's verdict table and class lists are that file's."""
    return ic.verdicts_follow_csv(r)
