"""Headline claims of powell-bar-impact (results/powell-bar-impact/), run by tests/scripts/claims_test.py."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import impact_claims as ic  # noqa: E402
from claims import check  # noqa: E402

FORMS = ("sph", "ncsph", "ssph", "tl")


def claim_completed_counts_follow_runs_csv(r):
    """The headline's 'completed k of n' per formulation is the count of status 'completed' in runs.csv."""
    return ic.completed_counts(r, FORMS)


def claim_first_stops_follow_runs_csv(r):
    """Each formulation's 'first stop' is the status and time of its run that stopped first (runs.csv)."""
    return ic.first_stops(r, FORMS)


def claim_least_length_error_is_the_named_run(r):
    """'Least e_len among the completed runs' names the completed run of least e_len in errors.csv."""
    return ic.least_error_named(r, "e_len")


def claim_fe_length_error_is_below_every_sph_difference(r):
    """FE's own length-change error (h_e 0.01 against 0.005) is below every completed SPH run's e_len, and 0.02's is larger."""
    return ic.fe_error_below_sph(r, "e_len", "linear", (0.02, 0.01))


def claim_length_error_recomputed(r):
    """e_len at the snapshot resolution, recomputed from signals.csv and fe_signals.csv, equals errors.csv's."""
    return ic.error_recomputed(r, "e_len", "length", "linear", "length", change=True)


def claim_pareto_front_recomputed(r):
    """The named fastest run for each attainable e_len is the Pareto front of errors.csv."""
    return ic.pareto_front_recomputed(r, "e_len")


def claim_rate_form_runs_are_mcms_configuration(r):
    """dt = TSSFAC h / c_P in every run."""
    return ic.mcm_time_step(r)


def claim_expansion_verdicts_follow_shape_csv(r):
    """'continues to expand' in the statement table holds exactly for the formulations that stopped or whose final
    length change (shape.csv) exceeds FE's largest (fe_signals.csv) by more than the table's gap (in dx)."""
    dx, gap = r.num("snapshot_spacing"), r.num("gap")
    fe = [q for q in r.csv("fe_signals.csv") if q["model"] == "linear"]
    side = min(q["element_side"] for q in fe)
    dl = [q["length"] for q in fe if q["element_side"] == side]
    bound = max(dl) - dl[0] + gap * dx
    runs = {x["formulation"]: x for x in r.csv("runs.csv") if abs(x["dx"] - dx) < 1e-12}
    shape = {x["formulation"]: x for x in r.csv("shape.csv")}
    table = r.key("statements_table")
    for f, label in (("sph", "basic SPH"), ("ncsph", "NCSPH")):
        expands = runs[f]["status"] != "completed" or shape[f]["dl_end"] > bound
        row = next(line for line in table.splitlines() if f"| {label} fails and continues to expand |" in line)
        check(("| yes |" in row) == expands, f"{label}: table '{row}', data expands = {expands}")
    return f"bound {bound:.4g} cm"


def claim_verdict_classes_follow_their_rates(r):
    """Each stability verdict's class (S/U/I/B) follows from its two growth rates and the floor in verdicts.csv, and
    the summary's verdict table and class lists are that file's."""
    return ic.verdicts_follow_csv(r)
