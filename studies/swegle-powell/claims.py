"""Headline claims of swegle-powell (results/swegle-powell/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, md_table, one, select, verdict_class

STATEMENTS = [  # key, formulation, side of xi = 1, "unstable" (a run on that side grew) or "stable" (none did)
    ("sph_tension", "sph", +1, True),
    ("ncsph_tension", "ncsph", +1, True),
    ("sph_compression", "sph", -1, False),
    ("cij_tension", "cij", +1, False),
    ("cij_compression", "cij", -1, True),
    ("ssph_tension", "ssph", +1, False),
    ("ssph_compression", "ssph", -1, False),
]


def _main(r):
    return select(r.csv("runs.csv"), set="main")


def _on_side(xi, side):
    return xi > 1 if side > 0 else xi < 1


def _h_list(hs):
    return ", ".join(f"{h:g}" for h in sorted(hs)) or "none"


def claim_configuration_is_mcms(r):
    """Issue 31 part 2: every main-set run is MCM's configuration — TSSFAC 0.8 with dt = TSSFAC h / c_P (run_rate_form
    rounds dt down to t_end / steps: within 0.5 %), bulk viscosity on; the sensitivity sets change one thing each."""
    cp = r.num("c_P")
    for x in r.csv("runs.csv"):
        want_tssfac = 0.4 if x["set"] == "half-dt" else 0.8
        approx(x["tssfac"], want_tssfac, f"{x.where()} TSSFAC", rel=1e-12)
        check(x["bulk_viscosity"] == (0 if x["set"] == "no-bulk" else 1), f"{x.where()}: bulk viscosity "
                                                                          f"{x['bulk_viscosity']} in set {x['set']}")
        dt = want_tssfac * x["h_over_dx"] * 0.01 / cp
        check(dt / 1.005 <= x["dt"] <= dt * (1 + 1e-9), f"{x.where()}: dt {x['dt']}, TSSFAC h / c_P = {dt}")
        layers = {"sph": 1, "xsph": 1, "ncsph": 2, "ncxsph": 2, "cij": 2, "ssph": 4}[x["formulation"]]
        check(x["layer_supports"] == layers, f"{x.where()}: {x['layer_supports']} supports of fixed layers, the "
                                             f"parameters state {layers}")
    return f"{len(r.csv('runs.csv'))} runs: TSSFAC, dt, bulk viscosity and fixed layers as their set states"


def claim_verdicts_follow_the_rules(r):
    """Every class is the one its two rates and the floor give; the summary's counts are the main set's."""
    floor = math.log(r.num("onset")) / (2 * r.num("t_end"))
    approx(r.num("detect"), floor, "detection floor", rel=2e-3)
    counts = {"S": 0, "U": 0, "I": 0, "B": 0}
    for x in r.csv("runs.csv"):
        approx(x["floor"], floor, f"{x.where()} floor", rel=2e-3)
        want = verdict_class(x["gamma_linear_class"], x["gamma_map_class"], x["floor"])
        check(x["verdict"] == want, f"{x.where()}: verdict {x['verdict']}, the rules give {want}")
        if x["set"] == "main":
            counts[x["verdict"]] += 1
    for c, n in counts.items():
        check(r.num(f"class_{c}") == n, f"summary class_{c} = {r.key(f'class_{c}')}, runs.csv has {n}")
    check(sum(counts.values()) == r.num("cases"), f"cases {r.key('cases')}, main rows {sum(counts.values())}")
    return ", ".join(f"{c} {n}" for c, n in counts.items())


def claim_verdict_tables_are_runs_csv(r):
    """Every cell of the per-h tables is its runs.csv row: class, gamma_J / gamma_M (2 digits, clamped at 0), and the
    measured rate or '–' for a run below the window."""
    runs = _main(r)
    xis = [float(x) for x in r.key("xi_list").split(",")]
    text = r.key("verdict_tables")
    blocks = [b for b in text.split("### h = ")[1:]]
    hs = sorted({x["h_over_dx"] for x in runs})
    check(len(blocks) == len(hs), f"{len(blocks)} tables, {len(hs)} h values")
    cells = 0
    for block in blocks:
        h = float(block.split()[0])
        table = md_table(block[block.index("|"):])
        for row in table:
            form = row[0].replace("**", "")
            for xi, cell in zip(xis, row[1:]):
                x = one(runs, formulation=form, xi=xi, h_over_dx=h)
                w = cell.replace("**", "").split()
                check(w[0] == x["verdict"], f"{x.where()}: table {cell}, verdict {x['verdict']}")
                approx(float(w[1]), max(x["gamma_linear_class"], 0.0), f"{x.where()} gamma_J", rel=0.05, abs_=1e-12)
                approx(float(w[3]), max(x["gamma_map_class"], 0.0), f"{x.where()} gamma_M", rel=0.05, abs_=1e-12)
                if x["grew"] == 1:
                    approx(float(w[5]), x["gamma_measured"], f"{x.where()} measured", rel=0.05)
                else:
                    check(w[5] == "–", f"{x.where()}: bounded run shown as {w[5]}")
                cells += 1
    check(cells == len(runs), f"{cells} cells, {len(runs)} main rows")
    return f"{cells} cells in {len(blocks)} tables match runs.csv"


def claim_statements_follow_the_runs(r):
    """Where each of Powell's statements holds (per h) is what the runs show: 'unstable' where a run on that side of
    xi = 1 grew, 'stable' where none did."""
    runs = _main(r)
    hs = sorted({x["h_over_dx"] for x in runs})
    found = []
    for key, form, side, unstable in STATEMENTS:
        yes = set()
        for h in hs:
            grew = [x["grew"] == 1 for x in select(runs, formulation=form, h_over_dx=h) if _on_side(x["xi"], side)]
            check(len(grew) == 3, f"{form} h={h}: {len(grew)} runs on side {side}")
            if (any(grew) if unstable else not any(grew)):
                yes.add(h)
        check(r.key(f"{key}_reproduced") == _h_list(yes), f"{key}: summary says {r.key(f'{key}_reproduced')}, "
                                                           f"runs.csv gives {_h_list(yes)}")
        check(r.key(f"{key}_not") == _h_list(set(hs) - yes), f"{key}_not: {r.key(f'{key}_not')}")
        found.append(f"{key} {_h_list(yes)}")
    return "; ".join(found)


def claim_grown_runs_have_a_rate(r):
    """A run that stopped at the energy limit grew (gamma_method 'mean' where no fit window fitted), and every run
    that grew has a finite positive rate; a run that completed below the window did not grow."""
    for x in r.csv("runs.csv"):
        if x["status"] == "energy-growth":
            check(x["grew"] == 1, f"{x.where()}: reached the energy limit but grew = {x['grew']}")
        if x["grew"] == 1:
            check(math.isfinite(x["gamma_measured"]) and x["gamma_measured"] > 0, f"{x.where()}: rate "
                                                                                    f"{x['gamma_measured']}")
        check(x["gamma_method"] in ("fit", "mean"), f"{x.where()}: gamma_method {x['gamma_method']}")
    return "every grown run has a rate"


def claim_map_predicts_the_runs(r):
    """The agree count is the rows where gamma_M above the floor equals the run growing; the disagreements listed are
    exactly the others."""
    runs = _main(r)
    agree = [x for x in runs if (x["gamma_map_class"] > x["floor"]) == (x["grew"] == 1)]
    check(r.num("agree") == len(agree), f"agree {r.key('agree')}, runs.csv gives {len(agree)}")
    listed = [line for line in r.key("disagreements").splitlines() if line.startswith("- `")]
    check(len(listed) == len(runs) - len(agree) or (not listed and len(runs) == len(agree)),
          f"{len(listed)} disagreements listed, {len(runs) - len(agree)} in runs.csv")
    return f"{len(agree)} of {len(runs)}"


def claim_powell_xsph_only_damps(r):
    """XSPH (2.71) acts outside F: gamma_J is the same with and without it, and the map with it never grows faster
    than without (for every h and xi: sph vs xsph, ncsph vs ncxsph). Fails if the smoothing fed energy in."""
    runs = _main(r)
    n = 0
    for base, smooth in (("sph", "xsph"), ("ncsph", "ncxsph")):
        for x in select(runs, formulation=base):
            y = one(runs, formulation=smooth, h_over_dx=x["h_over_dx"], xi=x["xi"])
            approx(y["gamma_linear_class"], x["gamma_linear_class"], f"{y.where()} gamma_J", rel=1e-6, abs_=1e-9)
            check(y["gamma_map_class"] <= x["gamma_map_class"] + 1e-9, f"{y.where()}: gamma_M with XSPH "
                                                                       f"{y['gamma_map_class']} > {x['gamma_map_class']}")
            n += 1
    return f"{n} pairs"


def claim_bulk_viscosity_is_invisible_at_rest(r):
    """The bulk viscosity's switch is off at rest (d = 0), so the no-bulk set has the main set's gamma_J and gamma_M
    at h = 1.3 to rounding; only the runs can differ."""
    runs = r.csv("runs.csv")
    rows = select(runs, set="no-bulk")
    check(len(rows) > 0, "no no-bulk rows")
    for x in rows:
        y = one(runs, set="main", formulation=x["formulation"], h_over_dx=x["h_over_dx"], xi=x["xi"])
        approx(x["gamma_linear_class"], y["gamma_linear_class"], f"{x.where()} gamma_J", rel=1e-6, abs_=1e-9)
        approx(x["gamma_map_class"], y["gamma_map_class"], f"{x.where()} gamma_M", rel=1e-6, abs_=1e-9)
    return f"{len(rows)} no-bulk rows"


def claim_equilibrium(r):
    """Every block starts in equilibrium: the largest unkicked acceleration is at most 1e-3 of the kick's scale (the
    growth is measured from the kick), and the summary states the largest."""
    worst = max(x["equilibrium_residual"] for x in _main(r))
    check(worst <= 1e-3, f"equilibrium residual {worst}")
    approx(r.num("equilibrium_residual"), worst, "equilibrium_residual", rel=0.05)
    return f"max {worst:.2g}"


def claim_ncsph_and_cij_grow_only_under_the_predictor_corrector(r):
    """README, 'Which settings make NCSPH and C_ij grow': here (leap-frog) no ncsph, ncxsph or cij run grows and every
    one is class S; in swegle-rate-form (GMS predictor-corrector, same block at h = 1.3) every ncsph and cij row is
    class I (gamma_J neutral, the map grows) and cij grows in tension too."""
    for x in _main(r):
        if x["formulation"] in ("ncsph", "ncxsph", "cij"):
            check(x["verdict"] == "S" and x["grew"] == 0, f"{x.where()}: {x['formulation']} {x['verdict']}, "
                                                          f"grew {x['grew']}")
    pc = r.other("swegle-rate-form").csv("runs.csv")
    for form in ("ncsph", "cij"):
        rows = select(pc, formulation=form)
        check(len(rows) == 7, f"swegle-rate-form: {len(rows)} {form} rows")
        for x in rows:
            check(x["verdict"] == "I", f"{x.where()}: {form} xi={x['xi']} is {x['verdict']}, not I")
    tension = [x for x in select(pc, formulation="cij") if x["xi"] > 1]
    check(all(x["grew"] == 1 for x in tension), "swegle-rate-form: a cij run in tension did not grow")
    return "leap-frog: S and bounded; predictor-corrector: class I, cij grows in tension"


def claim_bulk_viscosity_does_not_change_the_rates(r):
    """README: without the bulk viscosity the runs grow at the main set's rates (within 2 %) and the same runs grow:
    the viscosity on the SPH divergence does not see these modes. Fails if the no-bulk set's outcome differs."""
    runs = r.csv("runs.csv")
    n = 0
    for x in select(runs, set="no-bulk"):
        y = one(runs, set="main", formulation=x["formulation"], h_over_dx=x["h_over_dx"], xi=x["xi"])
        check(x["grew"] == y["grew"], f"{x.where()}: grew {x['grew']} without, {y['grew']} with the bulk viscosity")
        if x["grew"] == 1:
            approx(x["gamma_measured"], y["gamma_measured"], f"{x.where()} measured rate without bulk viscosity",
                   rel=0.02)
            n += 1
    return f"{n} growing runs at the same rate with and without"
