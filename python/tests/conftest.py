"""Shared helpers of the Python tests: the CLI (SPHSTAB_CLI, set by ctest) and its CSV output."""
import csv
import io
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs `sphstab ARGS...`; returns (returncode, stdout, stderr)."""
    path = os.environ.get("SPHSTAB_CLI")
    if not path or not os.path.exists(path):
        pytest.fail("SPHSTAB_CLI must name the sphstab program (ctest sets it)")

    def run(*args):
        p = subprocess.run([path, *map(str, args)], capture_output=True, text=True,
                           env={**os.environ, "OMP_NUM_THREADS": "1"})
        return p.returncode, p.stdout, p.stderr
    return run


def csv_rows(text):
    return list(csv.DictReader(io.StringIO(text)))


def cli_error(stderr):
    """The library's message in the CLI's one error line."""
    lines = stderr.strip().splitlines()
    assert len(lines) == 1, stderr
    prefix = "sphstab: error: "
    assert lines[0].startswith(prefix), stderr
    return lines[0][len(prefix):]
