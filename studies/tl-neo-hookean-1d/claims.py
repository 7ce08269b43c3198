"""Headline claims of tl-neo-hookean-1d (results/tl-neo-hookean-1d/), run by tests/scripts/claims_test.py."""
from claims import approx, check, select


def claim_thesis_table(r):
    """T11 against [Ismail2009]'s reference table: the analytic value agrees with the thesis to worst_thesis_difference
    (<= 5e-5 mu), and the quasi-static SPH runs to worst_static_relative (< 1e-4, relative)."""
    rows = r.csv("table.csv")
    worst = max(abs(x["t11_analytic_over_mu"] - x["t11_thesis_over_mu"]) for x in rows)
    static = max(abs(x["t11_static_sph_over_mu"] / x["t11_analytic_over_mu"] - 1) for x in rows)
    check(worst <= 5e-5, f"table.csv: analytic against thesis {worst:.3g}")
    approx(worst, r.num("worst_thesis_difference"), "worst thesis difference", rel=0.1, abs_=5e-6)
    approx(static, r.num("worst_static_relative"), "worst quasi-static relative error", rel=0.1)
    check(static < 1e-4, f"static error {static:.3g}")
    return f"{len(rows)} rows: thesis {worst:.2g}, static {static:.2g}"


def claim_jacobian_turns_indefinite_at_tangent_root(r):
    """At nu = 0.49 the TL Jacobian turns indefinite at F = f_sph, the root of dP/dF at f_tangent (difference
    f_difference < 1e-9); in hyperbolicity.csv the tangent modulus and the smallest Jacobian eigenvalue change sign
    together between the same imposed stretches."""
    check(abs(r.num("f_sph") - r.num("f_tangent")) < 1e-6 and r.num("f_difference") < 1e-9,
          f"f_sph {r.key('f_sph')} against f_tangent {r.key('f_tangent')}")
    rows = sorted(r.csv("hyperbolicity.csv"), key=lambda x: x["lambda_imposed"])
    tangent = [x["lambda_imposed"] for x in rows if x["tangent_over_modulus"] <= 0]
    jac = [x["lambda_imposed"] for x in rows if x["mu_min_over_mu_min_rest"] <= 0]
    check(tangent and jac and min(tangent) == min(jac), f"first non-positive tangent at {min(tangent or [0])}, "
                                                        f"Jacobian at {min(jac or [0])}")
    below = [x["lambda_imposed"] for x in rows if x["lambda_imposed"] < r.num("f_tangent")]
    check(max(below) < min(tangent), "a non-positive tangent below f_tangent")
    return f"F = {r.key('f_sph')} (tangent root {r.key('f_tangent')}); sampled sign change at {min(tangent)}"


def claim_ramps(r):
    """Dynamic ramps: the nu = 0.3 runs never depart from the static curve; the spread at F = 3.5 falls with the ramp
    length for each nu; at nu = 0.49 the departure happens only above F = 2 (departure_049)."""
    rows = r.csv("ramps.csv")
    for nu in (0.3, 0.49):
        sub = sorted(select(rows, nu=nu), key=lambda x: x["ramp_transits"])
        spreads = [x["spread_at_3.5"] for x in sub]
        check(all(a > b for a, b in zip(spreads, spreads[1:])), f"nu = {nu}: spread not falling with ramp: {spreads}")
    check(all(x["departure_lambda"] != x["departure_lambda"] for x in select(rows, nu=0.3)), "nu = 0.3 departs")
    return "spread falls with ramp length; nu = 0.3 never departs"
