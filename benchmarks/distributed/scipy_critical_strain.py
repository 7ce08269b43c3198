#!/usr/bin/env python3
"""Critical pre-strain of the 2D benchmark lattice by SciPy, from the matrices `sphstab jacobian elastic` exports.

e_crit = 1 / lambda_max of L x = lambda K x with K = A0 (positive definite), L = -A1 (stability/critical_load.hpp,
Criterion::Definiteness), solved as petsc_critical_load's default, with SciPy's ARPACK (`eigsh`) and SuperLU
(`splu`) in place of SLEPc and MUMPS:
  1. estimate theta of lambda_max with eigsh(L, M=K, which='LA', tol=1e-4) (K^-1 by one splu of K). A Ritz value is a
     Rayleigh quotient, so theta <= lambda_max, and ARPACK's tolerance bounds lambda_max - theta by about 1e-4 theta;
  2. shift-invert eigsh(L, M=K, sigma, which='LM') about sigma = theta (1 + 1e-2 4^k), k = 0, 1, ...: with sigma above
     lambda_max the eigenvalue nearest sigma is lambda_max. SuperLU's LU gives no inertia (PETSc's route checks it with
     MUMPS LDL^T), so the bound of step 1 stands in for it; a value found above sigma raises k.
Prints one CSV row in the columns of benchmarks/distributed/critical_strain_petsc.sh (route scipy, ranks 1).

Usage: scipy_critical_strain.py SPHSTAB_BINARY N WORKDIR
"""
import os
import resource
import subprocess
import sys
import time

import numpy as np
import scipy
import scipy.io
import scipy.sparse as sp
import scipy.sparse.linalg as sla


def cpu_seconds():
    self_ = resource.getrusage(resource.RUSAGE_SELF)
    return self_.ru_utime + self_.ru_stime


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: scipy_critical_strain.py SPHSTAB_BINARY N WORKDIR")
    binary, n, work = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    if n < 2:
        sys.exit("scipy_critical_strain: N must be >= 2, got %d" % n)
    t0 = time.perf_counter()
    os.makedirs(work, exist_ok=True)
    # Export: the sphstab process's time is counted in build_s (the CPU of a child is not in RUSAGE_SELF).
    export = subprocess.run([binary, "jacobian", "elastic", "--dim", "2", "--n", str(n), "--out", work],
                            capture_output=True, text=True)
    if export.returncode != 0:
        sys.exit("scipy_critical_strain: export failed: " + export.stderr.strip().splitlines()[-1])
    child = resource.getrusage(resource.RUSAGE_CHILDREN)
    export_cpu = child.ru_utime + child.ru_stime
    t_read = time.perf_counter()
    K = sp.csc_matrix(scipy.io.mmread(os.path.join(work, "A0.mtx")))
    L = sp.csc_matrix(-scipy.io.mmread(os.path.join(work, "A1.mtx")))
    t_solve = time.perf_counter()

    # 1. Estimate: the largest eigenvalue of K^-1 L (a lower bound, within about 1e-4).
    K_lu = sla.splu(K, permc_spec="MMD_AT_PLUS_A")
    estimate_solves = {"solves": 0}

    def k_solve(v, c=estimate_solves):
        c["solves"] += 1
        return K_lu.solve(v)

    Kinv = sla.LinearOperator(K.shape, matvec=k_solve, dtype=float)
    theta = sla.eigsh(L, k=1, M=K, Minv=Kinv, which="LA", tol=1e-4, return_eigenvectors=False)[0]
    iterations, solves = 1, estimate_solves["solves"]
    if not theta > 0:
        sys.exit("scipy_critical_strain: the estimate of lambda_max is %g <= 0: no critical strain" % theta)
    # 2. Shift-invert about sigma > lambda_max: the eigenvalue nearest sigma is then lambda_max.
    lam, x, status, reason = np.nan, None, "numerical-issue", ""
    for k in range(6):
        sigma = theta * (1 + 1e-2 * 4**k)
        A_lu = sla.splu(sp.csc_matrix(L - sigma * K), permc_spec="MMD_AT_PLUS_A")
        counter = {"solves": 0}

        def op(v, lu=A_lu, c=counter):
            c["solves"] += 1
            return lu.solve(v)

        OPinv = sla.LinearOperator(K.shape, matvec=op, dtype=float)
        vals, vecs = sla.eigsh(L, k=1, M=K, sigma=sigma, which="LM", OPinv=OPinv, tol=1e-10)
        iterations += 1
        solves += counter["solves"]
        if vals[0] < sigma:
            lam, x = vals[0], vecs[:, 0]
            status = "successful"
            break
        reason = "eigenvalue above the shift; shift raised"
    if status == "successful":
        residual = np.linalg.norm(L @ x - lam * (K @ x)) / (abs(lam) * np.linalg.norm(K @ x))
        if residual > 1e-6:
            status, reason = "numerical-issue", "residual %.3g > 1e-6" % residual
    else:
        residual = float("nan")
    t_end = time.perf_counter()
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    cpu = cpu_seconds() + export_cpu
    e = 1.0 / lam if status == "successful" else float("nan")
    method = "eigsh shift-invert+splu(scipy %s)" % scipy.__version__
    print("scipy,%s,1,%d,%d,%.15g,%s,%d,%d,%.3g,%.4g,%.4g,%.4g,%.4g,%.4g,%.5g,%.5g,\"%s\"" % (
        method, n, K.shape[0], e, status, iterations, solves, residual, t_read - t0, t_solve - t_read,
        t_end - t_solve, t_end - t0, cpu, rss, rss, reason))


if __name__ == "__main__":
    main()
