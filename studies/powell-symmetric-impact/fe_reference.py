"""Finite-element reference of Powell's symmetric impact [Powell2012, ch. 4 §4.1]: the block [0, L] x [0, H] of
../common/impact_fe.py (DOLFINx Q1, lumped mass, velocity Verlet; linear or Saint Venant-Kirchhoff) with v_y = -v0
above the mid-plane and +v0 below it (0 on it).

Usage from plot.py: fe_run(n, v0, t_end, points_a, snap_points, snap_times, model, cfl, collocated_dx).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
import impact_fe  # noqa: E402


def fe_run(n, v0, t_end, points_a, snap_points=None, snap_times=(), model="linear", cfl=0.5, collocated_dx=None,
           length=1.0, height=1.0, record_dt=None):
    """One run on an n x n mesh (impact_fe.fe_run). collocated_dx: Powell's mesh instead, nodes at the particles,
    [dx/2, L - dx/2]^2 with n elements."""
    lo = np.array([0.0, 0.0]) if collocated_dx is None else np.array([collocated_dx / 2] * 2)
    hi = np.array([length, height]) - lo
    mid = 0.5 * (lo[1] + hi[1])

    def velocity(X):
        w = np.zeros_like(X)
        w[:, 1] = np.where(X[:, 1] > mid, -v0, v0)
        return w
    return impact_fe.fe_run(n, n, t_end, velocity, points_a, lo, hi, snap_points, snap_times, model=model, cfl=cfl,
                            record_dt=record_dt)
