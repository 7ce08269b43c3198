"""Headline claims of tl-instability (results/tl-instability/), run by tests/scripts/claims_test.py."""
import cmath

from claims import approx, check, md_table, one, select

FREE_SURFACE_SETS = ["beam", "free-beam", "block"]


def claim_cases_table_is_cases_csv(r):
    """The cases table (asymmetry, gamma, gamma dx/c_p, unstable modes, gamma real/complex) is cases.csv (a gamma
    below the mode tolerance printed as 0), and gamma dx/c_p = gamma * dx / c_p with the summary's dx and c_p."""
    rows = r.csv("cases.csv")
    table = md_table(r.key("cases"))
    check(len(table) == len(rows) == 12, f"{len(table)} table rows, {len(rows)} cases.csv rows, expected 12")
    dx, cp = r.num("dx_mm") / 1000, r.num("c_p")
    for row in table:
        x = one(rows, set=row[0], form=row[1])
        check(int(row[2]) == x["particles"] and int(row[3]) == x["dofs"], f"{x.where()}: particles/DOFs")
        approx(float(row[4]), x["asymmetry"], f"{x.where()} asymmetry", rel=0.006)
        for col, name in ((6, "gamma"), (11, "gamma_real"), (12, "gamma_complex")):
            # below the tolerance (round-off, no unstable mode) the table prints 0
            want = x[name] if x[name] > x["tolerance"] else 0.0
            approx(float(row[col]), want, f"{x.where()} {name}", rel=6e-4)
        check(int(row[10]) == x["unstable_modes"], f"{x.where()}: unstable modes {x['unstable_modes']}, table {row[10]}")
        approx(x["gamma_dx_over_c"], x["gamma"] * dx / cp, f"{x.where()} gamma dx/c_p", rel=1e-3)
    return f"{len(table)} rows match cases.csv"


def claim_ncsph_unstable_only_with_free_surfaces(r):
    """Headline: NCSPH strain + plain divergence is non-symmetric (asymmetry > 0.1) with growing modes on the beam, the
    free beam and the free block; on the periodic lattice (correction spread ~ 0) it is symmetric to round-off and
    has no growing mode (gamma below the mode tolerance, i.e. round-off). The variational NCSPH and plain forms are symmetric to 1e-15 with no growing mode on every
    set, with the same correction spread."""
    rows = r.csv("cases.csv")
    for s in FREE_SURFACE_SETS:
        x = one(rows, set=s, form="ncsph")
        check(x["asymmetry"] > 0.1 and x["gamma"] > 0 and x["unstable_modes"] > 0,
              f"{x.where()}: asymmetry {x['asymmetry']:.3g}, gamma {x['gamma']:.4g}, {x['unstable_modes']} modes")
        check(x["correction_spread"] > 0.1, f"{x.where()}: correction spread {x['correction_spread']:.3g}")
    p = one(rows, set="periodic", form="ncsph")
    check(p["asymmetry"] < 1e-14 and p["gamma"] <= p["tolerance"] and p["unstable_modes"] == 0
          and p["correction_spread"] < 1e-13,
          f"{p.where()}: periodic NCSPH asymmetry {p['asymmetry']:.3g}, gamma {p['gamma']}")
    for form in ("ncsph-variational", "plain"):
        for x in select(rows, form=form):
            check(x["asymmetry"] < 1e-15 and x["gamma"] <= x["tolerance"] and x["unstable_modes"] == 0,
                  f"{x.where()}: {form} asymmetry {x['asymmetry']:.3g}, gamma {x['gamma']}")
            ref = one(rows, set=x["set"], form="ncsph")
            check(x["correction_spread"] == ref["correction_spread"], f"{x.where()}: a different correction spread")
    worst = max(select(rows, form="ncsph"), key=lambda x: x["gamma"])
    return f"NCSPH grows on {', '.join(FREE_SURFACE_SETS)} (up to {worst['gamma']:.4g} 1/s, {worst['set']}), " \
           f"not on periodic; variational and plain never"


def claim_growth_mostly_flutter(r):
    """The growing modes are mostly complex pairs (the fastest is one on every free-surface set); a few real negative
    mu on the beams, none on the block. On the beam, spectrum.csv's mu give unstable_modes (a conjugate pair counted
    once) and the fastest rate gamma; the variational form's spectrum has no mu with growth above its tolerance."""
    rows = r.csv("cases.csv")
    for s in FREE_SURFACE_SETS:
        x = one(rows, set=s, form="ncsph")
        check(x["gamma_complex"] == x["gamma"] and x["mu_im"] != 0, f"{x.where()}: the fastest mode is not a pair")
        if s == "block":
            check(x["gamma_real"] == 0, f"{x.where()}: a real negative mu on the block")
        else:
            check(0 < x["gamma_real"] < x["gamma_complex"], f"{x.where()}: gamma real {x['gamma_real']:.4g}")
    counts = {}
    for form in ("ncsph", "ncsph-variational"):
        x = one(rows, set="beam", form=form)
        growth = [(cmath.sqrt(-complex(y["mu_re"], y["mu_im"])).real, y["mu_im"])
                  for y in select(r.csv("spectrum.csv"), set="beam", form=form)]
        check(len(growth) == x["dofs"], f"spectrum.csv beam {form}: {len(growth)} mu for {x['dofs']} DOFs")
        unstable = [(g, im) for g, im in growth if g > x["tolerance"]]
        real = sum(im == 0 for _, im in unstable)
        pairs = (len(unstable) - real) / 2
        check(real + pairs == x["unstable_modes"], f"spectrum.csv beam {form}: {real} real + {pairs} pairs, cases.csv "
                                                   f"{x['unstable_modes']}")
        approx(max(g for g, _ in growth), x["gamma"], f"spectrum.csv beam {form} fastest growth", rel=1e-9, abs_=1e-12)
        counts[form] = (real, pairs)
    real, pairs = counts["ncsph"]
    check(pairs > 5 * real, f"beam NCSPH: {pairs:g} pairs and {real} real negative mu, not 'mostly complex pairs'")
    return f"beam NCSPH: {pairs:g} complex pairs, {real} real negative mu; variational: none"


def claim_fastest_mode_on_surface_not_clamp(r):
    """The fastest NCSPH mode sits on the outermost rows (share of |mode|^2 there above 80 % and at least 1.5x those
    rows' share of particles), on the block also on the corners (share at least 2x theirs); it needs no clamp: the
    free beam has clamp share 0 and grows at least as fast as the clamped beam."""
    rows = r.csv("cases.csv")
    for s in FREE_SURFACE_SETS:
        x = one(rows, set=s, form="ncsph")
        check(x["share_surface"] > 0.8 and x["share_surface"] >= 1.5 * x["particles_surface"],
              f"{x.where()}: surface share {x['share_surface']:.2f} of |mode|^2 for {x['particles_surface']:.2f} of "
              f"the particles")
    b = one(rows, set="block", form="ncsph")
    check(b["share_corner"] >= 2 * b["particles_corner"], f"{b.where()}: corner share {b['share_corner']:.2f} for "
                                                          f"{b['particles_corner']:.2f} of the particles")
    beam, free = one(rows, set="beam", form="ncsph"), one(rows, set="free-beam", form="ncsph")
    check(free["share_clamp"] == 0 and free["particles_clamp"] == 0, f"{free.where()}: free beam has a clamp share")
    check(free["gamma"] >= beam["gamma"], f"free beam {free['gamma']:.4g} 1/s slower than clamped {beam['gamma']:.4g}")
    shares = ", ".join(f"{one(rows, set=s, form='ncsph')['share_surface']:.2f}" for s in FREE_SURFACE_SETS)
    return f"surface shares {shares}; free beam {free['gamma']:.4g} >= clamped {beam['gamma']:.4g} 1/s"
