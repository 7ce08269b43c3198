"""Headline claims of forms (results/forms/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, one, select


def claim_compression_unstable_cases(r):
    """A finite critical compression (conservative form) in `unstable` of `cases` kernel x h/dx cases, all of them the
    mollifier at h/dx >= 2.2 (unstable_list), the others stable to the search limit (tcrit.csv and
    compression_conditions.csv agree)."""
    cond = r.csv("compression_conditions.csv")
    check(len(cond) == r.num("cases"), f"{len(cond)} cases, summary {r.key('cases')}")
    finite = [x for x in cond if math.isfinite(x["tcrit_minus_conservative"])]
    check(len(finite) == r.num("unstable"), f"{len(finite)} finite critical compressions, summary {r.key('unstable')}")
    check(all(x["kernel"] == "mollifier" and x["h_over_dx"] >= 2.2 - 1e-9 for x in finite),
          f"unstable cases {[(x['kernel'], x['h_over_dx']) for x in finite]}")
    for x in cond:
        t = one(r.csv("tcrit.csv"), kernel=x["kernel"], h_over_dx=x["h_over_dx"], form="conservative",
                direction="compression")
        check(t["tcrit"] == x["tcrit_minus_conservative"] or math.isclose(t["tcrit"], x["tcrit_minus_conservative"],
                                                                          rel_tol=1e-6),
              f"{t.where()}: {t['tcrit']} against {x.where()} {x['tcrit_minus_conservative']}")
    return f"{len(finite)} of {len(cond)} unstable in compression (mollifier, h/dx >= 2.2)"


def claim_stable_in_compression_iff_L_psd(r):
    """Stable in compression <=> L positive semi-definite, in l_psd_matching of cases (all): L's smallest eigenvalue is
    negative exactly in the unstable cases."""
    cond = r.csv("compression_conditions.csv")
    match = sum((x["L_lambda_min"] >= -1e-12) == (x["tcrit_minus_conservative"] == -math.inf) for x in cond)
    check(match == len(cond) == r.num("l_psd_matching"), f"{match} of {len(cond)} match, summary "
                                                         f"{r.key('l_psd_matching')}")
    check(sum(x["L_lambda_min"] >= -1e-12 for x in cond) == r.num("l_psd"), "l_psd count differs")
    return f"{match}/{len(cond)}"


def claim_conservative_symmetric(r):
    """Theorem 3.8: the conservative Jacobian is symmetric to conservative_asymmetry_max (< 1e-14) in every
    configuration of asymmetry.csv, while the other forms are not symmetric once displaced and loaded."""
    rows = r.csv("asymmetry.csv")
    cons = [x["relative_asymmetry"] for x in rows if x["form"] == "conservative"]
    check(max(cons) < 1e-14 and r.num("conservative_asymmetry_max") < 1e-14, f"conservative asymmetry "
                                                                           f"{max(cons):.3g}")
    # The headline's number is the largest over both tables (it once quoted the amplitude table's 3.2e-16 while
    # asymmetry.csv had 3.9e-16).
    amp = [x["relative_asymmetry"] for x in r.csv("asymmetry_vs_amplitude.csv") if x["form"] == "conservative"]
    approx(r.num("conservative_asymmetry_all"), max(cons + amp), "conservative_asymmetry_all", rel=0.05)
    approx(r.num("conservative_asymmetry_max"), max(amp), "conservative_asymmetry_max (amplitude table)", rel=0.05)
    other = [x for x in rows if x["form"] != "conservative" and x["config"] == "displaced-loaded"]
    check(other and all(x["relative_asymmetry"] > 1e-6 for x in other),
          f"a non-conservative form symmetric when displaced and loaded: {[x.where() for x in other if x['relative_asymmetry'] <= 1e-6]}")
    return f"conservative <= {max(cons):.2g}; others > 1e-6 displaced and loaded"


def claim_minus_has_no_critical_load(r):
    """'Does the minus form have a critical load: no': tcrit of the minus form is +inf in tension and -inf in
    compression in every case."""
    rows = select(r.csv("tcrit.csv"), form="minus")
    bad = [x.where() for x in rows if abs(x["tcrit"]) != math.inf]
    check(not bad and r.key("minus_critical_load") == "no", f"minus form finite at {bad[:5]}")
    return f"{len(rows)} minus-form rows infinite"


def claim_routes_cross_check(r):
    """Analytic and affine (complex-step) Jacobians give the same T_crit in cross_cases cases to cross_max (< 1e-8)."""
    rows = r.csv("crosscheck.csv")
    worst = max(x["relative_difference"] for x in rows if math.isfinite(x["relative_difference"]))
    check(len(rows) == r.num("cross_cases") and worst < 1e-8, f"{len(rows)} cases, worst {worst:.3g}")
    approx(worst, r.num("cross_max"), "largest difference", rel=0.05)
    return f"{len(rows)} cases to {worst:.2g}"


def claim_form_ratios(r):
    """Tension: T_crit(uncorrected) = 2 T_crit(plus) = 4 T_crit(conservative) in every case (ratio_dev)."""
    rows = r.csv("tcrit.csv")
    n = 0
    for x in select(rows, form="conservative", direction="tension"):
        if not math.isfinite(x["tcrit"]):
            continue
        p = one(rows, kernel=x["kernel"], h_over_dx=x["h_over_dx"], form="plus", direction="tension")["tcrit"]
        u = one(rows, kernel=x["kernel"], h_over_dx=x["h_over_dx"], form="uncorrected", direction="tension")["tcrit"]
        approx(p / x["tcrit"], 2.0, f"{x.where()} plus/conservative", rel=1e-8)
        approx(u / x["tcrit"], 4.0, f"{x.where()} uncorrected/conservative", rel=1e-8)
        n += 1
    return f"1:2:4 in {n} cases"
