"""Headline claims of swegle-rate-form (results/swegle-rate-form/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, md_table, one, select, verdict_class


def _finite(x):
    return isinstance(x, float) and math.isfinite(x)


def claim_verdicts_follow_the_rules(r):
    """Issue 31 part 1: every verdict in runs.csv is the class its two rates and the floor give (S/U/I/B), and the
    floor is the study's ln(onset) / (2 t_end). On the old data the column was a J-only S/U, which called the
    predictor-corrector's own growth at xi = 1 (gamma_map 0.13-0.2 /us, J neutral) stable and the run's growth a
    disagreement."""
    runs = r.csv("runs.csv")
    floor = math.log(r.num("onset")) / (2 * r.num("t_end"))
    approx(r.num("detect"), floor, "detection floor", rel=2e-3)
    counts = {"S": 0, "U": 0, "I": 0, "B": 0}
    for x in runs:
        approx(x["floor"], floor, f"{x.where()} floor", rel=2e-3)
        want = verdict_class(x["gamma_linear_class"], x["gamma_map_class"], x["floor"])
        check(x["verdict"] == want, f"{x.where()}: verdict {x['verdict']}, the rules give {want} (gamma_J "
                                    f"{x['gamma_linear_class']}, gamma_M {x['gamma_map_class']}, floor {x['floor']})")
        counts[x["verdict"]] += 1
    for c, n in counts.items():
        check(r.num(f"class_{c}") == n, f"summary class_{c} = {r.key(f'class_{c}')}, runs.csv has {n}")
    return ", ".join(f"{c} {n}" for c, n in counts.items())


def claim_stability_table_is_runs_csv(r):
    """Every cell of the verdict table is its runs.csv row: the class letter, gamma_J / gamma_M (2 digits, clamped at
    0), and the measured rate or '–' when the run stayed below the window."""
    runs = r.csv("runs.csv")
    xis = [float(x) for x in r.key("xi_list").split(",")]
    table = md_table(r.key("stability_table"))
    check(len(runs) == len(table) * len(xis) == r.num("cases"), f"runs.csv {len(runs)} rows, table {len(table)} x "
                                                                 f"{len(xis)}, cases {r.key('cases')}")
    for row in table:
        form = row[0].replace("**", "")
        for xi, cell in zip(xis, row[1:]):
            x = one(runs, formulation=form, xi=xi)
            words = cell.replace("**", "").split()
            check(words[0] == x["verdict"], f"{x.where()}: {form} xi={xi} verdict {x['verdict']}, table {cell}")
            approx(float(words[1]), max(x["gamma_linear_class"], 0.0), f"{x.where()} gamma_J in the table",
                   rel=0.05, abs_=1e-12)
            approx(float(words[3]), max(x["gamma_map_class"], 0.0), f"{x.where()} gamma_M in the table",
                   rel=0.05, abs_=1e-12)
            if x["grew"] == 1:
                approx(float(words[5]), x["gamma_measured"], f"{x.where()} measured gamma in the table", rel=0.05)
            else:
                check(words[5] == "–", f"{x.where()}: bounded run shown as {words[5]}")
    return f"{len(runs)} cells match runs.csv"


def claim_map_predicts_the_runs(r):
    """'A run at dt amplifies what its one-step map amplifies': agree counts the rows where gamma_M above the floor
    equals the run growing, and the listed disagreements are exactly the others."""
    runs = r.csv("runs.csv")
    agree = [x for x in runs if (x["gamma_map_class"] > x["floor"]) == (x["grew"] == 1)]
    for x in runs:
        check(x["map_predicts_growth"] == int(x["gamma_map_class"] > x["floor"]), f"{x.where()}: map_predicts_growth")
    check(len(agree) == r.num("agree"), f"runs.csv: {len(agree)} agreeing runs, summary says {r.key('agree')}")
    listed = r.key("disagreements").count("\n- ") + (1 if r.key("disagreements").startswith("- `") else 0)
    check(listed == len(runs) - len(agree), f"{listed} disagreements listed, runs.csv has {len(runs) - len(agree)}")
    comp = [x for x in runs if _finite(x["ratio"])]
    check(len(comp) == r.num("comparable"), f"{len(comp)} comparable runs, summary says {r.key('comparable')}")
    approx(min(x["ratio"] for x in comp), r.num("ratio_min"), "min ratio", abs_=6e-4)
    approx(max(x["ratio"] for x in comp), r.num("ratio_max"), "max ratio", abs_=6e-3)
    return f"{len(agree)}/{len(runs)} agree; {len(comp)} comparable"


def claim_integrator_growth_is_the_maps(r):
    """xi = 1 growth is the predictor-corrector's: at dt basic SPH's run grows and is class I (J neutral within the
    floor), its measured rate within 5 % of gamma_M for both position updates; at dt/2 the map's rate is 8x smaller
    (dt^3 law, within 2 %)."""
    dts = r.csv("dt_study.csv")
    big, small = max(x["dt"] for x in dts), min(x["dt"] for x in dts)
    for x in select(dts, dt=big):
        check(x["grew"] == 1 and x["verdict"] == "I", f"{x.where()}: at dt the run must grow and be class I")
        check(abs(x["gamma_measured"] / x["gamma_map_class"] - 1) <= 0.05,
              f"{x.where()}: measured {x['gamma_measured']} against the map's {x['gamma_map_class']}")
        approx(x["gamma_measured"] / x["gamma_map_class"], r.num(f"dt_ratio_{x['positions']}"),
               f"{x.where()} rendered measured/map", abs_=1e-3)
    for x in select(dts, dt=small):
        approx(one(dts, dt=big, positions=x["positions"])["gamma_map_class"] / x["gamma_map_class"], 8.0,
               f"{x.where()} map rate ratio dt/(dt/2)", rel=0.02)
        want = "I" if x["gamma_map_class"] > r.num("detect") else "S"  # xi = 1: J neutral
        check(x["verdict"] == want, f"{x.where()}: class {x['verdict']} at dt/2, the map's rate gives {want}")
    i_rates = [x["gamma_map_class"] for x in r.csv("runs.csv") if x["verdict"] == "I"]
    parts = r.key("integrator_rate_range").split("–")
    lo, hi = float(parts[0]), float(parts[-1])
    approx(min(i_rates), lo, "smallest class-I map rate", rel=0.05)  # rendered to 2 significant digits
    approx(max(i_rates), hi, "largest class-I map rate", rel=0.05)
    return f"class I map rates {min(i_rates):.3g}..{max(i_rates):.3g} /us"


def claim_powell_rows_are_the_classes(r):
    """The statement table's cells are the classes of runs.csv per xi on each side of 1, and the rendered rate cuts
    gamma_J(sph) / gamma_J(form) are recomputed from runs.csv."""
    runs = r.csv("runs.csv")
    for form in ("sph", "ncsph", "ncsph-xsph", "ncsph-anti", "cij", "ssph", "ssph-printed", "sph-xsph"):
        for side, key in ((1, "tension_"), (-1, "compression_")):
            rows = sorted((x for x in select(runs, formulation=form) if (x["xi"] - 1) * side > 0),
                          key=lambda x: x["xi"])
            stated = [c.split() for c in r.key(key + form).split(", ")]
            check([(float(a), b) for a, b in stated] == [(x["xi"], x["verdict"]) for x in rows],
                  f"{key}{form} = {r.key(key + form)}, runs.csv has {[(x['xi'], x['verdict']) for x in rows]}")

    def cut(form, side, measured):
        f = []
        for x in select(runs, formulation=form):
            if (x["xi"] - 1) * side <= 0:
                continue
            b = one(runs, formulation="sph", xi=x["xi"])
            if measured and x["grew"] == 1 and b["grew"] == 1:
                f.append(b["gamma_measured"] / x["gamma_measured"])
            elif not measured and x["gamma_linear_class"] > x["floor"] and b["gamma_linear_class"] > b["floor"]:
                f.append(b["gamma_linear_class"] / x["gamma_linear_class"])
        return f

    for key, form, side, measured in (("ssph_tension_cut", "ssph", 1, False), ("xsph_tension_cut", "sph-xsph", 1, False),
                                      ("xsph_compression_cut", "sph-xsph", -1, False),
                                      ("visc_compression_cut", "sph-visc", -1, True)):
        f = cut(form, side, measured)
        if not f:
            check(r.key(key) == "–", f"{key} = {r.key(key)}, but no xi has both unstable")
            continue
        parts = r.key(key).split("–")
        lo, hi = float(parts[0]), float(parts[-1])
        approx(min(f), lo, f"{key} low end", rel=0.05)  # rendered to 2 significant digits
        approx(max(f), hi, f"{key} high end", rel=0.05)
    return "statement table and rate cuts match runs.csv"


def claim_block_size_lowers_rate(r):
    """Basic SPH's linear rate at xi = 1.02 grows with the block size (swegle-nonlinear's block_size.csv) and its
    21 x 21 value equals this study's linear rate on its own block."""
    rows = sorted(select(r.other("swegle-nonlinear").csv("block_size.csv"), formulation="sph", xi=1.02),
                  key=lambda x: x["n"])
    rates = [x["gamma_linear"] for x in rows]
    check(all(a < b for a, b in zip(rates, rates[1:])), f"block_size.csv: sph rate not increasing with n: {rates}")
    own = one(r.csv("runs.csv"), formulation="sph", xi=1.02)["gamma_linear_class"]
    approx(rates[-1], own, "21 x 21 rate of block_size.csv against runs.csv", rel=1e-6)
    return f"sph xi = 1.02: {rates[0]:.3g} (n = {rows[0]['n']}) .. {rates[-1]:.3g} (n = {rows[-1]['n']})"


def claim_equilibrium(r):
    """Every block starts in equilibrium: max equilibrium_residual = the summary's, below 1e-6."""
    worst = max(x["equilibrium_residual"] for x in r.csv("runs.csv"))
    approx(worst, r.num("equilibrium_residual"), "largest equilibrium residual", rel=0.02)
    check(worst < 1e-6, f"equilibrium residual {worst:.3g}")
    return f"max residual {worst:.3g}"
