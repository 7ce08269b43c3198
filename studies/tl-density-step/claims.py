"""Headline claims of tl-density-step (results/tl-density-step/), run by tests/scripts/claims_test.py."""
from claims import check


def claim_coefficients_match_impedance(r):
    """All measured reflection/transmission coefficients (stress and velocity, two density ratios, two resolutions)
    are within 0.015 of the impedance values; R_v = -R_sigma; the finer run is not worse on R."""
    rows = r.csv("coefficients.csv")
    devs = []
    for x in rows:
        for c in ("R_stress", "T_stress", "R_velocity", "T_velocity"):
            devs.append(abs(x[c] - x[f"{c}_expected"]))
        check(abs(x["R_velocity"] + x["R_stress"]) < 1e-4, f"{x.where()}: R_v != -R_sigma")
    check(len(devs) == 16 and max(devs) < 0.015, f"{len(devs)} coefficients, worst deviation {max(devs):.3g}")
    return f"{len(devs)} coefficients, worst deviation {max(devs):.2g}"


def claim_reflection_sign_follows_impedance(r):
    """The reflected stress has the sign of the impedance step: R_sigma > 0 into the denser half (ratio 2), < 0 into the
    lighter (ratio 0.5); transmission T_sigma > 1 resp. < 1."""
    for x in r.csv("coefficients.csv"):
        up = x["ratio"] > 1
        check((x["R_stress"] > 0) == up and (x["T_stress"] > 1) == up, f"{x.where()}: ratio {x['ratio']}: R "
                                                                       f"{x['R_stress']:.3g}, T {x['T_stress']:.3g}")
    return "signs follow the impedance ratio"
