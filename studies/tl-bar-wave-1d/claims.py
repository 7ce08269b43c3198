"""Headline claims of tl-bar-wave-1d (results/tl-bar-wave-1d/), run by tests/scripts/claims_test.py."""
from claims import approx, check, md_table, one, select

ENDS = ("clamped", "mirror", "eta", "modified")
RUN = {"clamped": "hooke-1d-stress", "mirror": "hooke-1d-stress-mirror", "eta": "hooke-1d-stress-eta",
       "modified": "hooke-1d-stress-modified"}


def _speed(r, run, n):
    return one(r.csv("speeds.csv"), run=run, n=n)


def claim_arrivals_follow_the_material_speed(r):
    """The 1D-stress runs arrive with c_b, the 1D-strain Neo-Hookean run with c_L: every arrival within 0.5 us of the
    time expected with its own speed and > 1 us from the other; the Neo-Hookean 1D-stress run coincides with Hooke's
    (arrivals to 1e-4 us, errors to 0.01 kPa, at this amplitude)."""
    cb, cl = r.num("c_b"), r.num("c_l")
    rows = r.csv("arrivals.csv")
    for x in rows:
        own, other = ("t_expected_cl_us", "t_expected_cb_us") if "strain" in x["run"] else ("t_expected_cb_us",
                                                                                               "t_expected_cl_us")
        approx(x["c_model"], cl if "strain" in x["run"] else cb, f"{x.where()} model speed", rel=1e-5)
        check(0 < x["t_arrival_sph_us"] - x[own] < 0.5, f"{x.where()}: {x['t_arrival_sph_us'] - x[own]:.3g} us late")
        check(abs(x["t_arrival_sph_us"] - x[other]) > 1, f"{x.where()}: as close to the other speed")
        h = one(rows, run="hooke-1d-stress", probe_x=x["probe_x"])
        if x["run"] == "neo-hookean-1d-stress":
            approx(x["t_arrival_sph_us"], h["t_arrival_sph_us"], f"{x.where()} Neo-Hookean = Hooke", abs_=1e-4)
    for n in (300, 600, 1200):
        a, b = _speed(r, "neo-hookean-1d-stress", n), _speed(r, "hooke-1d-stress", n)
        for col in ("max_error_kpa_x0.05", "max_error_kpa_x0.1", "max_error_kpa_x0.15"):
            approx(a[col], b[col], f"{a.where()} {col} against Hooke", abs_=0.01)
    approx(0.15 / cb * 1e6, 30, "L/c_b (us), Ismail's 30 us", rel=1e-9)
    return f"{len(rows)} arrivals within 0.5 us of their own speed"


def claim_speed_and_interior_error_converge(r):
    """The SPH speed error (always slow) and the interior errors at x = 0.05 and 0.10 fall with dx for the clamped
    runs of all three materials; the speed error is below 0.75 % at n = 300 and 0.1 % at n = 1200."""
    for run in ("hooke-1d-stress", "neo-hookean-1d-strain", "neo-hookean-1d-stress"):
        xs = [_speed(r, run, n) for n in (300, 600, 1200)]
        err = [abs(x["speed_sph_005_010"] / x["c_model"] - 1) for x in xs]
        check(all(x["speed_sph_005_010"] < x["c_model"] for x in xs), f"{run}: an SPH speed above c")
        check(err == sorted(err, reverse=True) and err[0] < 0.0075 and err[-1] < 0.001, f"{run}: speed errors {err}")
        for col in ("max_error_kpa_x0.05", "max_error_kpa_x0.1"):
            v = [x[col] for x in xs]
            check(v == sorted(v, reverse=True), f"{run}: {col} {v} does not fall")
    return "speed and interior errors fall with dx (clamped runs)"


def claim_fixed_end_errors(r):
    """Headline: the largest fixed-end error (kPa, n = 300/600/1200): the clamped ghosts barely converge (58 -> 40.5,
    < 10 % from 600 to 1200), the odd mirror converges (48.8 -> 6.15, falling), Ismail's eta does not (> 100 kPa at
    600 and 1200, while its interior errors fall like the mirror's), the modified matrix grows to far above the pulse
    amplitude (each doubling of n > 3x, 5.3e4 kPa at 1200). The fixed-end table is speeds.csv."""
    table = md_table(r.key("fixed_end"))
    check(len(table) == 12, f"fixed_end table has {len(table)} rows")
    for row in table:
        x = _speed(r, RUN[row[0]], int(row[1]))
        for i, col in ((2, "max_error_kpa_x0.05"), (3, "max_error_kpa_x0.1"), (4, "max_error_kpa_x0.15")):
            approx(float(row[i]), x[col], f"{x.where()} {col} in the table", rel=6e-3)
    end = {e: [_speed(r, RUN[e], n)["max_error_kpa_x0.15"] for n in (300, 600, 1200)] for e in ENDS}
    c, m, eta, mod = end["clamped"], end["mirror"], end["eta"], end["modified"]
    check(c[2] / c[1] > 0.9 and c[2] > 35, f"clamped end errors {c} converge")
    check(m == sorted(m, reverse=True) and m[2] < 10, f"mirror end errors {m}")
    check(min(eta) > 100, f"eta end errors {eta}")
    for n in (600, 1200):
        for col in ("max_error_kpa_x0.05", "max_error_kpa_x0.1"):
            e, mi = _speed(r, RUN["eta"], n)[col], _speed(r, RUN["mirror"], n)[col]
            check(e < 1.2 * mi, f"eta {col} at n = {n}: {e:.3g} against mirror {mi:.3g}")
    check(mod[0] > 200 and mod[1] > 3 * mod[0] and mod[2] > 3 * mod[1], f"modified end errors {mod}")
    return "end error (kPa) " + "; ".join(f"{e} {'/'.join(f'{v:.3g}' for v in end[e])}" for e in ENDS)


def claim_modified_closure_is_a_divergence(r):
    """The modified-matrix closed loop has a real negative eigenvalue with gamma dx/c = 0.00663 at every n (gamma doubles
    with n), the leap-frog rate at dt equal to gamma (0.1 %), dt half the limit; the observed slope agrees with gamma at
    n = 600 and 1200 (within 5 %) and the e-folds double with n; clamped and mirror loops are symmetric (asymmetry
    < 1e-9) and stable, eta has a weak complex pair (gamma 8.2-8.6e3 1/s, ~0.1 e-folds)."""
    g = r.csv("closure_growth.csv")
    mod = sorted(select(g, fixed_end="modified"), key=lambda x: x["n"])
    for x in mod:
        approx(x["gamma_dx_over_c"], 0.00663, f"{x.where()} gamma dx/c", rel=0.002)
        check(x["mu_re"] < 0 and x["mu_im"] == 0, f"{x.where()}: fastest mu not real negative")
        approx(x["leapfrog_rate"], x["gamma"], f"{x.where()} leap-frog rate", rel=1e-3)
        approx(x["dt"] / x["dt_limit_abs_mu"], 0.5, f"{x.where()} dt / limit", rel=1e-3)
        if x["n"] >= 600:
            approx(x["observed_rate"], x["gamma"], f"{x.where()} observed rate", rel=0.05)
    for a, b in zip(mod, mod[1:]):
        approx(b["leapfrog_efolds_window"] / a["leapfrog_efolds_window"], 2, "e-folds per doubling of n", rel=0.01)
    for x in g:
        if x["fixed_end"] in ("clamped", "mirror"):
            check(x["gamma"] == 0 and x["asymmetry"] < 1e-9, f"{x.where()}: {x['fixed_end']} loop not symmetric/stable")
        if x["fixed_end"] == "eta":
            check(8.0e3 <= x["gamma"] <= 8.7e3 and x["mu_im"] != 0 and 0.09 < x["leapfrog_efolds_window"] < 0.12,
                  f"{x.where()}: eta gamma {x['gamma']:.3g}")
    efolds = "/".join(f"{x['leapfrog_efolds_window']:.3g}" for x in mod)
    return f"modified gamma dx/c = {mod[0]['gamma_dx_over_c']:.4g} at n = 300/600/1200; e-folds {efolds}"


def claim_wcc_is_ill_conditioned_and_every_closure_grows(r):
    """W_CC of the 5 constrained ghosts: cond2 = 212.5 and gain 4.85 at every n; positive definite for 1-7 layers,
    indefinite from 8 on; the closed loop grows with any number of constrained layers (1-11)."""
    w = r.csv("wcc_conditioning.csv")
    for x in select(w, study_set=1):
        approx(x["cond2"], 212.5, f"{x.where()} cond2", rel=1e-3)
        approx(x["closure_gain_inf"], 4.846, f"{x.where()} gain", rel=1e-3)
        check(x["layers"] == 5, f"{x.where()}: study set of {x['layers']} ghosts")
    check(len(select(w, study_set=1)) == 3, "study set not at three resolutions")
    for x in select(w, n=300):
        check((x["eig_min"] > 0) == (x["layers"] < 8), f"{x.where()}: eig_min {x['eig_min']:.3g} at {x['layers']}")
    layers = r.csv("closure_layers.csv")
    check([x["layers"] for x in layers] == list(range(1, 12)) and all(x["gamma"] > 0 and x["unstable_modes"] > 0
                                                                     for x in layers), "a stable closure")
    five = one(layers, layers=5)
    approx(five["gamma"], one(r.csv("closure_growth.csv"), fixed_end="modified", n=300)["gamma"],
           f"{five.where()} 5 layers = the study's closure", rel=1e-9)
    return "cond2 212.5, gain 4.85; indefinite from 8 layers; 11/11 closures grow"
