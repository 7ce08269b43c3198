"""Headline claims of jacobian-speed (results/jacobian-speed/), run by tests/scripts/claims_test.py.

summary.md is written by studies/jacobian-speed/report.py (no summary.md.in); its typed exponents and ranges are
parsed with r.stated and compared with jacobian.csv. Only ratios within the one run and fitted exponents are
asserted, never seconds."""
import math

from claims import approx, check, select


def _families(r):
    rows = r.csv("jacobian.csv")
    families = dict.fromkeys(x["family"] for x in rows)
    return {f: sorted(select(rows, family=f), key=lambda x: x["dofs"]) for f in families}


def _exponent(xs, ys):
    """Least-squares slope of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def claim_colours_depend_on_the_stencil_only(r):
    """The distance-2 colouring needs 9 colours in 1D at every n (100-10000 DOFs) and 178-184 (~180) in 2D over
    512-8192 DOFs (within 4 % while N grows 16x); the 2D colour counts are the ones critical-strain-2d's complex-step
    Jacobian reports at the same DOFs (benchmark.csv, JacobianCS)."""
    other = {x["dofs"]: x["colours"] for x in select(r.other("critical-strain-2d").csv("benchmark.csv"),
                                                     benchmark="JacobianCS")}
    out = []
    for fam, rows in _families(r).items():
        cols = [x["colours"] for x in rows]
        if fam.startswith("wave1d"):
            check(set(cols) == {9}, f"{fam}: colours {cols}, expected 9 at every n")
        else:
            check(all(170 <= c <= 190 for c in cols) and max(cols) / min(cols) <= 1.04, f"{fam}: colours {cols}")
            for x in rows:
                if x["dofs"] in other:
                    check(x["colours"] == other[x["dofs"]], f"{x.where()}: {x['colours']} colours, critical-strain-2d "
                                                             f"{other[x['dofs']]:g} at {x['dofs']} DOFs")
        out.append(f"{fam} {min(cols)}-{max(cols)}")
    check(len(other) >= 2, "critical-strain-2d benchmark.csv has fewer than 2 JacobianCS rows")
    return ", ".join(out)


def claim_fixed_number_of_force_evaluations(r):
    """Headline: a Jacobian costs a fixed number of real force evaluations, independent of N: Jacobian / force varies
    by at most 25 % over the DOF range of each family and its fitted exponent against DOFs is within +-0.06 of 0; the
    Jacobian time scales like N^(0.94..1.01) against N^(0.91..0.97) for one force evaluation, as summary.md types them
    (2 decimals)."""
    out = []
    for fam, rows in _families(r).items():
        ns = [x["dofs"] for x in rows]
        ratio = [x["ratio_to_real_force"] for x in rows]
        check(max(ratio) / min(ratio) <= 1.25, f"{fam}: Jacobian / force {min(ratio):.3g}..{max(ratio):.3g}")
        p = _exponent(ns, ratio)
        check(abs(p) <= 0.06, f"{fam}: Jacobian / force ~ N^{p:.3f}")
        pj = _exponent(ns, [x["jacobian_s"] for x in rows])
        pf = _exponent(ns, [x["jacobian_s"] / x["ratio_to_real_force"] for x in rows])
        check(0.85 <= pf <= pj <= 1.05, f"{fam}: Jacobian ~ N^{pj:.3f}, force ~ N^{pf:.3f}")
        sj, sf = (float(v) for v in
                  r.stated(rf"- {fam}: .*?Jacobian time ~ N\^([\d.]+ against ~ N\^[\d.]+) for", convert=False)
                  .split(" against ~ N^"))
        approx(sj, pj, f"summary.md {fam} Jacobian exponent", abs_=0.0051)
        approx(sf, pf, f"summary.md {fam} force exponent", abs_=0.0051)
        out.append(f"{fam} N^{p:+.2f}")
    return "Jacobian / force ~ " + ", ".join(out)


def claim_factor_is_the_complex_evaluation(r):
    """(Jacobian / force) / colours, the cost of one coloured column group in real force evaluations, is the complex /
    real force cost to within 20 % in every row (2.4-4.4): the Jacobian is colours x one complex force evaluation plus
    the scatter; the 2D conservative family costs more force evaluations than the plus form at every N."""
    worst = 0
    for x in r.csv("jacobian.csv"):
        approx(x["ratio_over_colours"], x["ratio_to_real_force"] / x["colours"], f"{x.where()} ratio_over_colours",
               rel=1e-9)
        dev = x["ratio_over_colours"] / x["complex_over_real"] - 1
        check(abs(dev) <= 0.20 and 2.3 <= x["ratio_over_colours"] <= 4.5,
              f"{x.where()}: per colour {x['ratio_over_colours']:.3g}, complex / real {x['complex_over_real']:.3g}")
        worst = max(worst, abs(dev))
    fam = _families(r)
    for c, p in zip(fam["elastic2d_conservative"], fam["elastic2d_plus"]):
        check(c["dofs"] == p["dofs"] and c["ratio_to_real_force"] > p["ratio_to_real_force"],
              f"{c.where()}: conservative {c['ratio_to_real_force']:.3g} not above plus {p['ratio_to_real_force']:.3g}")
    return f"per-colour cost within {100 * worst:.0f} % of complex / real"
