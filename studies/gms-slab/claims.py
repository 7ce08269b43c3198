"""Headline claims of gms-slab (results/gms-slab/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, md_table, one, select

GMS_EPS0_BREAK, GMS_NECK, GMS_EPS03_BREAK = 119, 394, 542


def _run(r, dp, eps):
    return one(r.csv("runs.csv"), dp=dp, eps=eps)


def _nan_or(value):
    return "-" if isinstance(value, float) and math.isnan(value) else value


def claim_headline_is_the_finer_run(r):
    """Headline: the key numbers (neck onset, break, cracks, distance from the junction, end displacement, strains) are
    the runs.csv row of the finer dp; ε = 0 has no neck onset and two cracks, ε = 0.3 one crack."""
    fine = min(x["dp"] for x in r.csv("runs.csv"))
    approx(r.num("fine_dp"), fine, "fine_dp", rel=1e-9)
    for eps, key in ((0.3, "eps03"), (0.0, "eps0")):
        x = _run(r, fine, eps)
        for col, k in (("t_break", "t_break"), ("t_separation", "t_separation"), ("cracks", "cracks"),
                       ("t_stop", "t_stop")):
            approx(r.num(f"{key}_{k}"), x[col], f"{x.where()} {k}", abs_=0.5)
        approx(r.num(f"{key}_break_junction"), min(x["junction_distance_left"], x["junction_distance_right"]),
               f"{x.where()} crack distance from its junction", rel=2e-3)
        approx(r.num(f"{key}_end_displacement"), x["end_displacement_at_break"], f"{x.where()} end displacement",
               rel=2e-3)
        approx(r.num(f"{key}_break_strain"), x["end_displacement_at_break"] / 3, f"{x.where()} break strain d/3",
               rel=5e-3)
        # each end moves 2.5e-6 t^2: the displacement at the break is the driven law at t_break
        approx(x["end_displacement_at_break"], 2.5e-6 * x["t_break"] ** 2, f"{x.where()} d(t_break)", rel=0.01)
    e3, e0 = _run(r, fine, 0.3), _run(r, fine, 0.0)
    approx(r.num("eps03_t_neck"), e3["t_neck"], f"{e3.where()} neck onset", abs_=0.5)
    approx(r.num("eps03_neck_strain"), 2.5e-6 * e3["t_neck"] ** 2 / 3, "ε = 0.3 neck strain d/3", rel=5e-3)
    check(r.key("eps0_t_neck") == "-" and math.isnan(e0["t_neck"]), f"{e0.where()}: ε = 0 has a neck onset")
    check(e0["cracks"] == 2 and e3["cracks"] == 1, f"cracks ε = 0: {e0['cracks']}, ε = 0.3: {e3['cracks']}")
    return f"dp = {fine}: ε = 0.3 neck {e3['t_neck']}, break {e3['t_break']} (1 crack); ε = 0 break {e0['t_break']} " \
           f"(2 cracks)"


def claim_results_table_is_runs_csv(r):
    """The results table's neck onset, t_w95, t_w10, break, separation, cracks and stop time are runs.csv, every run."""
    rows = r.csv("runs.csv")
    table = md_table(r.key("results_table"))
    check(len(table) == len(rows), f"results table {len(table)} rows, runs.csv {len(rows)}")
    for row in table:
        x = _run(r, float(row[0]), float(row[2]))
        for i, col in ((3, "t_neck"), (5, "t_w95"), (6, "t_w10"), (8, "t_separation"), (9, "cracks"), (13, "t_stop")):
            want = _nan_or(x[col])
            check(row[i] == "-" if want == "-" else float(row[i]) == want, f"{x.where()}: {col} {want}, table {row[i]}")
        brk, gms = row[7].split()
        check(float(brk) == x["t_break"], f"{x.where()}: break {x['t_break']}, table {brk}")
        want_gms = GMS_EPS03_BREAK if x["eps"] > 0 else GMS_EPS0_BREAK
        check(gms == f"({want_gms})", f"{x.where()}: GMS time {gms}")
    return f"{len(table)} rows = runs.csv"


def claim_eps0_breaks_without_a_neck_eps03_necks_then_breaks(r):
    """ε = 0 breaks near GMS's 119 (126 and 147, within 30 %) with no neck (the narrowest/median width of the inner
    window stays above 0.99 before the break), away from the junction (> 10 dp); when it has broken the ε = 0.3 slab is
    whole and not yet necking. ε = 0.3 necks (onset well before GMS's 394) and breaks in the middle (position
    0.5 +- 0.01) before 542, earlier at the finer dp; it is first narrower than 10 dp long before it breaks."""
    for dp in sorted({x["dp"] for x in r.csv("runs.csv")}):
        e0, e3 = _run(r, dp, 0.0), _run(r, dp, 0.3)
        check(abs(e0["t_break"] / GMS_EPS0_BREAK - 1) <= 0.3, f"{e0.where()}: ε = 0 break {e0['t_break']}")
        series = r.csv(f"series/{e0['tag']}.csv")
        ratio = min(s["min_width"] / s["median_width"] for s in series if s["t"] < e0["t_break"])
        check(ratio > 0.99, f"{e0['tag']}: narrowest/median {ratio:.4g} before the break (a neck)")
        d = min(e0["junction_distance_left"], e0["junction_distance_right"])
        check(d / dp > 10, f"{e0.where()}: ε = 0 crack {d / dp:.3g} dp from the junction")
        s3 = one(r.csv(f"series/{e3['tag']}.csv"), t=e0["t_break"])
        check(s3["broken"] == 0 and s3["fragments"] == 1 and e3["t_neck"] > e0["t_break"],
              f"{s3.where()}: ε = 0.3 broken or necking at the ε = 0 break")
        check(e3["t_neck"] < GMS_NECK / 1.5, f"{e3.where()}: neck onset {e3['t_neck']} not well before 394")
        check(e3["t_neck"] < e3["t_w10"] < e3["t_break"] - 50, f"{e3.where()}: onset/10 dp/break order")
        check(abs(e3["position_left"] - 0.5) <= 0.01, f"{e3.where()}: ε = 0.3 crack at {e3['position_left']}")
        check(e3["t_break"] < GMS_EPS03_BREAK, f"{e3.where()}: ε = 0.3 break after 542")
    breaks = [_run(r, dp, 0.3)["t_break"] for dp in sorted({x["dp"] for x in r.csv("runs.csv")})]
    check(breaks == sorted(breaks) and breaks[0] < breaks[-1], f"ε = 0.3 breaks by dp: {breaks}")
    return f"ε = 0.3 breaks {breaks} (fine to coarse), all before 542; ε = 0 without a neck"


def claim_frozen_spectrum(r):
    """Linearised states: the start is stable; without viscosity the growth rate rises from t = 60 to 100 (ε = 0),
    ε = 0.3 lowers it but has more unstable modes; with the viscosity on the rate falls about 20x (15-25x) to an
    e-folding time of about 20 (15-25) and ε = 0.3 changes it by < 5 %."""
    rows = r.csv("frozen_spectrum.csv")
    f = {(x["state"], x["eps"], x["viscosity"]): x for x in rows}
    check(all(f[("start", e, 0)]["growth_rate"] == 0 and f[("start", e, 0)]["unstable_eigenvalues"] == 0
              for e in (0, 0.3)), "the start is not stable")
    check(f[("t100", 0, 0)]["growth_rate"] > f[("t60", 0, 0)]["growth_rate"] > 0, "ε = 0 growth does not rise")
    for s in ("t60", "t100"):
        a, b = f[(s, 0, 0)], f[(s, 0.3, 0)]
        check(b["growth_rate"] < a["growth_rate"] and b["unstable_eigenvalues"] > a["unstable_eigenvalues"],
              f"{b.where()}: ε = 0.3 does not lower the rate and add modes")
    fall = f[("t100", 0, 0)]["growth_rate"] / f[("t100", 0, 1)]["growth_rate"]
    check(15 <= fall <= 25, f"viscosity lowers the rate {fall:.3g}x")
    efold = 1 / f[("t100", 0, 1)]["growth_rate"]
    check(15 <= efold <= 25, f"e-folding time {efold:.3g}")
    approx(f[("t100", 0.3, 1)]["growth_rate"], f[("t100", 0, 1)]["growth_rate"], "ε = 0.3 with viscosity", rel=0.05)
    table = md_table(r.key("frozen_table"))
    check(len(table) == len(rows), "frozen table rows differ from frozen_spectrum.csv")
    for row, x in zip(table, rows):
        approx(float(row[3]), x["growth_rate"], f"{x.where()} growth rate in the table", rel=5e-3, abs_=1e-9)
        check(int(row[4]) == x["unstable_eigenvalues"], f"{x.where()}: eigenvalue count in the table")
    return f"viscosity lowers the t = 100 rate {fall:.3g}x, e-folding {efold:.3g}"


def claim_artificial_stress_costs_more_per_step(r):
    """Cost, ratios within the run: the ε = 0.3 runs cost more CPU per particle-step than the ε = 0 runs at each dp,
    and the cost table is runs.csv."""
    out = []
    for dp in sorted({x["dp"] for x in r.csv("runs.csv")}):
        ratio = _run(r, dp, 0.3)["us_cpu"] / _run(r, dp, 0.0)["us_cpu"]
        check(ratio > 1, f"dp {dp}: ε = 0.3 / ε = 0 per particle-step {ratio:.3g}")
        out.append(f"{ratio:.3g}")
    for row in md_table(r.key("cost_table")):
        x = one(r.csv("runs.csv"), tag=row[0])
        check(int(row[3]) == x["steps"] and int(row[9]) == x["neighbour_builds"] and row[10] == x["status"],
              f"{x.where()}: cost table row differs")
    return f"ε = 0.3 / ε = 0 CPU per particle-step: {', '.join(out)}"
