"""Headline claims of critical-strain-2d (results/critical-strain-2d/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, close, md_table, one, select

INF = float("inf")


def _cell(value):
    """A table cell as a float ('inf', '-inf' included)."""
    return float(value)


def _printed(cell, value, what, digits):
    """The cell is `value` printed to `digits` significant digits (half a unit in the last place, plus 1 %)."""
    if value == 0 or not math.isfinite(value):
        return approx(cell, value, what, abs_=1e-15)
    ulp = 10 ** (math.floor(math.log10(abs(value))) - digits + 1)
    return approx(cell, value, what + f" (printed to {digits} digits)", abs_=0.505 * ulp)


def claim_headline_square_cubic_13(r):
    """Headline: square lattice, cubic, h = 1.3 dx, conservative, n = n_main: e_crit in tension and compression and
    the critical-mode wavevector (table_conservative) are the sweep.csv rows; every table row matches sweep.csv."""
    sweep = r.csv("sweep.csv")
    n = r.num("n_main")
    rows = md_table(r.key("table_conservative"))
    for row in rows:
        lattice, kernel, h = row[0], row[1], float(row[2])
        for direction, col in (("tension", 3), ("compression", 6)):
            x = one(sweep, lattice=lattice, kernel=kernel, h_over_dx=h, form="conservative", prestrain="isotropic",
                    direction=direction, n=n)
            _printed(_cell(row[col]), x["ecrit"], f"{x.where()} e_crit in table_conservative", 3)
            _printed(_cell(row[col + 2]), x["ecrit_infinite"], f"{x.where()} e_inf in table_conservative", 3)
            if math.isfinite(x["ecrit"]):
                kx, ky = (float(v) for v in row[col + 1].strip("()").split(","))
                _printed(kx, x["mode_kx_over_pi"], f"{x.where()} mode kx", 2)
                _printed(ky, x["mode_ky_over_pi"], f"{x.where()} mode ky", 2)
    t = one(sweep, lattice="square", kernel="cubic", h_over_dx=1.3, form="conservative", prestrain="isotropic",
            direction="tension", n=n)
    c = one(sweep, lattice="square", kernel="cubic", h_over_dx=1.3, form="conservative", prestrain="isotropic",
            direction="compression", n=n)
    check(t["ecrit"] > 0 > c["ecrit"] and abs(c["ecrit"]) < t["ecrit"],
          f"square cubic 1.3: tension {t['ecrit']:.3g}, compression {c['ecrit']:.3g} (compression expected smaller)")
    return (f"{len(rows)} table rows = sweep.csv; square cubic 1.3: {t['ecrit']:.3g} tension, "
            f"{c['ecrit']:.3g} compression")


def claim_routes_agree(r):
    """Bisection and eigen routes agree to route_max_rel_diff on the route_rows rows with a finite e_crit by both,
    route_over_1e-8 of them by more than 1e-8 (the route_worst case); every sweep row is successful."""
    sweep = r.csv("sweep.csv")
    both = [x for x in sweep if not math.isnan(x["ecrit_bisect"]) and math.isfinite(x["ecrit"])]
    check(len(both) == r.num("route_rows"), f"{len(both)} rows with both routes, summary says {r.key('route_rows')}")
    worst = max(both, key=lambda x: x["rel_diff"])
    approx(worst["rel_diff"], r.num("route_max_rel_diff"), f"{worst.where()} largest rel_diff", rel=0.05)
    over = sum(x["rel_diff"] > 1e-8 for x in both)
    check(over == r.num("route_over_1e-8"), f"{over} rows differ by > 1e-8, summary says {r.key('route_over_1e-8')}")
    name = (f"{worst['lattice']} {worst['kernel']} h/dx = {worst['h_over_dx']:g} {worst['form']} "
            f"{worst['prestrain']} {worst['direction']}")
    check(r.key("route_worst").startswith(name), f"worst case is {name}, summary names {r.key('route_worst')}")
    check(worst["rel_diff"] <= 1e-7, f"{worst.where()}: routes differ by {worst['rel_diff']:.3g}")
    bad = [x.where() for x in sweep if x["status"] != "successful"]
    check(len(bad) == r.num("rows_not_successful") == 0, f"rows not successful: {bad}")
    check(len(sweep) == r.num("sweep_rows"), f"sweep.csv has {len(sweep)} rows, summary {r.key('sweep_rows')}")
    return f"{len(both)} rows, max rel diff {worst['rel_diff']:.3g} ({name}), {over} above 1e-8"


def claim_isotropic_form_ratios_2_and_4(r):
    """Isotropic pre-strain: e_crit(plus) = 2 e_crit(conservative), e_crit(uncorrected) = 4 e_crit(conservative)
    (largest deviations ratio_dev_plus, ratio_dev_uncorrected); minus: e_crit = inf in both directions."""
    sweep = r.csv("sweep.csv")
    dev = {"plus": 0.0, "uncorrected": 0.0}
    pairs = 0
    for f, k in (("plus", 2.0), ("uncorrected", 4.0)):
        for y in select(sweep, form=f, prestrain="isotropic"):
            x = one(sweep, lattice=y["lattice"], kernel=y["kernel"], h_over_dx=y["h_over_dx"], form="conservative",
                    prestrain="isotropic", direction=y["direction"], n=y["n"])
            if math.isinf(x["ecrit"]):
                check(y["ecrit"] == x["ecrit"], f"{y.where()}: {f} finite where conservative is {x['ecrit']}")
                continue
            dev[f] = max(dev[f], abs(y["ecrit"] / x["ecrit"] / k - 1))
            pairs += 1
    approx(dev["plus"], r.num("ratio_dev_plus"), "largest deviation of plus/conservative from 2", rel=0.05)
    approx(dev["uncorrected"], r.num("ratio_dev_uncorrected"), "largest deviation of uncorrected/conservative from 4",
           rel=0.05)
    check(max(dev.values()) < 1e-7, f"form ratios deviate by {max(dev.values()):.3g}")
    minus = select(sweep, form="minus")
    check(minus and all(x["ecrit"] == (INF if x["direction"] == "tension" else -INF) for x in minus),
          "a minus-form row with a finite e_crit")
    return f"{pairs} pairs: plus 2x to {dev['plus']:.2g}, uncorrected 4x to {dev['uncorrected']:.2g}; minus inf " \
           f"in {len(minus)} rows"


def claim_infinite_lattice_counts(r):
    """Infinite lattice, conservative, square and hex, both pre-strains: e_inf = 0 (zone-boundary zero) in
    infinite_tension_zero of infinite_tension_cases in tension and infinite_compression_zero in compression; the
    tiny (< 1e-6), positive/finite and stable counts likewise. A finite block then survives only |e| ~ n^-2
    (versus_n.csv, _n_decay)."""
    rows = [x for x in r.csv("infinite.csv") if x["form"] == "conservative" and x["lattice"] in ("square", "hex")]
    for d, keys in (("tension", ("zero", "tiny", "positive", None)),
                    ("compression", ("zero", "tiny", "finite", "stable"))):
        e = [abs(x["ecrit_infinite"]) for x in rows if x["direction"] == d]
        got = (sum(v == 0 for v in e), sum(0 < v < 1e-6 for v in e), sum(1e-6 <= v < INF for v in e),
               sum(v == INF for v in e))
        want = tuple(r.num(f"infinite_{d}_{k}") if k else 0 for k in keys)
        check(len(e) == r.num(f"infinite_{d}_cases"), f"{len(e)} {d} cases, summary {r.key(f'infinite_{d}_cases')}")
        check(got == want, f"infinite.csv {d}: (zero, tiny, finite, stable) = {got}, summary {want}")
    zero_t = r.num("infinite_tension_zero") / r.num("infinite_tension_cases")
    check(zero_t > 0.9, f"tension e_inf = 0 in only {zero_t:.0%} ('essentially every kernel and h')")
    decay = _n_decay(r)
    return (f"tension zero {r.key('infinite_tension_zero')}/{r.key('infinite_tension_cases')}, compression zero "
            f"{r.key('infinite_compression_zero')}/{r.key('infinite_compression_cases')}; n x n block: {decay}")


def _n_decay(r):
    """Where e_inf = 0, |e_crit(n)| falls with n (slope p over 40-80 as in table_versus_n, within 1.8..2.3), and the
    periodic lattice (even n) has e = 0."""
    rows = r.csv("versus_n.csv")
    table = md_table(r.key("table_versus_n"))
    for row in table:
        lattice, direction = row[0], row[3]
        series = sorted(select(rows, lattice=lattice, direction=direction), key=lambda x: x["n"])
        check([x["n"] for x in series] == [10, 20, 40, 80], f"versus_n.csv {lattice} {direction}: n values")
        e = [abs(x["ecrit"]) for x in series]
        check(all(a > b for a, b in zip(e, e[1:])), f"versus_n.csv {lattice} {direction}: |e_crit| not falling {e}")
        p = math.log(e[2] / e[3]) / math.log(2)
        approx(p, float(row[8]), f"{lattice} {direction} slope p (40-80)", abs_=0.006)
        check(1.8 <= p <= 2.3, f"{lattice} {direction}: slope {p:.3g} not about 2")
        check(all(x["ecrit_infinite"] == 0 and x["ecrit_periodic"] == 0 for x in series),
              f"{lattice} {direction}: e_inf or periodic e not 0")
    return f"{len(table)} series, slopes {', '.join(row[8] for row in table)}"


def claim_uniaxial_plus_flutter(r):
    """Uniaxial plus form, spectrum criterion: flutter_cases of nonsymmetric_finite_cases finite cases lose stability
    by a complex pair before the real crossing, at flutter_ratio_min..flutter_ratio_max of it."""
    rows = r.csv("nonsymmetric.csv")
    check(len(rows) == r.num("nonsymmetric_rows"), f"{len(rows)} rows, summary {r.key('nonsymmetric_rows')}")
    finite = [x for x in rows if math.isfinite(x["ecrit"])]
    check(len(finite) == r.num("nonsymmetric_finite_cases"),
          f"{len(finite)} finite cases, summary {r.key('nonsymmetric_finite_cases')}")
    flutter = [x for x in finite if x["mechanism"] == "complex-pair"]
    check(len(flutter) == r.num("flutter_cases"), f"{len(flutter)} complex-pair cases, summary {r.key('flutter_cases')}")
    ratios = [x["ecrit"] / x["ecrit_eig"] for x in flutter if math.isfinite(x["ecrit_eig"])]
    check(all(0 < q < 1 for q in ratios), "a flutter load not below its real crossing")
    approx(min(ratios), r.num("flutter_ratio_min"), "min e_crit(flutter)/e(real crossing)", rel=5e-3)
    approx(max(ratios), r.num("flutter_ratio_max"), "max e_crit(flutter)/e(real crossing)", rel=5e-3)
    return f"{len(flutter)} of {len(finite)} flutter, ratio {min(ratios):.3g}..{max(ratios):.3g}"
