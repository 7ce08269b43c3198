#!/usr/bin/env python3
"""Speed of the Python front door against the CLI on the Fig. 3.2 sweep (critical tension of a 30-particle bar for
four kernels and h/dx = 0.80 ... 3.00, the conservative form): both call critical_tension_sweep, so the ratio is the
cost of the binding (argument conversion, result objects) plus, for the CLI, process start-up and CSV output.
Runs alternate (CLI, Python, CLI, ...) so that a busy machine slows both alike; prints the median wall time of each
and their ratio. Usage: PYTHONPATH=build/python benchmarks/python_critical_tension.py [build/bin/sphstab] [repeats]"""
import statistics
import subprocess
import sys
import time

import numpy as np

import sphstab

cli = sys.argv[1] if len(sys.argv) > 1 else "build/bin/sphstab"
repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 7
kernels = ["cubic", "quartic", "quintic", "wendland-c2"]
h = np.round(np.arange(0.80, 3.0001, 0.05), 2)
args = [cli, "tcrit", "--n", "30", "--kernel", ",".join(kernels), "--h", ",".join(f"{x:.2f}" for x in h)]
t_cli, t_py = [], []
for _ in range(repeats):
    t0 = time.perf_counter()
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    t_cli.append(time.perf_counter() - t0)
    t0 = time.perf_counter()
    cases = sphstab.critical_tension(n=30, kernels=kernels, h=h)
    t_py.append(time.perf_counter() - t0)
assert len(cases) == len(out.strip().splitlines()) - 1
m_cli, m_py = statistics.median(t_cli), statistics.median(t_py)
print(f"cases {len(cases)}, repeats {repeats}: CLI median {m_cli:.4f} s, Python median {m_py:.4f} s, "
      f"Python / CLI = {m_py / m_cli:.3f}")
