"""Headline claims of powell-clamped-beam (results/powell-clamped-beam/), run by tests/scripts/claims_test.py."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import impact_claims as ic  # noqa: E402
from claims import approx, check  # noqa: E402

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


# ---- The sensitivities (sensitivity_*.csv): S-SPH with the means of G, and every formulation at half the load ----

def _sensitivity_failed(r, x):
    """The statement table's failure rule for one sensitivity_runs.csv row, from that file and sensitivity_order.csv:
    (failed, largest clumped share, most fragments)."""
    share = float(r.key("clumped_share").split()[0]) / 100
    order = [q for q in r.csv("sensitivity_order.csv") if (q["formulation"], q["case"]) == (x["formulation"], x["case"])
             and abs(q["dx"] - x["dx"]) < 1e-12]
    check(order, f"{x.where()}: no sensitivity_order.csv records")
    clumped, fragments = max(q["clumped_share"] for q in order), max(q["fragments"] for q in order)
    return x["status"] != "completed" or clumped > share or fragments > 1, clumped, fragments


def claim_half_load_ssph_verdict_follows_runs_and_order(r):
    """'At half load S-SPH completes intact / fails' follows from its run (sensitivity_runs.csv: status) and its
    particle order (sensitivity_order.csv: clumped share, fragments) by the statement table's failure rule, and so do
    the summary's lists of the formulations intact and failed at half load."""
    runs = [x for x in r.csv("sensitivity_runs.csv") if x["case"] == "half-load"]
    verdict = {x["formulation"]: _sensitivity_failed(r, x) for x in runs}
    failed, clumped, fragments = verdict["ssph"]
    want = "fails" if failed else "completes intact"
    check(r.key("half_load_ssph") == want, f"summary half_load_ssph '{r.key('half_load_ssph')}', data: {want}")
    x = next(q for q in runs if q["formulation"] == "ssph")
    how = (("completes" if x["status"] == "completed" else f"stops ({x['status']})")
           + (", in one piece" if fragments == 1 else f", in up to {fragments} fragments")
           + f", clumped up to {100 * clumped:.2g} %")
    check(r.key("half_load_ssph_how") == how, f"summary half_load_ssph_how '{r.key('half_load_ssph_how')}', data {how}")
    for key, state in (("half_load_intact", False), ("half_load_failed", True)):
        names = ", ".join(ic.LABEL[x["formulation"]] for x in runs if verdict[x["formulation"]][0] == state) or "none"
        check(r.key(key) == names, f"summary {key} '{r.key(key)}', data '{names}'")
    return f"S-SPH at half load {want}: clumped up to {clumped:.3g}, fragments up to {fragments}"


def claim_sensitivity_table_follows_runs_and_order(r):
    """Every row of sensitivity.csv has its run's status and v0 (sensitivity_runs.csv, same order) and the failure
    verdict, clumped share and fragments of sensitivity_order.csv; the summary's table lists them in that order
    after the study's own runs, and 'S-SPH (means of G) at the snapshot resolution' is that row's verdict."""
    runs, table = r.csv("sensitivity_runs.csv"), r.csv("sensitivity.csv")
    check(len(runs) == len(table), f"{len(runs)} sensitivity runs, {len(table)} sensitivity.csv rows")
    lines = r.key("sensitivity_table").split("\n")
    check(len(lines) == len(FORMS) + len(table), f"sensitivity_table has {len(lines)} rows")
    for x, y, line in zip(runs, table, lines[len(FORMS):]):
        failed, clumped, fragments = _sensitivity_failed(r, x)
        for k in ("formulation", "case", "status", "v0", "dx"):
            check(x[k] == y[k], f"{y.where()}: {k} {y[k]}, {x.where()}: {x[k]}")
        check(y["failed"] == ("yes" if failed else "no"), f"{y.where()}: failed {y['failed']}, data {failed}")
        approx(y["clumped_max"], clumped, f"{y.where()} clumped_max", rel=1e-9)
        check(y["fragments_max"] == fragments, f"{y.where()}: fragments {y['fragments_max']}, data {fragments}")
        cells = [c.strip() for c in line.strip("| ").split("|")]
        check(cells[1] == ic.LABEL[x["formulation"]] and cells[-1] == y["failed"],
              f"summary row '{line}' is not {x['formulation']} failed {y['failed']}")
    dx = r.num("snapshot_spacing")
    g = next(y for y in table if y["formulation"] == "ssph-g" and y["case"] == "load" and abs(y["dx"] - dx) < 1e-12)
    want = "fails" if g["failed"] == "yes" else "completes intact"
    check(r.key("ssph_g_at_snapshot_spacing") == want, f"summary '{r.key('ssph_g_at_snapshot_spacing')}', csv {want}")
    return f"{len(table)} sensitivity runs"


def claim_sensitivity_runs_are_measured_against_fe_at_their_own_load(r):
    """Each sensitivity run's errors are against an FE run at its own load: the FE run's initial speed at A (fe_v0)
    equals the run's v0, and sensitivity_fe_runs.csv has the linear and SVK FE runs at every load of the runs."""
    table = r.csv("sensitivity.csv")
    for y in table:
        approx(y["fe_v0"], y["v0"], f"{y.where()} FE initial speed at A", rel=1e-9)
    loads = {y["v0"] for y in table}
    fe = {(q["model"], q["v0"]) for q in r.csv("sensitivity_fe_runs.csv")}
    for v0 in loads:
        check({("linear", v0), ("svk", v0)} <= fe, f"no FE runs at v0 = {v0} in sensitivity_fe_runs.csv")
    return "loads " + ", ".join(f"{v:g}" for v in sorted(loads))


def claim_sensitivity_deflection_error_recomputed(r):
    """e_defl of every sensitivity run at the snapshot resolution, recomputed from sensitivity_signals.csv and the
    linear FE run at the run's own load in sensitivity_fe_signals.csv, equals sensitivity.csv's (to 1e-6)."""
    dx = r.num("snapshot_spacing")
    runs = r.csv("sensitivity_runs.csv")
    sig, fe = r.csv("sensitivity_signals.csv"), r.csv("sensitivity_fe_signals.csv")
    n = 0
    for x, y in zip(runs, r.csv("sensitivity.csv")):
        if abs(x["dx"] - dx) > 1e-12:
            continue
        column = f"deflection_at_{x['x_A']:g}_{x['y_A']:g}"
        ref = [q for q in fe if q["model"] == "linear" and abs(q["v0"] - x["v0"]) < 1e-12]
        ts, ys = [q["t"] for q in ref], [q[column] for q in ref]
        s = [q for q in sig if (q["formulation"], q["case"]) == (x["formulation"], x["case"])
             and abs(q["dx"] - dx) < 1e-12 and q["t"] <= x["t_stop"] + 1e-12]
        e = math.sqrt(sum((q["deflection"] - ic.interp(ts, ys, q["t"])) ** 2 for q in s) / len(s)) / max(map(abs, ys))
        approx(e, y["e_defl"], f"{y.where()} e_defl", rel=1e-6)
        n += 1
    return f"{n} runs"


def claim_ssph_cause_follows_the_sensitivities(r):
    """The summary's conclusion on S-SPH's failure (neither / one / both changes remove it) follows from the failure
    verdicts of S-SPH with the means of G at Powell's load and of S-SPH at half load at the snapshot resolution,
    recomputed from sensitivity_runs.csv and sensitivity_order.csv."""
    dx = r.num("snapshot_spacing")
    runs = r.csv("sensitivity_runs.csv")
    g = next(x for x in runs if (x["formulation"], x["case"]) == ("ssph-g", "load") and abs(x["dx"] - dx) < 1e-12)
    h = next(x for x in runs if (x["formulation"], x["case"]) == ("ssph", "half-load"))
    fails = (_sensitivity_failed(r, g)[0], _sensitivity_failed(r, h)[0])
    text = r.key("ssph_causes")
    want = ("neither" if all(fails) else "either change: each" if not any(fails) else "only")
    check(want in text, f"summary '{text}' for means-of-G failed {fails[0]}, half-load failed {fails[1]}")
    return f"means of G failed {fails[0]}, half load failed {fails[1]}"
