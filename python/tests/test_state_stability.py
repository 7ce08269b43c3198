"""The stability of a state given as arrays: the same spectrum and verdict as the lattice built in C++ (the CLI's
`spectrum`), a moving state, and bad arrays that raise one-line errors instead of crashing."""
import numpy as np
import scipy.io
import pytest

import sphstab
from conftest import csv_rows

E, NU, RHO0, DX = 2.1, 0.3, 7.8, 0.01


def lattice_state(dim, n, h_over_dx, xi, kernel="cubic"):
    """The CLI's `spectrum` lattice (fixed layers one support thick) at volume strain xi, as arrays."""
    h = h_over_dx * DX
    p = sphstab.lattice("line" if dim == 1 else "square", n, spacing=DX,
                        support_radius=sphstab.Kernel(kernel, dim).support_radius(h))
    rho = RHO0 / xi
    return dict(x=p.x, density=np.full(len(p), rho), mass=rho * p.volume, h=h, fixed=p.fixed, spacing=DX)


@pytest.mark.parametrize("dim,n,h,xi,integrator", [(2, 8, 1.3, 1.02, "pc"), (2, 8, 1.2, 0.98, "leapfrog"),
                                                   (1, 30, 1.5, 1.03, "pc")])
def test_state_from_arrays_gives_the_spectrum_and_verdict_of_the_lattice_built_in_cpp(cli, dim, n, h, xi, integrator):
    dt, t_end = 0.002, 20.0  # below the step limits (h / c_p ~ 0.02): the map grows only where J does
    rc, out, err = cli("spectrum", "--dim", dim, "--n", n, "--h", h, "--xi", xi, "--dx", DX, "--youngs", E,
                       "--poisson", NU, "--density", RHO0, "--integrator", integrator, "--dt", dt, "--t-end", t_end)
    assert rc == 0, err
    (row,) = csv_rows(out)
    s = sphstab.state_stability(**lattice_state(dim, n, h, xi), youngs=E, poisson=NU, rho0=RHO0,
                                integrator=integrator, dt=float(row["dt"]), floor=float(row["floor"]))
    v = s.verdict
    assert v.status == "successful", v.reason
    assert s.at_rest and s.free == (n if dim == 1 else n * n)
    # The masses pass through m / rho0 * rho0 (a rounding of the last bit), so the rates agree to rounding.
    gamma = float(row["growth_rate"])
    assert abs(v.semi_discrete_growth - gamma) <= 1e-9 * max(abs(gamma), 1e-9 * abs(v.lambda_max))
    assert abs(v.map_growth - float(row["map_growth"])) <= 1e-9 * abs(v.lambda_max)
    assert v.letter == row["verdict"]
    if gamma > 1e-6 * v.lambda_max:  # an unstable lattice: the mode's wavevector is the CLI's
        m = s.semi_discrete_mode
        assert m["shape"].shape == (s.free, dim)
        assert abs(m["kx_over_pi"] - float(row["mode_kx_over_pi"])) < 1e-6
        if dim == 2:
            assert abs(m["ky_over_pi"] - float(row["mode_ky_over_pi"])) < 1e-6
    ts = s.time_step
    assert ts.status == "successful" and ts.leapfrog > 0


def test_a_moving_state_is_linearised_where_it_is():
    st = lattice_state(2, 6, 1.3, 1.0)
    rng = np.random.default_rng(7)
    free = ~st["fixed"]
    v = np.zeros_like(st["x"])
    v[free] = 1e-3 * rng.standard_normal((free.sum(), 2))
    # A state another code could have produced: moved particles, a density field that is not uniform.
    moved = {**st, "x": st["x"].copy(), "density": st["density"] * (1 + 1e-3 * rng.standard_normal(len(free)))}
    moved["x"][free] += 1e-3 * DX * rng.standard_normal((free.sum(), 2))
    s = sphstab.state_stability(**moved, v=v, youngs=E, poisson=NU, rho0=RHO0, dt=0.002, t_end=10.0)
    assert s.verdict.status == "successful", s.verdict.reason
    assert not s.at_rest
    assert s.verdict.map_route in ("closed-form", "stepper")
    assert s.time_step.status == "not-computed" and "rest" in s.time_step.reason
    assert s.acceleration_max > 0  # a moving state is not an equilibrium: said, not hidden
    # At rest the same lattice at xi = 1 is an equilibrium to rounding.
    r = sphstab.state_stability(**st, youngs=E, poisson=NU, rho0=RHO0, dt=0.002, t_end=10.0)
    assert r.acceleration_max < 1e-9 * s.acceleration_max


def test_bad_arrays_raise_one_line_errors():
    st = lattice_state(2, 4, 1.3, 1.0)
    common = dict(youngs=E, poisson=NU, rho0=RHO0, dt=0.002, t_end=10.0)

    def check(match, **change):
        args = {**st, **common, **change}
        with pytest.raises(ValueError, match=match) as e:
            sphstab.state_stability(**args)
        assert "\n" not in str(e.value)

    n = len(st["density"])
    check("density must be", density=st["density"][:-1])
    check("mass must be", mass=np.ones(n + 1))
    check("v must be", v=np.zeros((n, 3)))
    x = st["x"].copy()
    x[3, 1] = np.nan
    check("position of particle 3 is not finite", x=x)
    check("h must be finite and > 0", h=-1.0)
    mass = st["mass"].copy()
    mass[2] = -1.0
    check("mass of particle 2 must be finite and > 0", mass=mass)
    x = st["x"].copy()
    x[5] = x[4]
    check("particles 4 and 5 coincide", x=x)
    v = np.zeros_like(st["x"])
    v[np.flatnonzero(st["fixed"])[0]] = 1.0
    check("fixed particle .* has a velocity", v=v)
    check("every particle is fixed", fixed=np.ones(n, dtype=bool))
    check("dt must be", dt=0.0)
    check("unknown integrator", integrator="euler")
    check("unknown kernel", kernel="nope")
    check("Poisson|poisson|nu", poisson=0.7)
    with pytest.raises(ValueError, match="2-D|columns"):
        sphstab.state_stability(**{**st, **common, "x": np.zeros((n, 3))})


def test_modes_are_written_for_paraview_and_the_file_reads_back_as_the_same_state(tmp_path):
    st = lattice_state(2, 6, 1.3, 1.02)
    common = dict(youngs=E, poisson=NU, rho0=RHO0, dt=0.002, t_end=20.0)
    s = sphstab.state_stability(**st, **common)
    path = tmp_path / "modes.vtp"
    sphstab.write_modes_vtk(path, s, st["x"], st["density"], st["mass"], st["h"], fixed=st["fixed"])
    back = sphstab.read_particle_state(str(path), h=st["h"], spacing=DX)
    assert np.array_equal(back["x"], st["x"]) and np.array_equal(back["mass"], st["mass"])
    assert back["fixed"] == list(st["fixed"])
    again = sphstab.state_stability(**back, **common)
    assert again.verdict.semi_discrete_growth == s.verdict.semi_discrete_growth
    assert again.verdict.letter == s.verdict.letter
    text = path.read_text()
    assert 'Name="semi_discrete_mode"' in text and 'Name="map_mode"' in text
    with pytest.raises(ValueError, match=".csv or .vtp"):
        sphstab.read_particle_state(str(tmp_path / "state.txt"), h=0.013)


def test_jacobian_at_a_state_equals_the_cli_export(cli, tmp_path):
    rc, _, err = cli("jacobian", "rate-form", "--n", 6, "--xi", 1.02, "--dx", DX, "--youngs", E, "--poisson", NU,
                     "--density", RHO0, "--out", tmp_path)
    assert rc == 0, err
    ref = scipy.io.mmread(str(tmp_path / "J.mtx")).tocsr()
    ref.sort_indices()
    j, y, offsets = sphstab.rate_form_jacobian(**lattice_state(2, 6, 1.3, 1.02), youngs=E, poisson=NU, rho0=RHO0)
    assert j.shape == ref.shape and offsets.shape == (len(lattice_state(2, 6, 1.3, 1.02)["density"]), 4)
    assert np.array_equal(j.indptr, ref.indptr) and np.array_equal(j.indices, ref.indices)
    # The masses pass through m / rho0 * rho0 (the last bit): equal to rounding.
    assert np.max(np.abs(j.data - ref.data)) <= 1e-12 * np.max(np.abs(ref.data))
    assert np.max(np.abs(j.data)) > 0


@pytest.mark.parametrize("n,xi", [(12, 1.02), (12, 0.98)])
def test_symbol_over_the_box_wavevectors_gives_the_periodic_spectrum(cli, n, xi):
    # Two routes to the growth of a periodic square lattice: the exact Bloch symbol at the box's n x n wavevectors
    # (max over k), and the reduced full-state spectrum of `sphstab spectrum --periodic`.
    m = np.arange(n)
    k = 2 * np.pi * np.array([(a, b) for a in m for b in m], dtype=float) / (n * DX)
    d = sphstab.rate_form_dispersion(k, lattice="square", n=n, h=1.3, dx=DX, xi=xi, youngs=E, poisson=NU, rho0=RHO0)
    rc, out, err = cli("spectrum", "--periodic", "--n", n, "--h", 1.3, "--xi", xi, "--dx", DX, "--youngs", E,
                       "--poisson", NU, "--density", RHO0)
    assert rc == 0, err
    (row,) = csv_rows(out)
    gamma = float(row["growth_rate"])
    omega = np.sqrt(np.max(np.abs(d["omega2"])))
    assert d["growth_rate"].shape == (n * n,) and d["omega2"].shape == (n * n, 2)
    if gamma > 1e-6 * omega:  # unstable: the fastest Bloch wave is the spectrum's growth rate
        assert abs(np.max(d["growth_rate"]) - gamma) <= 1e-8 * gamma
    else:  # neutral: every branch has omega^2 >= 0 to rounding
        assert np.min(d["omega2"].real) >= -1e-9 * np.max(np.abs(d["omega2"]))
    with pytest.raises(ValueError, match="columns"):
        sphstab.rate_form_dispersion(np.zeros((3, 3)), n=n, youngs=E, poisson=NU, rho0=RHO0)
