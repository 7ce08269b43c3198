"""Headline claims of mean-polishing (results/mean-polishing/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, select


def _rows(r, correction, form, direction, op=None):
    rows = select(r.csv("tcrit.csv"), N=30, correction=correction, form=form, direction=direction)
    return [x for x in rows if op is None or x["corrected_operator"] == op]


def claim_no_critical_tension(r):
    """No critical tension (T_crit = inf) in all cases with the mean polish, the Shepard-column polish and column-Shepard
    (conservative) and the minus form; counts equal the summary's tension_inf/cases."""
    out = []
    for corr, form in (("mean-polish", "conservative"), ("shepard-column-polish", "conservative"),
                       ("column-shepard", "conservative"), ("none", "minus")):
        rows = _rows(r, corr, form, "tension")
        inf = sum(x["tcrit"] == math.inf for x in rows)
        check(inf == len(rows) == r.num(f"{corr}.{form}.tension_inf") == r.num(f"{corr}.{form}.cases"),
              f"tcrit.csv {corr}/{form}: {inf} of {len(rows)} infinite, summary "
              f"{r.key(f'{corr}.{form}.tension_inf')}/{r.key(f'{corr}.{form}.cases')}")
        out.append(f"{corr}/{form} {inf}/{len(rows)}")
    return "; ".join(out)


def claim_shepard_keeps_finite_tension(r):
    """Shepard keeps a finite T_crit in every conservative case (tension_finite/cases), smallest min_tension; the
    uncorrected conservative form's smallest is none.conservative.min_tension."""
    rows = _rows(r, "shepard", "conservative", "tension")
    finite = [x["tcrit"] for x in rows if math.isfinite(x["tcrit"])]
    check(len(finite) == len(rows) == r.num("shepard.conservative.tension_finite"), f"{len(finite)} of {len(rows)}")
    approx(min(finite), r.num("shepard.conservative.min_tension"), "smallest Shepard T_crit", rel=0.01)
    none = [x["tcrit"] for x in _rows(r, "none", "conservative", "tension")]
    approx(min(none), r.num("none.conservative.min_tension"), "smallest uncorrected T_crit", rel=0.01)
    return f"Shepard finite in {len(finite)}/{len(rows)}, min {min(finite):.3g}"


def claim_momentum_price(r):
    """Price of the corrections: the momentum error (total force over sum |V a|, largest over the kernels; operator
    strain for conservative, divergence for uncorrected, as the summary says) of column-Shepard (conservative) and local
    polish (uncorrected) equals the summary's, and both are nonzero (not momentum conserving)."""
    rows = r.csv("momentum.csv")
    for corr, form, op in (("column-shepard", "conservative", "strain"), ("local-polish", "uncorrected", "divergence")):
        vals = [x["total_force_relative"] for x in select(rows, correction=corr, form=form, corrected_operator=op)]
        check(vals, f"momentum.csv has no {corr}/{form}")
        approx(max(vals), r.num(f"momentum.{corr}.{form}"), f"{corr}/{form} momentum error", rel=0.05)
        check(min(vals) > 1e-10, f"{corr}/{form} conserves momentum for some kernel")
    return f"column-Shepard {r.key('momentum.column-shepard.conservative')}, local polish " \
           f"{r.key('momentum.local-polish.uncorrected')}"


def claim_mean_polish_fills_jacobian(r):
    """The mean polish is non-local: the plus-form Jacobian grows from jacobian_plus_none to jacobian_plus_mean_polish
    nonzeros (locality.csv), the full N x N = 900 for N = 30."""
    loc = {x["correction"]: x for x in r.csv("locality.csv")}
    none, mean = loc["none"]["jacobian_nonzero_plus"], loc["mean-polish"]["jacobian_nonzero_plus"]
    check(none == r.num("nonlocal.jacobian_plus_none") and mean == r.num("nonlocal.jacobian_plus_mean_polish"),
          f"locality.csv {none} -> {mean}")
    check(mean == r.num("n") ** 2 and none < mean / 3, f"{none} -> {mean} nonzeros")
    return f"{none} -> {mean}"


def claim_nonsymmetric_counts(r):
    """The counts of nonsymmetric A (the cases decided by the spectrum criterion instead of definiteness): in the N = 30
    sweep (first criterion of each tension case) and with thin layers (thin_layers.csv) equal the summary's, and the
    thin-layer table lists exactly the rows that are nonsymmetric or not in equilibrium."""
    seen, nonsym, cases = set(), 0, 0
    for x in r.csv("tcrit.csv"):
        key = (x["kernel"], x["h_over_dx"], x["correction"], x["form"], x["corrected_operator"])
        if x["N"] != 30 or x["direction"] != "tension" or key in seen:
            continue
        seen.add(key)
        cases += 1
        nonsym += x["criterion"] != "definiteness"
    check(nonsym == r.num("nonsymmetric_cases"), f"tcrit.csv: {nonsym} of {cases} nonsymmetric, summary "
          f"{r.key('nonsymmetric_cases')}")
    check(0 < nonsym < cases, f"{nonsym} of {cases}: the count separates symmetric from nonsymmetric cases")
    thin = r.csv("thin_layers.csv")
    thin_nonsym = sum(x["criterion"] != "definiteness" for x in thin)
    listed = sum(x["criterion"] != "definiteness" or x["equilibrium_residual"] > 1e-10 for x in thin)
    check(thin_nonsym == r.num("thin_nonsymmetric") and len(thin) == r.num("thin_cases"),
          f"thin_layers.csv: {thin_nonsym} of {len(thin)} nonsymmetric, summary {r.key('thin_nonsymmetric')} of "
          f"{r.key('thin_cases')}")
    rows = [l for l in r.text("summary.md").split("## Boundary sensitivity")[1].split("##")[0].splitlines()
            if l.startswith("| ") and not l.startswith("| correction")]
    check(len(rows) == listed, f"the thin-layer table lists {len(rows)} rows, {listed} are nonsymmetric or off equilibrium")
    return f"{nonsym} of {cases} nonsymmetric (N = 30); thin layers {thin_nonsym} of {len(thin)}, {listed} listed"
