"""Headline claims of swegle-rate-form (results/swegle-rate-form/), run by tests/scripts/claims_test.py."""
import math
import re

from claims import approx, check, md_table, one, select


def _finite(x):
    return isinstance(x, float) and math.isfinite(x)


def claim_stability_table_is_runs_csv(r):
    """Every S/U cell (and measured gamma) of the stability table is the measured_verdict of runs.csv."""
    runs = r.csv("runs.csv")
    xis = [float(x) for x in r.key("xi_list").split(",")]
    table = md_table(r.key("stability_table"))
    check(len(runs) == len(table) * len(xis) == r.num("cases"), f"runs.csv {len(runs)} rows, table {len(table)} x "
                                                                 f"{len(xis)}, cases {r.key('cases')}")
    for row in table:
        form = row[0].replace("**", "")
        for xi, cell in zip(xis, row[1:]):
            run = one(runs, formulation=form, xi=xi)
            words = cell.replace("**", "").split()
            check(words[0] == run["measured_verdict"], f"{run.where()}: {form} xi={xi} {run['measured_verdict']}, "
                                                       f"table {cell}")
            if words[0] == "U":
                approx(float(words[1]), run["gamma_measured"], f"{run.where()} gamma in the table", rel=6e-3)
    return f"{len(runs)} cells match runs.csv"


def claim_block_cases_exist(r, text=None):
    """Issue 31 item 3. Every 'on a(n) N × N block, ξ = x is stable/unstable' the summary names exists in a committed
    CSV with that verdict: this study's runs.csv for its own block size n, results/swegle-nonlinear/block_size.csv
    (basic SPH, full-state linear rate against the detection limit) for the others. The old text named an 11 × 11
    block at ξ = 1.01, which no CSV has."""
    src = r.md if text is None else text
    cases = re.findall(r"[Oo]n an? (\d+) × \d+ block, ξ = (\d\.\d+) is (?:\w+ )?(stable|unstable)", src)
    check(cases, "summary.md names no (block size, ξ) case")
    n = r.num("n")
    sizes = r.other("swegle-nonlinear").csv("block_size.csv")
    for size, xi, verdict in cases:
        size, xi = int(size), float(xi)
        if size == n:
            row = one(r.csv("runs.csv"), formulation="sph", xi=xi)
            unstable = row["measured_verdict"] == "U"
        else:
            found = select(sizes, formulation="sph", n=size, xi=xi)
            check(found, f"summary.md names a {size} × {size} block at ξ = {xi} ({verdict}); no row of runs.csv "
                         f"(n = {n}) or results/swegle-nonlinear/block_size.csv has it")
            row = found[0]
            unstable = row["gamma_linear"] > r.num("detect")
        check(unstable == (verdict == "unstable"), f"{row.where()}: {size} × {size}, ξ = {xi} is "
                                                   f"{'unstable' if unstable else 'stable'}, summary.md says {verdict}")
    return "; ".join(f"{s} × {s} ξ = {x} {v}" for s, x, v in cases)


def claim_block_size_lowers_rate(r):
    """'The rate depends on the block size, not the verdict': basic SPH's linear rate at ξ = 1.02 grows with the block
    size (block_size.csv) and equals this study's linear rate on its own block."""
    rows = sorted(select(r.other("swegle-nonlinear").csv("block_size.csv"), formulation="sph", xi=1.02),
                  key=lambda x: x["n"])
    rates = [x["gamma_linear"] for x in rows]
    check(all(a < b for a, b in zip(rates, rates[1:])), f"block_size.csv: sph rate not increasing with n: {rates}")
    own = one(r.csv("runs.csv"), formulation="sph", xi=1.02)["gamma_linear_class"]
    approx(rates[-1], own, f"21 × 21 rate of block_size.csv against runs.csv", rel=1e-6)
    return f"sph ξ = 1.02: {rates[0]:.3g} (n = {rows[0]['n']}) .. {rates[-1]:.3g} (n = {rows[-1]['n']})"


def claim_linear_agreement(r):
    """Verdicts agree in agree of cases runs; every disagreement has a neutral spectrum (gamma_linear_class = 0) and is
    at ξ = 1 or one of ncsph, ncsph-xsph, cij; measured/linear in [ratio_min, ratio_max] over the comparable runs,
    below 1 for sph-visc and sph-all."""
    runs = r.csv("runs.csv")
    agree = [x for x in runs if x["linear_verdict"] == x["measured_verdict"]]
    check(len(agree) == r.num("agree"), f"runs.csv: {len(agree)} agreeing verdicts, summary says {r.key('agree')}")
    for x in runs:
        if x["linear_verdict"] != x["measured_verdict"]:
            check(x["gamma_linear_class"] == 0 and (x["xi"] == 1 or x["formulation"] in ("ncsph", "ncsph-xsph", "cij")),
                  f"{x.where()}: disagreement at a non-neutral spectrum ({x['formulation']}, ξ = {x['xi']})")
    comp = [x for x in runs if _finite(x["ratio"])]
    check(len(comp) == r.num("comparable"), f"{len(comp)} comparable runs, summary says {r.key('comparable')}")
    approx(min(x["ratio"] for x in comp), r.num("ratio_min"), "min ratio", abs_=6e-4)
    approx(max(x["ratio"] for x in comp), r.num("ratio_max"), "max ratio", abs_=6e-3)
    smooth = [x["ratio"] for x in comp if x["formulation"] not in ("sph-visc", "sph-all")]
    approx(min(smooth), r.num("smooth_ratio_min"), "min ratio without viscosity", abs_=6e-4)
    visc = [x for x in comp if x["formulation"] in ("sph-visc", "sph-all")]
    check(all(x["ratio"] < 1 for x in visc), "a viscous run with measured/linear >= 1")
    top = max(comp, key=lambda x: x["ratio"])
    check(top["formulation"] == "ssph" and top["xi"] == 1.01, f"{top.where()}: the high end is not ssph at ξ = 1.01")
    approx(top["gamma_linear_class"], r.stated(r"whose linear rate \((0\.\d+) /µs\)"), "ssph ξ = 1.01 linear rate",
           abs_=0.005)
    return f"{len(agree)}/{len(runs)} agree; {len(comp)} comparable"


def claim_integrator_growth(r):
    """ξ = 1 growth is the predictor-corrector's: at dt the measured rate equals the Heun map's within 3 %, at dt/2 the
    map's rate is 8 x smaller and the run does not grow; the neutral-spectrum runs grow at 0.1–0.2 /µs (text)."""
    dts = r.csv("dt_study.csv")
    big, small = max(x["dt"] for x in dts), min(x["dt"] for x in dts)
    for x in select(dts, dt=big):
        check(x["grew"] == 1 and abs(x["gamma_measured"] / x["gamma_map_class"] - 1) <= 0.03,
              f"{x.where()}: measured {x['gamma_measured']} against the map's {x['gamma_map_class']}")
    for x in select(dts, dt=small):
        check(x["grew"] == 0, f"{x.where()}: the dt/2 run grows")
        approx(one(dts, dt=big, positions=x["positions"])["gamma_map_class"] / x["gamma_map_class"], 8.0,
               f"{x.where()} map rate ratio dt/(dt/2)", rel=0.01)
    lo, hi = (r.stated(r"At the study's dt = 0\.3 h/c_P it is (\d\.\d+)–(\d\.\d+) /µs", group=g) for g in (1, 2))
    neutral = [x["gamma_measured"] for x in r.csv("runs.csv") if x["gamma_linear_class"] == 0 and
               _finite(x["gamma_measured"]) and x["formulation"] not in ("sph-as", "sph-all")]
    check(lo - 0.05 <= min(neutral) and max(neutral) < hi + 0.05,
          f"integrator growth {min(neutral):.3g}..{max(neutral):.3g} /µs, text says {lo}–{hi}")
    return f"neutral-spectrum growth {min(neutral):.3g}..{max(neutral):.3g} /µs"


def claim_powell_comparison_ranges(r):
    """The ranges typed in the Powell table: ssph cuts the measured tension rate of sph by the stated factor range;
    the viscosity's compression switch cuts sph's compressive rate to the stated fraction range; sph grows at every
    ξ != 1; cij neutral at every ξ; ncsph-anti unstable both ways."""
    runs = r.csv("runs.csv")
    lo, hi = (r.stated(r"cuts the measured rate of basic SPH by a factor (\d+)–(\d+)", group=g) for g in (1, 2))
    f = [one(runs, formulation="sph", xi=xi)["gamma_measured"] / one(runs, formulation="ssph", xi=xi)["gamma_measured"]
         for xi in (1.01, 1.02, 1.04)]
    check(lo - 0.5 <= min(f) and max(f) < hi + 0.5, f"sph/ssph in tension {min(f):.3g}..{max(f):.3g}, text {lo}–{hi}")
    lo, hi = (r.stated(r"cuts the measured rate to (\d\.\d+)–(\d\.\d+) of basic SPH", group=g) for g in (1, 2))
    v = [one(runs, formulation="sph-visc", xi=xi)["gamma_measured"] / one(runs, formulation="sph", xi=xi)["gamma_measured"]
         for xi in (0.96, 0.98, 0.99)]
    approx(min(v), lo, "min sph-visc/sph in compression", abs_=0.005)
    approx(max(v), hi, "max sph-visc/sph in compression", abs_=0.005)
    for x in select(runs, formulation="sph"):
        check(x["xi"] == 1 or (x["linear_verdict"] == "U" and x["measured_verdict"] == "U"), f"{x.where()}: sph stable")
    check(all(x["gamma_linear_class"] == 0 for x in select(runs, formulation="cij")), "cij not neutral")
    check(all(x["linear_verdict"] == "U" for x in select(runs, formulation="ncsph-anti") if x["xi"] != 1),
          "ncsph-anti not unstable at every ξ != 1")
    return f"ssph factor {min(f):.3g}..{max(f):.3g}; viscosity {min(v):.3g}..{max(v):.3g}"


def claim_equilibrium(r):
    """Every block starts in equilibrium: max equilibrium_residual = the summary's, below 1e-6."""
    worst = max(x["equilibrium_residual"] for x in r.csv("runs.csv"))
    approx(worst, r.num("equilibrium_residual"), "largest equilibrium residual", rel=0.02)
    check(worst < 1e-6, f"equilibrium residual {worst:.3g}")
    return f"max residual {worst:.3g}"
