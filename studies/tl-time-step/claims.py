"""Headline claims of tl-time-step (results/tl-time-step/), run by tests/scripts/claims_test.py."""
from claims import approx, check, one


def claim_limit_below_ismail_rule(r):
    """The validation bar's leap-frog limit is limit_over_rule (0.72) of Ismail's dt = h/c (4.47): below it, so the
    thesis's rule is unstable; the symbol route agrees with the bar to 1e-4 and Spectra with dense to 1e-12."""
    ratio = r.num("dt_limit_ns") / r.num("dt_rule_ns")
    approx(ratio, r.num("limit_over_rule"), "limit / rule", rel=1e-3)
    check(ratio < 1, f"limit / rule {ratio:.4g} >= 1")
    approx(r.num("dt_symbol_ns"), r.num("dt_limit_ns"), "symbol against bar limit", rel=1e-4)
    check(r.num("spectra_vs_dense") < 1e-12, f"spectra vs dense {r.key('spectra_vs_dense')}")
    return f"limit {r.key('dt_limit_ns')} ns = {ratio:.4f} h/c"


def claim_runs_bracket_the_limit(r):
    """Runs: bounded at 0.99 of the limit and at 0.72 h/c (below it), unstable at 1.01 of the limit, 0.73 h/c and
    Ismail's h/c (above it): the verdict is 'bounded' exactly when dt/limit < 1."""
    for x in r.csv("runs.csv"):
        check((x["verdict"] == "bounded") == (x["dt_over_limit"] < 1), f"{x.where()}: {x['run']} dt/limit "
                                                                       f"{x['dt_over_limit']:.4g}, {x['verdict']}")
    ismail = one(r.csv("runs.csv"), run="h/c (Ismail 4.47)")
    check(ismail["verdict"] == "unstable", "Ismail's h/c run is not unstable")
    return "bounded iff dt < limit (5 runs); Ismail's h/c unstable"


def claim_symbol_ratio_independent_of_support(r):
    """For the mollifier the symbol limit over Ismail's rule is about 0.72 at every support tabled (s = 3 ... 12)."""
    vals = [r.num(k) for k in r.summary if k.startswith("mollifier_symbol_ratio_s")]
    check(len(vals) >= 4 and max(vals) - min(vals) < 0.01 and all(abs(v - 0.72) < 0.01 for v in vals), f"{vals}")
    return f"{min(vals):.4f}..{max(vals):.4f}"
