"""Headline claims of gms-plate (results/gms-plate/), run by tests/scripts/claims_test.py.

Every range, count and ratio the summary's prose names is rendered by the driver (plate_tables.hpp); these claims
recompute each from the CSVs, so a summary that says more than its data fails here."""
import math

from claims import approx, check, one, select

PERIOD_TABLES = ["periods.csv", "convergence.csv", "clamp.csv", "dt.csv", "viscosity.csv", "eps.csv"]
REARRANGED = 1.5  # dp: a grid bond longer than the fragment criterion (plate_tables.hpp kRearrangedStretch)


def span(values, decimals):
    """The driver's study::Range::text: "lo–hi" at `decimals`, one value when both print the same; NaN skipped."""
    values = [v for v in values if not math.isnan(v)]
    if not values:
        return "-"
    lo, hi = (f"{v:.{decimals}f}" for v in (min(values), max(values)))
    return lo if lo == hi else f"{lo}–{hi}"


def rendered(r, key, value, digits):
    """summary.json[key] is `value` as the driver renders it with `digits` significant digits (%.*g)."""
    text = r.key(key)
    if math.isnan(value):
        check(text == "-", f"summary {key} = {text!r}, expected '-' (no value)")
    elif text != f"{value:.{digits}g}":  # a last-ulp difference can flip a rounding: then within half a last digit
        approx(r.num(key), value, f"summary {key}", rel=0.6 * 10 ** (1 - digits), abs_=1e-15)
    return value


def claim_periods_over_two_cycles(r):
    """Issue 31 item 7: every tabulated period (cm/c0) rests on at least 5 zero crossings, i.e. two full cycles, and
    the summary states the fewest count found in the period tables; a run with fewer crossings has no period, and
    the summary counts those runs; the SI plate states its own count."""
    rows = [x for f in PERIOD_TABLES for x in r.csv(f)]
    counts = [x["crossings"] for x in rows if not math.isnan(x["period"])]
    unmeasured = {x["tag"] for x in rows if math.isnan(x["period"])}
    check(all(x["crossings"] < 5 for x in rows if math.isnan(x["period"])), "a run with 5 crossings and no period")
    check(all(x["max_bond_stretch"] > REARRANGED for x in rows if math.isnan(x["period"])),
          "a run without a period whose lattice did not rearrange (the summary says they rearranged)")
    check(r.num("unmeasured_runs") == len(unmeasured), f"summary unmeasured_runs {r.key('unmeasured_runs')}, CSVs "
                                                       f"{len(unmeasured)}")
    check(min(counts) >= 5, f"a tabulated period from {min(counts)} crossings (fewer than two cycles)")
    check(r.num("min_crossings") == min(counts), f"summary min_crossings {r.key('min_crossings')}, CSVs {min(counts)}")
    check(r.num("min_cycles") == (min(counts) - 1) // 2, "min_cycles does not follow from min_crossings")
    si = one(r.csv("si.csv"))
    check(si["crossings"] == r.num("si_crossings") and si["crossings"] >= 5, f"{si.where()}: {si['crossings']}")
    return f"{len(counts)} periods from {min(counts)}..{max(counts)} crossings; SI plate {si['crossings']}"


def richardson(d, T):
    """T = T0 + C d^p through three points, p by bisection on [0.05, 8] (as plate_tables.hpp), or (nan, nan)."""
    q = (T[0] - T[1]) / (T[1] - T[2])

    def g(p):
        return (d[0] ** p - d[1] ** p) / (d[1] ** p - d[2] ** p) - q

    lo, hi = 0.05, 8.0
    if not g(lo) * g(hi) < 0:
        return math.nan, math.nan
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    C = (T[1] - T[2]) / (d[1] ** p - d[2] ** p)
    return p, T[2] - C * d[2] ** p


def claim_extrapolation_without_rearranged_runs(r):
    """Issue 31 item 7: the headline extrapolation is fitted through the three finest runs of the resolution study
    whose grid bonds stayed below 1.5 dp, and the three finest runs overall are only its sensitivity; both fits,
    recomputed here from convergence.csv, equal extrapolation.csv and the summary; the rearranged runs the summary
    lists are those of the CSV."""
    conv = sorted(r.csv("convergence.csv"), key=lambda x: x["across"])
    clean = [x for x in conv if x["max_bond_stretch"] <= REARRANGED]
    rearranged = [x["across"] for x in conv if not x["max_bond_stretch"] <= REARRANGED]
    listed = r.key("rearranged_across")
    check(listed == (", ".join(map(str, rearranged)) or "none"), f"summary lists rearranged {listed}, CSV {rearranged}")
    fits = {x["fit"]: x for x in r.csv("extrapolation.csv")}
    for name, runs, key_p, key_t, key_from in (("unrearranged", clean[-3:], "observed_order", "extrapolated_period",
                                                "extrapolation_from"),
                                               ("finest", conv[-3:], "finest_fit_order", "finest_fit_period",
                                                "finest_fit_from")):
        check(len(runs) == 3, f"fewer than three runs for the {name} fit")
        p, T0 = richardson([x["dp"] for x in runs], [x["period"] for x in runs])
        row = fits[name]
        frm = "/".join(str(x["across"]) for x in runs)
        check(row["from_across"] == frm, f"{row.where()}: fit {name} from {row['from_across']}, expected {frm}")
        check(r.key(key_from) == frm, f"summary {key_from} {r.key(key_from)}, expected {frm}")
        for col, want, rel in (("observed_order", p, 1e-6), ("extrapolated_period", T0, 1e-9)):
            if math.isnan(want):  # no power law through the three periods: the driver writes nan
                check(math.isnan(row[col]), f"{row.where()}: {col} {row[col]}, expected nan")
            else:
                approx(row[col], want, f"{row.where()} {col}", rel=rel)
        rendered(r, key_p, p, 3)
        rendered(r, key_t, T0, 5)
        n_bad = sum(1 for x in runs if not x["max_bond_stretch"] <= REARRANGED)
        check(row["rearranged_runs"] == n_bad, f"{row.where()}: {row['rearranged_runs']} rearranged, expected {n_bad}")
    check(fits["unrearranged"]["rearranged_runs"] == 0, "the headline fit uses a rearranged run")
    return (f"headline from {fits['unrearranged']['from_across']} (order {fits['unrearranged']['observed_order']:.3g},"
            f" T0 {fits['unrearranged']['extrapolated_period']:.1f}); rearranged {rearranged}")


def claim_resolution_statements(r):
    """Where GMS's T_sph falls in the resolution sequence, the closest run, and that the unrearranged runs' period
    falls with dp ("the period falls with dp") and stays above the Timoshenko period ("too soft")."""
    conv = sorted(r.csv("convergence.csv"), key=lambda x: x["across"])
    clean = [x for x in conv if x["max_bond_stretch"] <= REARRANGED]
    periods = [x["period"] for x in clean]
    check(all(a > b for a, b in zip(periods, periods[1:])), f"unrearranged periods not falling with dp: {periods}")
    check(all(x["period"] > x["timoshenko_period"] for x in clean), "an unrearranged run below the Timoshenko period")
    stretch = [x["max_bond_stretch"] for x in conv]
    check(all(a < b for a, b in zip(stretch, stretch[1:])), f"bond stretch not growing with resolution: {stretch}")
    paper = conv[0]["paper_period"]
    between = [f"between {a['across']} and {b['across']}" for a, b in zip(conv, conv[1:])
               if (a["period"] - paper) * (b["period"] - paper) <= 0]
    check(r.key("paper_between") == (between[-1] if between else "outside the runs' range"),
          f"summary paper_between '{r.key('paper_between')}', CSV {between}")
    closest = min(conv, key=lambda x: abs(x["error_vs_paper"]))
    check(r.num("closest_across") == closest["across"], f"closest run {closest['across']} across")
    rendered(r, "closest_vs_paper", 100 * closest["error_vs_paper"], 2)
    return f"clean periods {[round(p) for p in periods]}; GMS {r.key('paper_between')}"


def claim_table_ranges(r):
    """The ranges of the Tables 1-2 bullets: error to T_sph at small amplitude (H = 2), the V_f 0.001/0.01 spread,
    the rise, decay and bond stretch at V_f = 0.03 and 0.05 (GMS's own rise beside it), and H = 1."""
    rows = r.csv("periods.csv")
    h2 = select(rows, H=2)
    small = [100 * x["error_vs_paper"] for x in h2 if x["tip_speed"] <= 0.01]
    check(r.key("small_vs_paper") == span(small, 1), f"small_vs_paper {r.key('small_vs_paper')}, CSV {span(small, 1)}")
    spread, rise03, rise05, decay05, st03, st05, prise = [], [], [], [], [], [], []
    for mu in (0.22, 0.3, 0.6):
        a, b = one(h2, mu=mu, tip_speed=0.001), one(h2, mu=mu, tip_speed=0.01)
        m, big = one(h2, mu=mu, tip_speed=0.03), one(h2, mu=mu, tip_speed=0.05)
        spread.append(100 * abs(a["period"] / b["period"] - 1))
        rise03.append(100 * (m["period"] / b["period"] - 1)), st03.append(m["max_bond_stretch"])
        rise05.append(100 * (big["period"] / b["period"] - 1)), st05.append(big["max_bond_stretch"])
        decay05.append(100 * big["decay_per_period"]), prise.append(100 * (big["paper_period"] / b["paper_period"] - 1))
        check(big["max_fragments"] <= r.num("fragments05"), f"{big.where()}: {big['max_fragments']} fragments")
    rendered(r, "small_vf_spread", max(v for v in spread if not math.isnan(v)), 2)
    for key, values, dec in (("rise03", rise03, 1), ("stretch03", st03, 2), ("rise05", rise05, 1),
                             ("stretch05", st05, 2), ("decay05", decay05, 0), ("paper_rise05", prise, 1)):
        check(r.key(key) == span(values, dec), f"summary {key} {r.key(key)}, CSV {span(values, dec)}")
    check(min(st05) > REARRANGED, f"V_f = 0.05 said to rearrange, bonds {st05}")
    h1 = select(rows, H=1)
    h1_small = [100 * x["error_vs_paper"] for x in h1 if x["tip_speed"] == 0.01]
    h1_decay = [100 * x["decay_per_period"] for x in h1 if x["tip_speed"] >= 0.03]
    check(r.key("h1_small_vs_paper") == span(h1_small, 1), f"h1_small_vs_paper {r.key('h1_small_vs_paper')}")
    check(r.key("h1_large_decay") == span(h1_decay, 0), f"h1_large_decay {r.key('h1_large_decay')}")
    return f"small {span(small, 1)} %; V_f 0.05 rise {span(rise05, 1)} %, bonds {span(st05, 2)} dp"


def claim_sensitivities(r):
    """Clamp spread, dt change, viscosity spread and decays, the MCM deck's row, the eps = 0.3 lengthening and the
    eps = 0 run against the linear period, each as the summary renders it."""
    clamp = [x["period"] for x in r.csv("clamp.csv")]
    rendered(r, "clamp_spread", max(clamp) / min(clamp) - 1, 2)
    dts = [x["period"] for x in r.csv("dt.csv")]
    rendered(r, "dt_change", abs(dts[0] / dts[1] - 1), 2)
    visc = r.csv("viscosity.csv")
    mcm, rest = visc[0], visc[1:]
    check(mcm["alpha"] == 0.06 and mcm["beta"] == 1.5, f"{mcm.where()}: not the MCM deck's row")
    rendered(r, "mcm_stretch", mcm["max_bond_stretch"], 2)
    vp = [x["period"] for x in rest]
    rendered(r, "visc_period_spread", 100 * (max(vp) / min(vp) - 1), 2)
    check(r.key("visc_decay") == span([100 * x["decay_per_period"] for x in rest], 1), "visc_decay")
    eps = r.csv("eps.csv")
    lengthening = [100 * (one(eps, eps=0.3, tip_speed=v)["period"] / one(eps, eps=0, tip_speed=v)["period"] - 1)
                   for v in (0.001, 0.01)]
    check(r.key("eps_lengthening") == span(lengthening, 1), f"eps_lengthening {r.key('eps_lengthening')}")
    lin = one(r.csv("linear.csv"), across=r.num("across_h2"))["linear_period"]
    e0 = one(eps, eps=0, tip_speed=0.01)["period"]
    rendered(r, "eps0_vs_linear", 100 * (e0 / lin - 1), 2)
    e3 = one(eps, eps=0.3, tip_speed=0.01)["period"]
    check(abs(e0 / lin - 1) < 0.5 * abs(e3 / lin - 1), "the artificial stress does not account for most of the run's "
                                                       f"difference to the linear period ({e0:.1f}, {e3:.1f}, {lin:.1f})")
    return f"clamp {r.key('clamp_spread')}, dt {r.key('dt_change')}, eps +{span(lengthening, 1)} %"


def claim_root_break(r):
    """GMS's Fig. 2: at mu = 0.6, V_f = 0.05 the epsilon = 0 plate breaks (2 fragments, break time as stated), the
    epsilon = 0.3 plate stays in one fragment."""
    root = r.csv("root.csv")
    e0, e3 = one(root, eps=0), one(root, eps=0.3)
    check(e0["max_fragments"] == r.num("root_eps0_fragments") == 2, f"{e0.where()}: {e0['max_fragments']} fragments")
    approx(e0["break_time"], r.num("root_eps0_break_time"), "eps 0 break time", abs_=0.06)
    check(e3["max_fragments"] == r.num("root_eps03_fragments") == 1, f"{e3.where()}: {e3['max_fragments']} fragments")
    check(e3["max_bond_stretch"] > REARRANGED, f"{e3.where()}: said to rearrange, bonds {e3['max_bond_stretch']} dp")
    return f"eps 0: 2 fragments at t = {e0['break_time']:.1f}; eps 0.3: 1 fragment"


def claim_frozen_spectra(r):
    """The frozen-spectrum numbers of the prose, from frozen_spectrum.csv: unstable counts without viscosity, the
    eps ratio, and with viscosity at t = 140 the mode's place, e-folding time and growth factor to the break."""
    fs = r.csv("frozen_spectrum.csv")
    novisc = [x for x in fs if x["state"] != "start" and x["viscosity"] == 0 and x["eps"] == 0]
    check(r.key("frozen_novisc_unstable") == span([x["unstable_eigenvalues"] for x in novisc], 0),
          "frozen_novisc_unstable")
    v0, v3 = one(fs, state="t140", eps=0, viscosity=1), one(fs, state="t140", eps=0.3, viscosity=1)
    check(v0["growth_rate"] > 0, f"{v0.where()}: the viscosity-on eps = 0 state is not unstable")
    rendered(r, "frozen_visc_efold", 1 / v0["growth_rate"], 2)
    t_break = one(r.csv("root.csv"), eps=0)["break_time"]
    rendered(r, "frozen_visc_factor", math.exp(v0["growth_rate"] * (t_break - 140)), 2)
    rendered(r, "frozen_visc_ratio", v3["growth_rate"] / v0["growth_rate"], 2)
    rendered(r, "frozen_visc_peak_x", v0["mode_peak_x"], 2)
    return f"e-folding {1 / v0['growth_rate']:.3g}, growth x{math.exp(v0['growth_rate'] * (t_break - 140)):.3g}"
