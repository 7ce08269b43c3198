"""Headline claims of critical-tension (results/critical-tension/), run by tests/scripts/claims_test.py."""
from statistics import median

from claims import approx, check, close, fmt, select

KERNELS = ["cubic", "quartic", "quintic", "wendland-c2", "wendland-c4", "gaussian"]


def claim_sweep_complete(r):
    """270 = 6 kernels x 45 h/dx cases, every one finite and 'successful' (summary: cases, finite, successful)."""
    rows = r.csv("fig32.csv")
    check(len(rows) == r.num("cases") == 6 * 45, f"fig32.csv has {len(rows)} rows, summary cases = {r.num('cases')}")
    check(sorted({x["kernel"] for x in rows}) == sorted(KERNELS), "fig32.csv kernels differ from the six")
    bad = [x.where() for x in rows if x["status"] != "successful" or not x["tcrit"] > 0]
    check(not bad, f"rows not successful or without a finite T_crit > 0: {bad}")
    check(r.num("finite") == r.num("successful") == len(rows), "summary finite/successful differ from the row count")
    return f"{len(rows)} cases, all successful with T_crit > 0"


def claim_routes_agree(r):
    """Eigen and bisection routes agree to max_rel_diff (<= 1e-7); above_1e8 cases differ by more than 1e-8, all
    with T_crit < 1e-5 (ill-conditioned K)."""
    rows = r.csv("fig32.csv")
    worst = max(rows, key=lambda x: x["rel_diff"])
    approx(worst["rel_diff"], r.num("max_rel_diff"), f"{worst.where()} largest rel_diff", rel=0.05)
    check(worst["rel_diff"] <= 1e-7, f"{worst.where()}: routes differ by {worst['rel_diff']:.3g} > 1e-7")
    check(worst["kernel"] == r.key("max_rel_diff_kernel") and close(worst["h_over_dx"], r.num("max_rel_diff_h"),
                                                                     abs_=1e-9),
          f"{worst.where()}: worst case is {worst['kernel']} h={worst['h_over_dx']}, summary names "
          f"{r.key('max_rel_diff_kernel')} h={r.key('max_rel_diff_h')}")
    above = [x for x in rows if x["rel_diff"] > 1e-8]
    check(len(above) == r.num("above_1e8"), f"{len(above)} rows with rel_diff > 1e-8, summary says {r.key('above_1e8')}")
    check(all(x["tcrit"] < 1e-5 for x in above), f"a case with rel_diff > 1e-8 has T_crit >= 1e-5: "
                                                 f"{[x.where() for x in above if x['tcrit'] >= 1e-5]}")
    return f"max rel diff {worst['rel_diff']:.3g} ({worst['kernel']}, h={worst['h_over_dx']}), {len(above)} above 1e-8"


def claim_form_ratios_exact(r):
    """Powell conclusion 6: T_crit(plus)/T_crit(conservative) = 2 and uncorrected/conservative = 4 exactly."""
    dev = 0.0
    for x in r.csv("forms.csv"):
        for col, want in (("ratio_plus", 2.0), ("ratio_uncorrected", 4.0)):
            approx(x[col], want, f"{x.where()} {col}", rel=1e-12)
        dev = max(dev, abs(x["tcrit_plus"] / x["tcrit_conservative"] - 2) / 2,
                  abs(x["tcrit_uncorrected"] / x["tcrit_conservative"] - 4) / 4)
    # the CSV prints 12 significant digits, so ratios recomputed from its T_crit columns agree to ~1e-11
    check(dev <= 1e-10 and r.num("max_form_dev") <= 1e-12, f"form ratio deviation {dev:.3g}, summary "
                                                            f"{r.key('max_form_dev')}")
    return f"ratios 2 and 4 to {dev:.2g} in {len(r.csv('forms.csv'))} cases"


def claim_estimate_342_factor_about_100_only_at_small_h(r):
    """Powell conclusion 1: (3.42)/T_crit = 103.6 for every kernel at h/dx <= 1; over all h it spans
    ratio_min..ratio_max (median ratio_median), so 'about 100' does not hold everywhere."""
    rows = r.csv("fig32.csv")
    small = [x["ratio_first_minor"] for x in rows if x["h_over_dx"] <= 1 + 1e-9]
    check(all(close(v, r.num("ratio_small"), rel=1e-3) for v in small),
          f"(3.42)/T_crit at h/dx <= 1 ranges {min(small):.5g}..{max(small):.5g}, summary says {r.key('ratio_small')}")
    mid = [x["ratio_first_minor"] for x in rows if 1 + 1e-9 < x["h_over_dx"] <= 1.4 + 1e-9]
    approx(min(mid), r.num("ratio_mid_min"), "min (3.42)/T_crit, 1 < h/dx <= 1.4", rel=5e-3)
    approx(max(mid), r.num("ratio_mid_max"), "max (3.42)/T_crit, 1 < h/dx <= 1.4", rel=5e-3)
    allr = [x["ratio_first_minor"] for x in rows]
    approx(min(allr), r.num("ratio_min"), "min (3.42)/T_crit", rel=5e-3)
    approx(max(allr), r.num("ratio_max"), "max (3.42)/T_crit", rel=5e-3)
    approx(median(allr), r.num("ratio_median"), "median (3.42)/T_crit", rel=5e-3)
    check(max(allr) > 1000 and min(allr) < 50, "the ratio no longer spans orders of magnitude; revisit 'only there'")
    return f"103.6 at h<=1; all h {min(allr):.3g}..{max(allr):.3g}, median {median(allr):.3g}"


def claim_peaks(r):
    """Powell conclusion 3: the argmax of T_crit(h) per kernel is peak_list, in [1.2, 2] for peaks_in_range kernels."""
    rows = r.csv("fig32.csv")
    stated = dict(item.rsplit(" ", 1) for item in r.key("peak_list").split(", "))
    inside = 0
    for k in KERNELS:
        best = max(select(rows, kernel=k), key=lambda x: x["tcrit"])
        approx(best["h_over_dx"], float(stated[k]), f"{best.where()} h/dx of max T_crit for {k}", abs_=1e-9)
        inside += 1.2 - 1e-9 <= best["h_over_dx"] <= 2 + 1e-9
    check(inside == r.num("peaks_in_range"), f"{inside} peaks in [1.2, 2], summary says {r.key('peaks_in_range')}")
    return f"peaks {r.key('peak_list')}; {inside} of 6 in [1.2, 2]"


def claim_infinite_limit_classes(r):
    """T_crit,inf = 0 with L^(pi/dx) > 0 in zero_limit_cases, > 1e-12 in positive_limit_cases, neutral in the rest."""
    rows = r.csv("fig32.csv")
    zero = [x for x in rows if x["l_hat_sawtooth"] > 1e-12 and x["tcrit_infinite"] == 0]
    positive = [x for x in rows if x["tcrit_infinite"] > 1e-12]
    neutral = len(rows) - len(zero) - len(positive)
    got = (len(zero), len(positive), neutral)
    want = (r.num("zero_limit_cases"), r.num("positive_limit_cases"), r.num("neutral_cases"))
    check(got == want, f"fig32.csv: (zero, positive, neutral) = {got}, summary says {want}")
    check(not any(x["l_hat_sawtooth"] > 1e-12 for x in positive), "a positive limit with L^(pi/dx) > 0")
    return f"zero {got[0]}, positive {got[1]}, neutral {got[2]}"


def claim_decay_exponent_two(r):
    """Where L^(pi/dx) > 0, T_crit ~ N^-p with p in [p_zero_limit_min, p_zero_limit_max], within 0.05 of 2."""
    ps = [x["p_tcrit"] for x in r.csv("exponents.csv") if x["l_hat_sawtooth"] > 1e-12]
    check(ps and all(abs(p - 2) <= 0.05 for p in ps), f"exponents.csv: p = {min(ps):.4g}..{max(ps):.4g}, not 2 +- 0.05")
    approx(min(ps), r.num("p_zero_limit_min"), "min p", abs_=0.006)
    approx(max(ps), r.num("p_zero_limit_max"), "max p", abs_=0.006)
    return f"{len(ps)} fits, p = {min(ps):.3f}..{max(ps):.3f}"


def claim_wendland_c2_leads_at_small_h(r):
    """Conclusion 5 reversed: for h/dx <= c2_leads_up_to Wendland C2 has the largest T_crit of the six, and not at the
    next h/dx."""
    rows = r.csv("fig32.csv")
    hs = sorted({x["h_over_dx"] for x in rows})
    limit = r.num("c2_leads_up_to")
    for h in hs:
        at = select(rows, h_over_dx=h)
        leader = max(at, key=lambda x: x["tcrit"])["kernel"]
        if h <= limit + 1e-9:
            check(leader == "wendland-c2", f"fig32.csv h/dx={h}: {leader} has the largest T_crit, not wendland-c2")
        else:
            check(leader != "wendland-c2", f"fig32.csv h/dx={h}: wendland-c2 still leads beyond {limit}")
            break
    return f"wendland-c2 leads up to h/dx = {limit}"


def claim_tension_order_5e4_at_n30(r):
    """Conclusion 2: at N = 30 the largest T_crit over 1.2 <= h/dx <= 2 is band_max_min..band_max_max across kernels
    (order 1e-4..1e-2); at N = 960 and h/dx = 1.2 it is tcrit_960_min..tcrit_960_max (~ N^-2)."""
    rows = r.csv("fig32.csv")
    band = [max(x["tcrit"] for x in select(rows, kernel=k) if 1.2 - 1e-9 <= x["h_over_dx"] <= 2 + 1e-9)
            for k in KERNELS]
    approx(min(band), r.num("band_max_min"), "min over kernels of max T_crit in [1.2, 2]", rel=5e-3)
    approx(max(band), r.num("band_max_max"), "max over kernels of max T_crit in [1.2, 2]", rel=5e-3)
    n960 = [x["tcrit"] for x in select(r.csv("versus_n.csv"), N=960, h_over_dx=1.2)]
    check(len(n960) == 6, f"versus_n.csv: {len(n960)} rows at N = 960, h/dx = 1.2")
    approx(min(n960), r.num("tcrit_960_min"), "min T_crit(N=960, h=1.2)", rel=5e-3)
    approx(max(n960), r.num("tcrit_960_max"), "max T_crit(N=960, h=1.2)", rel=5e-3)
    check(max(n960) < 1e-5 < min(band), "T_crit at N = 960 is not below the N = 30 band")
    return f"N=30 band {min(band):.3g}..{max(band):.3g}; N=960 {min(n960):.3g}..{max(n960):.3g}"


def claim_growth_above_tcrit(r):
    """Growth rate is 0 below T_crit (0.5 T_crit) and positive above; at 1.5 T_crit it is growth_min..growth_max."""
    rows = r.csv("growth.csv")
    at15 = []
    for x in rows:
        f = x["T"] / x["tcrit"]
        if f < 1:
            check(x["growth_rate"] == 0 and x["unstable_modes"] == 0, f"{x.where()}: growth below T_crit")
        else:
            check(x["growth_rate"] > 0, f"{x.where()}: no growth at T = {f:.2g} T_crit")
            if close(f, 1.5, rel=1e-6):
                at15.append(x["growth_rate"])
    check(len(at15) == 6, f"growth.csv: {len(at15)} rows at 1.5 T_crit")
    approx(min(at15), r.num("growth_min"), "min growth at 1.5 T_crit", abs_=6e-4)
    approx(max(at15), r.num("growth_max"), "max growth at 1.5 T_crit", abs_=6e-4)
    return f"gamma(1.5 T_crit) = {min(at15):.3g}..{max(at15):.3g}"
