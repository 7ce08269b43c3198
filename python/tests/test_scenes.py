"""Scenes and the run loop from Python (GMS's and Powell's): the run is the CLI's `sphstab scene` run, the observer sees every record and
can stop the run, an exception in it stops the run and reaches the caller, and a scene's state goes straight into
state_stability."""
import numpy as np
import pytest

import sphstab
from conftest import csv_rows


def test_rings_run_equals_the_cli_scene(cli):
    rc, out, err = cli("scene", "rings", "--dp", 0.5, "--t-end", 3, "--record-every", 1, "--pair-loop", "pairs")
    assert rc == 0, err
    rows = [r for r in csv_rows(out) if r["status"] == ""]  # the last row is the run's status
    scene = sphstab.gms_rings_scene(spacing=0.5)
    assert scene.integrator == "pc1"  # one rate evaluation per step (results/gms-pc1), as the CLI's default
    r = sphstab.run(scene, cfl=0.5, t_end=3.0, record_every=1)
    assert r.status == "completed"
    assert len(r.times) == len(rows)
    assert np.array_equal(np.array(r.times), np.array([float(x["t"]) for x in rows]))
    # The same scene, scheme, integrator and step: the same bits (the CLI prints shortest round-trip decimals).
    assert np.array_equal(np.array(r.kinetic_energy), np.array([float(x["kinetic"]) for x in rows]))


def test_powell_bar_impact_equals_the_cli_scene(cli):
    # Powell's bar impact with basic SPH at dx = 0.1 cm, as the CLI runs it: leap-frog, XSPH (2.71) 0.1, TSSFAC 0.8.
    rc, out, err = cli("scene", "bar-impact", "--formulation", "sph", "--dp", 0.1, "--t-end", 2, "--record-every", 1)
    assert rc == 0, err
    rows = [r for r in csv_rows(out) if r["status"] == ""]
    scene = sphstab.powell_impact_scene("bar", spacing=0.1, formulation="sph", t_end=2.0)
    assert scene.name == "bar-impact" and scene.measures[0] == "length"
    r = sphstab.run(scene, cfl=0.8, integrator="leapfrog", xsph=0.1)
    assert r.status == "completed"
    assert np.array_equal(np.array(r.kinetic_energy), np.array([float(x["kinetic"]) for x in rows]))
    # and these are the scene's own defaults (integrate/scene_run.hpp), which run(scene) takes
    assert (scene.integrator, scene.leapfrog_xsph, scene.cfl) == ("leapfrog", 0.1, 0.8)
    assert np.array_equal(np.array(sphstab.run(scene).kinetic_energy), np.array(r.kinetic_energy))
    with pytest.raises(ValueError, match="clamp"):
        sphstab.powell_impact_scene("beam", spacing=0.03)
    with pytest.raises(ValueError, match="formulation"):
        sphstab.powell_impact_scene("bar", formulation="tl")
    with pytest.raises(ValueError):
        sphstab.run(scene, integrator="pc", xsph=0.1)  # Powell's XSPH belongs to the leap-frog


def test_observer_sees_every_record_and_stops_the_run():
    scene = sphstab.gms_rings_scene(spacing=0.5, inner_radius=1.0, outer_radius=2.0)
    seen = []
    r = sphstab.run(scene, cfl=0.5, t_end=5.0, record_every=2,
                    observer=lambda step, t, y: seen.append((step, t, y.size)) or ("enough" if step >= 6 else None))
    assert r.status == "stopped" and "enough" in r.message
    assert [s for s, _, _ in seen] == [0, 2, 4, 6]
    assert all(n == scene.y0.size for _, _, n in seen)

    def broken(step, t, y):
        raise RuntimeError("observer failed on purpose")
    with pytest.raises(RuntimeError, match="on purpose"):
        sphstab.run(scene, cfl=0.5, t_end=5.0, observer=broken)
    with pytest.raises(ValueError, match="observer must be callable"):
        sphstab.run(scene, observer=3)
    with pytest.raises(ValueError, match="unknown integrator"):
        sphstab.run(scene, integrator="euler")
    with pytest.raises(ValueError, match="dt or cfl"):
        sphstab.run(scene, dt=0.1, cfl=0.5)


def test_a_scene_state_goes_into_state_stability():
    # At the initial state each ring translates rigidly and is unstressed: the only force is GMS's viscosity between
    # approaching particles of the two rings (across the gap, within the support). Receding rings feel none.
    for speed, forced in ((0.059, True), (-0.059, False)):
        scene = sphstab.gms_rings_scene(spacing=0.5, inner_radius=1.0, outer_radius=2.0, speed=speed)
        state = scene.state(scene.y0)
        assert state["x"].shape == (scene.particles, 2) and not any(state["fixed"])
        assert np.allclose(np.abs(state["v"][:, 0]), abs(speed))  # each ring at |speed| c0 (c0 = 1), along +-x
        s = sphstab.state_stability(**state, **scene.material, scheme=scene.scheme_options, dt=scene.time_step(0.5),
                                    t_end=scene.t_end)
        assert s.verdict.status == "successful", s.verdict.reason
        assert not s.at_rest and s.free == scene.particles
        assert (s.acceleration_max > 1e-6) == forced, (speed, s.acceleration_max)
        if not forced:
            assert s.acceleration_max == 0.0


def test_slab_end_zones_follow_their_prescribed_acceleration():
    a = 5e-3
    scene = sphstab.gms_slab_scene(spacing=0.1, acceleration=a)
    x0 = scene.state(scene.y0)["x"]
    r = sphstab.run(scene, cfl=0.5, t_end=2.0)
    assert r.status == "completed"
    x = scene.state(r.y)["x"]
    left, right = np.argmin(x0[:, 0]), np.argmax(x0[:, 0])
    # Driven particles move as x0 + a t^2 / 2 exactly (RateFormScheme::set_driven), outwards at both ends.
    expected = 0.5 * a * r.time**2
    assert abs((x0[left, 0] - x[left, 0]) - expected) <= 1e-12 + 1e-9 * expected
    assert abs((x[right, 0] - x0[right, 0]) - expected) <= 1e-12 + 1e-9 * expected
    assert "min_width" in scene.measures
    assert 0 < scene.measure("min_width", r.y) <= 1.0 + 1e-9
