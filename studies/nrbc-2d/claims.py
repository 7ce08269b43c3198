"""Headline claims of nrbc-2d (results/nrbc-2d/), run by tests/scripts/claims_test.py."""
from claims import approx, check, md_table, one, select

FIELDS = {"centred (2.73)": "centred", "skewed (2.74)": "skewed", "central disc (2.76)": "disc",
          "central disc, v0 = 0.05": "disc_fast"}
POWELL = 0.0025  # Powell's "less than 0.25 %" of KE0


def _run(r, boundary, field, timing="whole"):
    return one(r.csv("runs.csv"), boundary=boundary, field=field, timing=timing)


def _dev(r, boundary, field, timing="whole"):
    return _run(r, boundary, field, timing)["max_deviation"]


def _series(r, boundary, field, timing="whole"):
    name = f"{boundary}_{field}" + ("" if timing == "-" else f"_{timing}")
    return r.csv(f"series/{name}.csv")


def claim_table_is_runs_csv(r):
    """Headline: the table's largest (KE - KE_ref)/KE0 per field and boundary, its time, status and absorbing
    particles are runs.csv; only the free NCSPH blocks (and no absorbing run) stop with energy growth."""
    rows = r.csv("runs.csv")
    table = md_table(r.key("table"))
    for row in table:
        field, boundary = FIELDS[row[0]], row[1].replace(" †", "")
        x = one(rows, boundary=boundary, field=field, timing=row[2])
        check(row[4] == x["status"], f"{x.where()}: status {x['status']}, table {row[4]}")
        check(int(row[3].split()[0]) == x["absorbing"], f"{x.where()}: absorbing {x['absorbing']}, table {row[3]}")
        dev, t = row[5].split(" % at t = ")
        approx(float(dev), 100 * x["max_deviation"], f"{x.where()} largest deviation (%)", rel=6e-3)
        if t != "-":
            approx(float(t), x["t_max_deviation"], f"{x.where()} time of the largest deviation", rel=6e-3)
    check(len(table) == len([x for x in rows if x["boundary"] != "reference"]), "table rows differ from runs.csv")
    stopped = sorted({x["boundary"] for x in rows if x["status"] != "completed"})
    check(stopped == ["free"], f"runs that did not complete: {stopped}")
    return f"{len(table)} rows = runs.csv; only 'free' stops (energy growth)"


def claim_square_absorbs_but_not_to_powell(r):
    """Centred and skewed square: P deviates 2.7 % / 3.7 % and M 4.5 % / 6.9 % of KE0 (M worse than P), 10-30x
    Powell's 0.25 %; with P the block comes to rest (KE at 4 us ~ 2e-5 KE0), M skewed keeps ~5 % (residual motion)."""
    for b, f, want in (("P", "centred", 2.74), ("M", "centred", 4.51), ("P", "skewed", 3.74), ("M", "skewed", 6.89)):
        x = _run(r, b, f)
        approx(100 * x["max_deviation"], want, f"{x.where()} {b} {f} deviation (%)", abs_=0.006)
        check(10 <= x["max_deviation"] / POWELL <= 30, f"{x.where()}: {x['max_deviation'] / POWELL:.3g}x Powell's 0.25 %")
    for f in ("centred", "skewed"):
        check(_dev(r, "M", f) > _dev(r, "P", f), f"{f}: M {_dev(r, 'M', f):.3g} not worse than P {_dev(r, 'P', f):.3g}")
    p = _run(r, "P", "centred")
    check(1e-5 <= p["ke_end"] <= 3e-5, f"{p.where()}: P centred KE at the end {p['ke_end']:.3g} KE0, not ~2e-5")
    m = _run(r, "M", "skewed")
    approx(m["ke_end"], 0.05, f"{m.where()} M skewed KE at the end", abs_=0.005)
    return f"P {100 * _dev(r, 'P', 'centred'):.3g}/{100 * _dev(r, 'P', 'skewed'):.3g} %, M " \
           f"{100 * _dev(r, 'M', 'centred'):.3g}/{100 * _dev(r, 'M', 'skewed'):.3g} % (centred/skewed)"


def claim_square_deviation_before_the_front(r):
    """The largest deviations of the centred runs and of P skewed occur at t = 0.42-0.70 us, before the front reaches
    the edge midpoints (0.83 us); after t = 1.2 us M centred stays within Powell's 0.25 %, P centred has a second
    bump of about 1.2 % near t = 1.5 us (1.3-1.7) that has decayed below 0.1 % by 2.5 us; M skewed peaks at ~2.5 us."""
    times = [_run(r, b, "centred", t)["t_max_deviation"] for b in ("P", "M") for t in ("whole", "half")]
    times += [_run(r, b, "centred")["t_max_deviation"] for b in ("H-Powell", "H-Higdon")]
    times += [_run(r, "P", "skewed", t)["t_max_deviation"] for t in ("whole", "half")]
    check(all(0.41 <= t <= 0.70 < 0.83 for t in times), f"times of the largest deviations {times}")
    for timing in ("whole", "half"):
        m = _series(r, "M", "centred", timing)
        late = max(abs(x["ke_over_ke0"] - x["ke_ref_over_ke0"]) for x in m if x["t"] > 1.2)
        check(late <= POWELL, f"M centred {timing}: {100 * late:.3g} % after t = 1.2 us")
        p = [x for x in _series(r, "P", "centred", timing) if x["t"] > 1.2]
        bump = max(p, key=lambda x: abs(x["ke_over_ke0"] - x["ke_ref_over_ke0"]))
        size = abs(bump["ke_over_ke0"] - bump["ke_ref_over_ke0"])
        check(1.3 <= bump["t"] <= 1.7 and abs(size - 0.012) <= 0.001, f"{bump.where()}: P bump {100 * size:.3g} % "
                                                                        f"at t = {bump['t']:.3g}")
        tail = max(abs(x["ke_over_ke0"] - x["ke_ref_over_ke0"]) for x in p if x["t"] >= 2.5)
        check(tail < 0.001, f"P centred {timing}: {100 * tail:.3g} % after 2.5 us")
    m = _run(r, "M", "skewed")
    approx(m["t_max_deviation"], 2.5, f"{m.where()} time of M skewed's largest deviation", abs_=0.1)
    return f"largest deviations at t = {min(times):.3g}..{max(times):.3g} us; M within 0.25 % after 1.2 us"


def claim_disc_and_boundary_variants(r):
    """Disc (2.76): P 1.69 %, M 0.79 % (M better), at t = 0.85-1.07 us; Powell's H worse than P (2.74 -> 3.9 % centred,
    1.69 -> 2.64 % disc), Higdon's factor 1.62 % centred (better than P) and 1.66 % disc (as P, within 0.05); the
    LS-DYNA traction 1.18 % / 0.83 % between M and P, the plain block without it 43 %, traction on the centred field
    42 %; the fast disc within 0.05 % of KE0 of the slow one; half and whole step differ by at most 0.2 % of KE0."""
    for b, f, want in (("P", "disc", 1.69), ("M", "disc", 0.786), ("H-Powell", "centred", 3.9),
                       ("H-Powell", "disc", 2.64), ("H-Higdon", "centred", 1.62), ("H-Higdon", "disc", 1.66),
                       ("traction", "disc", 1.18), ("traction", "disc_fast", 0.83), ("traction", "centred", 42.3)):
        approx(100 * _dev(r, b, f), want, f"{b} {f} deviation (%)", abs_=0.006 if want < 10 else 0.06)
    approx(100 * _run(r, "free-plain", "disc", "-")["max_deviation"], 43, "free-plain disc deviation (%)", abs_=0.5)
    check(_dev(r, "M", "disc") < _dev(r, "P", "disc"), "disc: M not better than P")
    check(all(0.845 <= _run(r, b, "disc", t)["t_max_deviation"] < 1.075 for b in ("P", "M") for t in ("whole", "half")),
          "disc P/M deviations outside t = 0.85-1.07 us (3 digits)")
    for f in ("centred", "disc"):
        check(_dev(r, "H-Powell", f) > _dev(r, "P", f), f"{f}: Powell's H not worse than P")
    check(_dev(r, "H-Higdon", "centred") < _dev(r, "P", "centred"), "centred: Higdon's factor not better than P")
    check(abs(_dev(r, "H-Higdon", "disc") - _dev(r, "P", "disc")) <= 0.0005, "disc: Higdon's factor not as P")
    for f in ("disc", "disc_fast"):
        check(_dev(r, "M", f) < _dev(r, "traction", f) < _dev(r, "P", f), f"{f}: traction not between M and P")
    for b in ("P", "M", "H-Powell", "H-Higdon"):
        d = abs(_dev(r, b, "disc_fast") - _dev(r, b, "disc"))
        check(d <= 0.0005, f"{b}: fast disc differs from the slow one by {100 * d:.3g} % of KE0")
    steps = [abs(_dev(r, b, f, "whole") - _dev(r, b, f, "half")) for b in ("P", "M") for f in ("centred", "skewed", "disc")]
    check(max(steps) <= 0.00205, f"half and whole step differ by up to {100 * max(steps):.3g} % of KE0")
    return f"disc P {100 * _dev(r, 'P', 'disc'):.3g} %, M {100 * _dev(r, 'M', 'disc'):.3g} %; half/whole step " \
           f"<= {100 * max(steps):.2g} %"


def claim_free_ncsph_block_blows_up(r):
    """The free NCSPH block blows up: kinetic energy above 100 KE0 near t = 3.5 us (centred, skewed; 3.7 us for the fast
    disc), the free disc block 7.9 KE0 at 4 us; the free plain block completes."""
    for f, t in (("centred", 3.54), ("skewed", 3.59), ("disc_fast", 3.73)):
        x = _run(r, "free", f, "-")
        check(x["status"] == "energy-growth" and x["ke_end"] > 100, f"{x.where()}: free {f} {x['status']}, "
                                                                     f"KE {x['ke_end']:.3g} KE0")
        approx(x["t_max_deviation"], t, f"{x.where()} blow-up time", abs_=0.01)
    d = _run(r, "free", "disc", "-")
    approx(d["ke_end"], 7.9, f"{d.where()} free disc KE at 4 us (KE0)", abs_=0.05)
    plain = select(r.csv("runs.csv"), boundary="free-plain")
    check(all(x["status"] == "completed" for x in plain), "a free plain block did not complete")
    return "free NCSPH blocks > 100 KE0 at 3.5-3.7 us; free disc 7.9 KE0 at 4 us"
