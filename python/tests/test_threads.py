"""Threads and the OpenMP wait policy (core/threads.hpp): the program sets the policy itself unless the environment
chose one — the CLI by re-executing itself, the Python package before its module loads libgomp — and the thread count
is settable from Python as with the CLI's --threads."""
import os
import subprocess
import sys

import numpy as np
import pytest

import sphstab
from sphstab import _sphstab

POLICY_VARIABLES = ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")


def clean_environment(**extra):
    env = {k: v for k, v in os.environ.items() if k not in POLICY_VARIABLES}
    env.update(extra)
    return env


def cli_wait_policy(env):
    """The wait policy `sphstab --version` reports."""
    p = subprocess.run([os.environ["SPHSTAB_CLI"], "--version"], capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stderr
    assert p.stdout.startswith("sphstab "), p.stdout
    assert ", 1 thread," in p.stdout  # ctest's OMP_NUM_THREADS=1
    return p.stdout.strip().split("wait policy ")[1]


def test_cli_sets_its_wait_policy_unless_the_environment_does():
    assert cli_wait_policy(clean_environment()) == f"OMP_WAIT_POLICY={_sphstab.program_wait_policy}"
    assert cli_wait_policy(clean_environment(OMP_WAIT_POLICY="active")) == "OMP_WAIT_POLICY=active"
    assert cli_wait_policy(clean_environment(GOMP_SPINCOUNT="0")) == "GOMP_SPINCOUNT=0"


def test_package_sets_the_same_policy_before_its_module_loads():
    code = "import sphstab; print(sphstab.wait_policy())"
    env = clean_environment(PYTHONPATH=os.pathsep.join(sys.path))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True).stdout
    assert out.strip() == f"OMP_WAIT_POLICY={_sphstab.program_wait_policy}"
    env["OMP_WAIT_POLICY"] = "active"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True).stdout
    assert out.strip() == "OMP_WAIT_POLICY=active"


def test_threads_are_settable_and_results_the_same_bits():
    before = sphstab.threads()
    try:
        with pytest.raises(ValueError, match="thread count must be >= 1"):
            sphstab.set_threads(0)
        runs = []
        for t in (1, 2):
            sphstab.set_threads(t)
            assert sphstab.threads() == t
            runs.append(sphstab.run(sphstab.gms_rings_scene(spacing=0.25), t_end=2.0, record_every=1).kinetic_energy)
        sphstab.set_fixed_threads(True)
        runs.append(sphstab.run(sphstab.gms_rings_scene(spacing=0.25), t_end=2.0, record_every=1).kinetic_energy)
        sphstab.set_fixed_threads(False)
        assert len(runs[0]) > 10
        assert np.array_equal(np.array(runs[0]), np.array(runs[1]))
        assert np.array_equal(np.array(runs[0]), np.array(runs[2]))
    finally:
        sphstab.set_threads(before)
