"""Headline claims of gms-rings (results/gms-rings/), run by tests/scripts/claims_test.py."""
import math

from claims import approx, check, one, select

VARIANTS = {"": "", "pairs_": "_pairs", "fast_": "_fast", "halfdt_": "_halfdt"}  # summary prefix -> tag suffix


def _gms_runs(r, eps):
    out = {}
    for prefix, suffix in VARIANTS.items():
        rows = select(r.csv("runs.csv"), tag=f"gms_eps{eps}{suffix}")
        if rows:
            out[prefix] = rows[0]
    return out


def claim_outcome_words_follow_counts(r):
    """The outcome the summary and headline print for each GMS-unit run is the driver's rule on runs.csv: a ring
    breaks iff more than break_share_pct % of its particles left its largest fragment at some record (lost_max), else
    'intact' with ' (sheds k)' when k = lost_max > 0, then ', separated' iff separated."""
    share = r.num("break_share_pct") / 100
    n = 0
    for eps, key in (("0", "eps0"), ("0.3", "eps03")):
        for prefix, x in _gms_runs(r, eps).items():
            if x["lost_max"] > share * x["per_ring"]:
                want = f"a ring breaks ({x['lost_end']} particles lost)"
            else:
                shed = f" (sheds {x['lost_max']})" if x["lost_max"] > 0 else ""
                want = "intact" + shed + (", separated" if x["separated"] == 1 else ", not separated by t_end")
            got = r.key(f"{prefix}{key}_outcome")
            check(got == want, f"{x.where()}: {x['tag']} outcome '{got}', runs.csv gives '{want}'")
            n += 1
    return f"{n} outcomes follow runs.csv"


def claim_eps0_fractures(r):
    """GMS Fig. 6 reproduced: at epsilon = 0 every GMS-unit variant (rows, pairs, fast) breaks a ring, more than 40 % of
    its particles outside its largest fragment, first split at eps0_ring_break_time, and the rings do not separate."""
    runs = _gms_runs(r, "0")
    check(len(runs) >= 3, f"{len(runs)} epsilon = 0 GMS runs")
    for x in runs.values():
        check(x["lost_end"] > 0.4 * x["per_ring"] and x["separated"] == 0,
              f"{x.where()}: {x['tag']} lost {x['lost_end']} of {x['per_ring']}, separated {x['separated']}")
        approx(x["ring_break_time"], r.num("eps0_ring_break_time"), f"{x.where()} first ring split", abs_=0.06)
    return f"lost {runs['']['lost_end']} of {runs['']['per_ring']} at t_end; first split at {r.key('eps0_ring_break_time')}"


def claim_eps03_outcome_is_the_same_at_half_the_time_step(r):
    """Issue 31 item 8. At epsilon = 0.3 every variant (rows, pairs, fast, rows at dt/2) has the same outcome class,
    intact and separated: what breaks off is at most a few particles (lost_max below the break line), against more
    than 1000 at epsilon = 0. The old rule (a ring 'breaks' at a second fragment) flipped the verdict between dt and
    dt/2 on 2 torn-off particles of 2196."""
    runs = _gms_runs(r, "0.3")
    check(set(runs) == set(VARIANTS), f"epsilon = 0.3 variants present: {sorted(runs)}")
    share = r.num("break_share_pct") / 100
    for p, x in runs.items():
        word = r.key(f"{p}eps03_outcome")
        check(word.startswith("intact") and word.endswith(", separated"), f"{x.where()}: {x['tag']} outcome '{word}'")
        check(x["lost_max"] <= share * x["per_ring"], f"{x.where()}: {x['tag']} loses {x['lost_max']}")
    eps0 = min(x["lost_end"] for x in _gms_runs(r, "0").values())
    worst = max(x["lost_max"] for x in runs.values())
    check(eps0 > 500 * max(worst, 1), f"epsilon = 0 loses only {eps0}")
    return f"all {len(runs)} variants intact and separated, at most {worst} torn off; epsilon = 0 loses >= {eps0}"


def claim_rebound_unaffected(r):
    """'The rings' rebound speed, the centre-of-mass row, is unaffected': the right ring's vx at t_end agrees within 1 %
    across the epsilon = 0.3 variants (rows, pairs, fast, dt/2); restitution eps03_restitution for rows and pairs."""
    runs = _gms_runs(r, "0.3")
    vx = [x["com_vx1_after"] if x["separated"] == 1 else float(r.key(f"{p}eps03_vx_end")) for p, x in runs.items()]
    check(max(vx) / min(vx) - 1 < 0.01, f"rebound speeds {vx}")
    for p in ("", "pairs_"):
        approx(runs[p]["restitution"], r.num(f"{p}eps03_restitution"), f"{runs[p].where()} restitution", abs_=0.006)
    return f"vx {min(vx):.4g}..{max(vx):.4g}; restitution {r.key('eps03_restitution')}"


def claim_loop_speed_order(r):
    """Ratios within one run set: per particle-step (CPU) the pair loop is cheaper than the row loop and the one-rate
    ('fast') step cheaper than the pair loop, in every units/epsilon configuration."""
    runs = r.csv("runs.csv")
    out = []
    for units, eps in (("gms", "0"), ("gms", "0.3"), ("si", "0"), ("si", "0.3")):
        rows, pairs, fast = (one(runs, tag=f"{units}_eps{eps}{s}")["us_cpu"] for s in ("", "_pairs", "_fast"))
        check(fast < pairs < rows, f"runs.csv {units} eps {eps}: us_cpu rows {rows}, pairs {pairs}, fast {fast}")
        out.append(f"{rows / fast:.2g}x")
    return "rows/fast " + ", ".join(out)


def claim_frozen_spectra(r):
    """The linearised spectra along the epsilon = 0 collision (frozen_spectrum.csv), as the summary reads them: taken
    in the four mirror classes (invariance residuals <= 1e-10, the peak named in the quadrant x, y >= 0; no mode named
    for a state without an unstable eigenvalue); the start is stable; at contact unstable modes without viscosity under epsilon = 0 and 0.3, fewer and slower with it on; on
    the rebound the epsilon = 0 growth rate rises from state to state; epsilon = 0.3 lowers the last state's largest
    growth rate (the summary's ratio) yet has more unstable eigenvalues than epsilon = 0 at every rebound state."""
    rows = r.csv("frozen_spectrum.csv")
    for x in rows:
        check(x["symmetry_residual"] <= 1e-10, f"{x.where()}: invariance residual {x['symmetry_residual']}")
        if x["unstable_eigenvalues"] > 0:
            check(x["mode_class_x"] in (1, -1) and x["mode_class_y"] in (1, -1), f"{x.where()}: mode class")
            check(x["mode_peak_x"] >= -1e-9 and x["mode_peak_y"] >= -1e-9, f"{x.where()}: peak outside x, y >= 0")
        else:  # no unstable eigenvalue: no mode to name
            check(math.isnan(x["mode_class_x"]) and math.isnan(x["mode_peak_x"]), f"{x.where()}: a stable mode named")
    for x in select(rows, state="start"):
        check(x["unstable_eigenvalues"] == 0, f"{x.where()}: the start has unstable eigenvalues")
    first = min(x["t"] for x in rows if x["state"] != "start")
    for eps in (0, 0.3):
        off, on = one(rows, t=first, eps=eps, viscosity=0), one(rows, t=first, eps=eps, viscosity=1)
        check(off["unstable_eigenvalues"] > 0, f"{off.where()}: no unstable mode at contact")
        check(on["unstable_eigenvalues"] < off["unstable_eigenvalues"] and on["growth_rate"] < off["growth_rate"],
              f"{on.where()}: the viscosity does not reduce the unstable modes")
    eps0 = sorted((x for x in rows if x["state"] != "start" and x["eps"] == 0 and x["viscosity"] == 0),
                  key=lambda x: x["t"])
    for a, b in zip(eps0, eps0[1:]):
        check(b["growth_rate"] > a["growth_rate"], f"{b.where()}: epsilon = 0 growth does not rise")
    last = eps0[-1]
    l03 = one(rows, t=last["t"], eps=0.3, viscosity=0)
    ratio = l03["growth_rate"] / last["growth_rate"]
    check(ratio < 1, f"{l03.where()}: epsilon = 0.3 does not lower the growth rate")
    approx(r.num("frozen_last_eps03_over_eps0"), ratio, "summary frozen_last_eps03_over_eps0", abs_=0.0051)
    for x in eps0[1:]:  # the rebound states: epsilon = 0.3 has more unstable eigenvalues than epsilon = 0
        x03 = one(rows, t=x["t"], eps=0.3, viscosity=0)
        check(x03["unstable_eigenvalues"] > x["unstable_eigenvalues"], f"{x03.where()}: fewer unstable with 0.3")
    return (f"{len(rows)} spectra in 4 classes; last state epsilon = 0.3 / 0: {ratio:.2f}; unstable "
            f"{last['unstable_eigenvalues']} -> {l03['unstable_eigenvalues']}")
