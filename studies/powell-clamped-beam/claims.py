"""Headline claims of powell-clamped-beam (results/powell-clamped-beam/), run by tests/scripts/claims_test.py."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import impact_claims as ic  # noqa: E402
from claims import check  # noqa: E402

FORMS = ("sph", "ncsph", "ssph", "tl", "tl-svk")


def claim_completed_counts_follow_runs_csv(r):
    """The headline's 'completed k of n' per formulation is the count of status 'completed' in runs.csv."""
    return ic.completed_counts(r, FORMS)


def claim_first_stops_follow_runs_csv(r):
    """Each formulation's 'first stop' is the status and time of its run that stopped first (runs.csv)."""
    return ic.first_stops(r, FORMS)


def claim_least_deflection_error_is_the_named_run(r):
    """'Least e_defl among the completed runs' names the completed run of least e_defl in errors.csv."""
    return ic.least_error_named(r, "e_defl")


def claim_fe_deflection_error_is_below_every_sph_difference(r):
    """FE's own deflection error (linear, h_e 0.01 against 0.005) is below every completed SPH run's e_defl, and 0.02's is
    larger."""
    return ic.fe_error_below_sph(r, "e_defl", "linear", (0.02, 0.01))


def claim_deflection_error_recomputed(r):
    """e_defl at the snapshot resolution, recomputed from signals.csv and fe_signals.csv, equals errors.csv's."""
    return ic.error_recomputed(r, "e_defl", "deflection", "linear", "deflection_at_{x}_{y}")


def claim_pareto_front_recomputed(r):
    """The named fastest run for each attainable e_defl is the Pareto front of errors.csv."""
    return ic.pareto_front_recomputed(r, "e_defl")


def claim_rate_form_runs_are_mcms_configuration(r):
    """dt = TSSFAC h / c_P in every run."""
    return ic.mcm_time_step(r)


def claim_failure_verdict_follows_runs_and_order(r):
    """'basic SPH has failed' holds exactly when basic SPH stopped, clumped beyond the table's share or broke into
    fragments, from runs.csv and order.csv."""
    dx = r.num("snapshot_spacing")
    share = float(r.key("clumped_share").split()[0]) / 100
    run = next(x for x in r.csv("runs.csv") if x["formulation"] == "sph" and abs(x["dx"] - dx) < 1e-12)
    order = [x for x in r.csv("order.csv") if x["formulation"] == "sph" and abs(x["dx"] - dx) < 1e-12]
    clumped, fragments = max(x["clumped_share"] for x in order), max(x["fragments"] for x in order)
    failed = run["status"] != "completed" or clumped > share or fragments > 1
    row = next(line for line in r.key("statements_table").splitlines() if "| basic SPH has failed" in line)
    check(("| yes |" in row) == failed, f"table '{row}', data failed = {failed}")
    return f"clumped up to {clumped:.3g}, fragments up to {fragments}"


def claim_verdict_classes_follow_their_rates(r):
    """Each stability verdict's class (S/U/I/B) follows from its two growth rates and the floor in verdicts.csv, and
    the summary's verdict table and class lists are that file's."""
    return ic.verdicts_follow_csv(r)
