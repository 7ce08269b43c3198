"""Headline claims of swegle (results/swegle/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, close, md_table, one, select, verdict_class

FORMS = ["sph", "sph-xsph", "ncsph", "tl", "cij", "ssph", "ssph-pp", "ssph-pp-noxsph", "ssph-printed", "sph-gms",
         "conservative"]


def unstable(row):
    """The run's verdict as the stability table shows it: U unless the KE stayed bounded."""
    return row["run_verdict"] != "bounded"


def claim_stability_table_is_runs_csv(r):
    """Every cell of the stability table is its runs.csv row (11 x 7 runs): the verdict class, then after '·' the
    run: '–' exactly when the KE stayed bounded."""
    runs = r.csv("runs.csv")
    xis = [float(x) for x in r.key("xi_list").split(",")]
    table = md_table(r.key("stability_table"))
    check([row[0] for row in table] == FORMS, f"stability_table rows {[row[0] for row in table]}")
    check(len(runs) == len(FORMS) * len(xis), f"runs.csv has {len(runs)} rows, expected {len(FORMS) * len(xis)}")
    for row in table:
        for xi, cell in zip(xis, row[1:]):
            run = one(runs, formulation=row[0], xi=xi)
            words = cell.replace("**", "").split()
            check(words[0] == run["verdict"], f"{run.where()}: {row[0]} xi={xi} verdict {run['verdict']}, table {cell}")
            shown = cell.split("·")[1].split()[0]
            check((shown == "–") == (not unstable(run)) and (shown == "blow-up") == (
                run["run_verdict"] == "blow-up" and run["grew"] == 0),
                  f"{run.where()}: {row[0]} xi={xi} run_verdict {run['run_verdict']}, table says {cell}")
    return f"{len(runs)} cells match runs.csv"


def claim_verdicts_follow_the_rules(r):
    """Issue 31 part 1: each verdict is the class of its two rates against the floor (the detection limit of the
    run); the switching surface has none. Leap-frog is symplectic, so no class I where the map is below its limit."""
    floor = r.num("detect")
    counts = {}
    for x in r.csv("runs.csv"):
        if x["verdict"] == "n/a":
            check(x["linear_verdict"] == "switching surface" or not isinstance(x["verdict_gamma_m"], float)
                  or math.isnan(x["verdict_gamma_m"]),
                  f"{x.where()}: verdict n/a without a reason")
            continue
        want = verdict_class(x["verdict_gamma_j"], x["verdict_gamma_m"], floor)
        check(x["verdict"] == want, f"{x.where()}: verdict {x['verdict']}, the rules give {want}")
        counts[want] = counts.get(want, 0) + 1
    return ", ".join(f"{c} {n}" for c, n in sorted(counts.items()))


def claim_verdict_classes(r):
    """Headline: sph, sph-xsph and conservative grow in both directions; ncsph, tl, cij stay bounded at every xi;
    only sph-gms grows at xi = 1; the per-particle S-SPH is stable in tension and unstable in compression, the
    printed switch the reverse."""
    runs = r.csv("runs.csv")

    def grows(form, side):
        rows = [x for x in select(runs, formulation=form) if side(x["xi"])]
        return [unstable(x) for x in rows]

    comp, rest, tens = (lambda xi: xi < 1), (lambda xi: xi == 1), (lambda xi: xi > 1)
    for form in ("sph", "sph-xsph", "conservative"):
        check(all(grows(form, comp)) and all(grows(form, tens)), f"runs.csv: {form} does not grow at every xi != 1")
    for form in ("ncsph", "tl", "cij"):
        check(not any(grows(form, lambda xi: True)), f"runs.csv: {form} grows somewhere")
    at_rest = [f for f in FORMS if any(grows(f, rest))]
    check(at_rest == ["sph-gms"], f"runs.csv: unstable at xi = 1: {at_rest}, expected only sph-gms")
    check(all(grows("ssph-pp", comp)) and not any(grows("ssph-pp", tens)), "ssph-pp: not U in compression, S in tension")
    check(not any(grows("ssph-printed", comp)) and all(grows("ssph-printed", tens)),
          "ssph-printed: not S in compression, U in tension")
    return "sph/sph-xsph/conservative U both ways; ncsph/tl/cij S; sph-gms alone U at rest; S-SPH switch directions"


def claim_linear_theory_predicts_growth(r):
    """Measured/predicted gamma in [ratio_min, ratio_max] for the ratio_count comparable runs (in equilibrium, fitted
    window, xi != 1 for the switching forms), all within 3 % of 1; and no linear/run disagreement."""
    rows = [x for x in r.csv("runs.csv") if x["in_equilibrium"] == 1 and not math.isnan(x["ratio"])
            and isinstance(x["gamma_measured"], float) and not math.isnan(x["gamma_measured"])
            and x["linear_verdict"] != "switching surface"]
    ratios = [x["ratio"] for x in rows]
    check(len(rows) == r.num("ratio_count"), f"runs.csv: {len(rows)} comparable runs, summary says "
                                             f"{r.key('ratio_count')}")
    approx(min(ratios), r.num("ratio_min"), "smallest measured/predicted", rel=1e-3)
    approx(max(ratios), r.num("ratio_max"), "largest measured/predicted", rel=1e-3)
    check(0.97 <= min(ratios) and max(ratios) <= 1.0, f"ratios {min(ratios):.4g}..{max(ratios):.4g} not in [0.97, 1]")
    bad = [x.where() for x in r.csv("runs.csv") if x["agreement"] not in ("agree", "n/a", "below detection")]
    check(not bad and r.key("disagreements") == "- none", f"linear/run disagreements: {bad}")
    return f"{len(rows)} runs, measured/predicted {min(ratios):.4g}..{max(ratios):.4g}"


def claim_xsph_mitigates(r):
    """XSPH slows but does not remove the tensile growth: 0 < gamma(sph-xsph)/gamma(sph) < 1 at xi = 1.01, 1.04,
    equal to xsph_over_sph_* ."""
    runs = r.csv("runs.csv")
    for xi in ("1.01", "1.04"):
        ratio = (one(runs, formulation="sph-xsph", xi=float(xi))["gamma_measured"]
                 / one(runs, formulation="sph", xi=float(xi))["gamma_measured"])
        check(0 < ratio < 1, f"runs.csv: gamma(sph-xsph)/gamma(sph) = {ratio:.3g} at xi = {xi}")
        approx(ratio, r.num(f"xsph_over_sph_{xi}"), f"gamma ratio at xi = {xi}", rel=2e-3)
    return f"ratios {r.key('xsph_over_sph_1.01')}, {r.key('xsph_over_sph_1.04')}"


def claim_modes(r):
    """Growing modes: sph at xi_min is the zone corner (1, 1) (checkerboard), at xi_max the longitudinal (1, 0);
    sph-gms at xi_max the transverse (0, 1); linear mode and run agree."""
    runs = r.csv("runs.csv")
    for form, xi, want in (("sph", 0.96, (1, 1)), ("sph", 1.04, (1, 0)), ("sph-gms", 1.04, (0, 1)),
                           ("conservative", 0.96, (1, 1))):
        x = one(runs, formulation=form, xi=xi)
        for col in (("mode_kx", "mode_ky"), ("run_kx", "run_ky")):
            got = (x[col[0]], x[col[1]])
            check(close(got[0], want[0], abs_=1e-6) and close(got[1], want[1], abs_=1e-6),
                  f"{x.where()}: {form} xi={xi} {col} = {got}, expected {want}")
    check(r.key("k_sph_xi_min").startswith("(1, 1)") and r.key("k_sph_xi_max").startswith("(1, 0)")
          and r.key("k_sph-gms_xi_max").startswith("(0, 1)"), "summary.json mode keys differ from runs.csv")
    return "sph (1,1) in compression, (1,0) in tension; sph-gms (0,1) in tension"


def _compressive_mechanism_sentence(r, text):
    """The square-lattice B_y sign the Powell comparison states at the h of the study, and that h."""
    h = float(r.stated(r"with h = (1\.\d+) dx the transverse lattice sum B_y", text))
    sign = r.stated(r"transverse lattice sum B_y of Gray, Monaghan & Swift \(2001, 5\.24\)[^.]*? is "
                    r"(negative|positive)", text, convert=False)
    return h, sign


def claim_compressive_mode_is_not_gms_transverse(r, text=None):  # text: another summary.md, e.g. an old one
    """Issue 31 item 1. The summary states the sign of GMS's square-lattice B_y (5.24) at k = (pi, 0), h = 1.3 dx;
    it must be the sign in results/artificial-stress/thresholds.csv (+0.117: positive, so B_y is not what makes the
    block unstable in compression). The old text said 'negative'."""
    h, sign = _compressive_mechanism_sentence(r, text)
    row = one(r.other("artificial-stress").csv("thresholds.csv"), lattice="square", h_over_dp=h)
    actual = "positive" if row["By"] > 0 else "negative"
    check(sign == actual, f"summary.md says B_y is {sign} at h = {h} dx; {row.where()} has B_y = {row['By']:.4g}")
    check(row["fyy"] < 0, f"{row.where()}: f_yy = {row['fyy']:.4g}, the text says the square-lattice f_yy < 0")
    return f"B_y(pi, 0; h = {h}) = {row['By']:+.4g} ({sign}), f_yy = {row['fyy']:.4g} < 0"


def claim_compressive_mode_is_zone_corner(r):
    """Issue 31 item 1. The compressive mode is k = (pi, pi)/dx: the summary's 'stable in compression at h = a dx and
    unstable at zero strain at h = b dx, at k dx/pi = (1, 1)' holds in results/critical-strain-2d/infinite.csv
    (square, cubic, conservative, isotropic), and the sph run at xi_min grows in that mode."""
    pattern = (r"stable in compression at h = (1\.\d+) dx and unstable at zero strain at h = (1\.\d+) dx, at "
               r"k dx/pi = \((\d), (\d)\)")
    a, b, kx, ky = (r.stated(pattern, group=i, convert=False) for i in (1, 2, 3, 4))
    inf = r.other("critical-strain-2d").csv("infinite.csv")
    sel = dict(lattice="square", kernel="cubic", form="conservative", prestrain="isotropic", direction="compression")
    stable = one(inf, h_over_dx=float(a), **sel)
    check(stable["ecrit_infinite"] == -math.inf, f"{stable.where()}: h = {a} is not stable in compression "
                                                 f"(e_crit,inf = {stable['ecrit_infinite']})")
    unst = one(inf, h_over_dx=float(b), **sel)
    check(unst["ecrit_infinite"] == 0 and (unst["kx_over_pi"], unst["ky_over_pi"]) == (int(kx), int(ky)),
          f"{unst.where()}: h = {b}: e_crit,inf = {unst['ecrit_infinite']} at k dx/pi = "
          f"({unst['kx_over_pi']}, {unst['ky_over_pi']}), summary says 0 at ({kx}, {ky})")
    run = one(r.csv("runs.csv"), formulation="sph", xi=r.num("xi_min"))
    check((run["mode_kx"], run["mode_ky"]) == (1, 1), f"{run.where()}: sph compressive mode is not (1, 1)")
    return f"stable at h = {a}, unstable at h = {b} at ({kx}, {ky}); sph xi_min mode (1, 1)"


def claim_energy_second_order(r):
    """Energy error of the conservative and TL forms is O(dt^2): halving dt divides it by 4 +- 10 %, observed order
    2 +- 0.2 (energy.csv)."""
    rows = r.csv("energy.csv")
    out = []
    for form in ("conservative", "tl"):
        errs = [x["max_rel_energy_error"] for x in sorted(select(rows, formulation=form), key=lambda x: -x["dt"])]
        check(len(errs) == 3, f"energy.csv: {len(errs)} rows for {form}")
        for a, b in zip(errs, errs[1:]):
            check(3.6 <= a / b <= 4.4, f"energy.csv {form}: error ratio {a / b:.3g} not 4 +- 10 %")
        order = math.log2(errs[1] / errs[2])  # the summary's observed order: dt against dt/2
        check(abs(order - 2) <= 0.2, f"energy.csv {form}: order {order:.3g}")
        approx(order, r.num(f"energy_{form}_order"), f"{form} observed order", abs_=0.01)
        out.append(f"{form} order {order:.3g}")
    return ", ".join(out)


def claim_onedim_forms(r):
    """1D: the uncorrected, plus and conservative forms grow in tension only, minus/ncsph/cij never; measured = linear
    gamma within 1 %."""
    rows = r.csv("onedim_runs.csv")
    for x in rows:
        grows = x["grew"] == 1
        want = x["form"] in ("uncorrected", "plus", "conservative") and x["T"] > 0
        check(grows == want, f"{x.where()}: {x['form']} T={x['T']:.3g} grew={x['grew']}")
        if grows:
            approx(x["gamma_measured"], x["gamma_linear_excited"], f"{x.where()} measured gamma", rel=0.01)
    return f"{len(rows)} 1D runs: tension-unstable forms uncorrected/plus/conservative"

