#!/usr/bin/python3
"""Issue 13's SciPy comparison of the large-lattice critical strain: per n, in the same run, (a) the matrix-free block
LOBPCG (benchmarks/lattice_lobpcg_benchmark, 1 thread, the report's main-row options: block 4, tol 1e-8, margin 0.02,
--measure), (b) `sphstab jacobian elastic` exports A0, A1 of the same case (benchmarks/strain_lattice.hpp: square
lattice, cubic, h = 1.3 dx, conservative, isotropic pre-strain, lambda = 1.2115..., mu = 0.8077...), (c) SciPy's
`eigsh` in shift-invert mode on them, in a child process with OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = 1:
  K = (A0 + A0^T)/2, L = -(A1 + A1^T)/2; lambda_max of L x = lambda K x by
  eigsh(L, k=1, M=K, sigma=sigma, which='LM', mode='normal') without OPinv, so eigsh factorises L - sigma K itself with
  SuperLU (scipy.sparse.linalg.splu, default options: COLAMD, partial pivoting); e_crit = 1/lambda_max. Timed
  (time.perf_counter): that one call, i.e. factorisation + ARPACK iterations (the Matrix Market read is timed apart).
  sigma = lambda_LOBPCG (1 + 1e-3): the eigenvalue nearest sigma is the largest if sigma lies above it. The result
  does not rest on that choice; it is certified by Sylvester's law of inertia: the number of eigenvalues above a shift
  s is the number of positive pivots of an LDL^T of L - s K, here a SuperLU factorisation with a symmetric permutation
  and no row pivoting (SymmetricMode, diag_pivot_thresh = 0, MMD_AT_PLUS_A; checked perm_r = perm_c). None above
  lambda_eigsh (1 + 1e-9) and at least one above lambda_eigsh (1 - 1e-9) put lambda_max within 1e-9 of lambda_eigsh
  (the second count is the multiplicity: 2 here, the square lattice's x <-> y symmetry). If the first count is not 0,
  sigma was below lambda_max: it is raised to lambda_LOBPCG (1 + 1e-2), then (1 + 1e-1). The two certificate
  factorisations are timed apart (certificate_s) and not in the eigsh time.
Peak memory of eigsh: getrusage(RUSAGE_SELF).ru_maxrss of the child right after the eigsh call (peak RSS of the whole
Python process so far: interpreter, the matrices read and symmetrised, eigsh's LU; eigsh_loaded_rss_MB is the same
before the solve, certificate_peak_rss_MB after the certificates; tracemalloc does not see SuperLU's C allocations:
0.003 MB traced for a 116 MB LU at n = 64). The parent kills a child above --max-rss (default 8 GB, polled from /proc
each 0.5 s) or --limit seconds (default 1800 for the whole child: read, eigsh, certificates; a row with status
memory-limit / timeout, or uncertified with the eigsh values if the kill came during the certificate), and stops at
the first size that fails.
Writes OUTDIR/scipy_eigsh.csv; `benchmarks/lattice_lobpcg_report.py ... --summary-only` renders it into summary.md.

/usr/bin/python3 benchmarks/scipy_eigsh_compare.py build/bin results/critical-strain-large [--sizes 32,64,128,256]
    [--limit 1800] [--max-rss 8192]
"""
import csv
import io
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

SIZES = [32, 64, 128, 256]
LAMBDA, MU = "1.2115384615384615", "0.8076923076923077"  # benchmarks/strain_lattice.hpp (rho drops out of the pencil)
SHIFT_MARGINS = (1e-3, 1e-2, 1e-1)  # sigma = lambda_LOBPCG (1 + margin); the next one if eigsh's value is not the top
BRACKET = 1e-9  # certificate: no eigenvalue above lambda_eigsh (1 + BRACKET), m >= 1 above lambda_eigsh (1 - BRACKET)
FIELDS = ["n", "dofs", "status", "e_crit_lobpcg", "e_crit_eigsh", "rel_diff", "lobpcg_total_s", "lobpcg_solve_s",
          "lobpcg_cpu_s", "lobpcg_peak_rss_MB", "lobpcg_iterations", "export_s", "read_s", "eigsh_s", "ratio_lobpcg_eigsh",
          "eigsh_peak_rss_MB", "eigsh_loaded_rss_MB", "sigma_over_lambda_lobpcg", "eigs_above_upper",
          "eigs_above_lower", "certificate_s", "certificate_peak_rss_MB", "residual", "asymmetry_A0", "asymmetry_A1",
          "lu_nnz_certificate", "scipy", "numpy", "blas", "threads_env", "cpu", "commit", "load_before", "reason"]


def rss_mb(pid):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return 0.0


def blas_name():
    """The BLAS behind Debian's libblas.so.3 alternative (SciPy and SuperLU link it)."""
    try:
        target = os.path.realpath("/usr/lib/x86_64-linux-gnu/libblas.so.3")
    except OSError:
        return "?"
    return "openblas" if "openblas" in target else "blis" if "blis" in target else \
        "reference" if "/blas/" in target else os.path.basename(os.path.dirname(target))


def case(work, lam_estimate):
    """Child: the eigsh solve on WORK/A0.mtx, A1.mtx; prints one JSON line."""
    import numpy as np
    import scipy
    import scipy.io
    import scipy.sparse as sp
    import scipy.sparse.linalg as sla

    out = {"scipy": scipy.__version__, "numpy": np.__version__}
    t0 = time.perf_counter()
    A0 = sp.csc_matrix(scipy.io.mmread(os.path.join(work, "A0.mtx")))
    A1 = sp.csc_matrix(scipy.io.mmread(os.path.join(work, "A1.mtx")))
    out["read_s"] = time.perf_counter() - t0
    out["asymmetry_A0"] = abs(A0 - A0.T).max() / abs(A0).max()
    out["asymmetry_A1"] = abs(A1 - A1.T).max() / abs(A1).max()
    K = sp.csc_matrix((A0 + A0.T) * 0.5)
    L = sp.csc_matrix((A1 + A1.T) * -0.5)
    del A0, A1
    out["dofs"] = K.shape[0]
    out["eigsh_loaded_rss_MB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0

    def above(shift):
        """How many eigenvalues of L x = lambda K x lie above shift: the positive pivots of an LDL^T of L - shift K
        (SuperLU with a symmetric permutation and no row pivoting); None if SuperLU still permuted rows."""
        lu = sla.splu(sp.csc_matrix(L - shift * K), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                      options=dict(SymmetricMode=True))
        out["lu_nnz_certificate"] = lu.L.nnz + lu.U.nnz
        if not (lu.perm_r == lu.perm_c).all():
            return None
        return int((lu.U.diagonal() >= 0).sum())

    cert_s = 0.0
    out["status"], out["reason"] = "numerical-issue", "no shift above lambda_max found"
    for margin in SHIFT_MARGINS:
        sigma = lam_estimate * (1 + margin)
        out["sigma_over_lambda_lobpcg"] = 1 + margin
        t = time.perf_counter()
        vals, vecs = sla.eigsh(L, k=1, M=K, sigma=sigma, which="LM", mode="normal")
        out["eigsh_s"] = time.perf_counter() - t
        out["eigsh_peak_rss_MB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
        lam, x = float(vals[0]), vecs[:, 0]
        out["residual"] = float(np.linalg.norm(L @ x - lam * (K @ x)) / (abs(lam) * np.linalg.norm(K @ x)))
        out["e_crit_eigsh"] = 1.0 / lam
        if not lam < sigma:  # an eigenvalue above sigma: sigma was below lambda_max
            continue
        print(json.dumps(dict(out, status="uncertified", reason="killed during the certificate")), flush=True)
        t = time.perf_counter()
        out["eigs_above_upper"] = above(lam * (1 + BRACKET))
        cert_s += time.perf_counter() - t
        if out["eigs_above_upper"] != 0:  # None (no inertia) or an eigenvalue above lam: not the top one
            out["reason"] = f"{out['eigs_above_upper']} eigenvalues above lambda_eigsh (1 + {BRACKET:g})"
            if out["eigs_above_upper"] is None:
                break
            continue
        t = time.perf_counter()
        out["eigs_above_lower"] = above(lam * (1 - BRACKET))
        cert_s += time.perf_counter() - t
        if not out["eigs_above_lower"]:
            out["reason"] = f"{out['eigs_above_lower']} eigenvalues above lambda_eigsh (1 - {BRACKET:g})"
        elif out["residual"] > 1e-8:
            out["reason"] = f"residual {out['residual']:.3g} > 1e-8"
        else:
            out["status"], out["reason"] = "successful", ""
        break
    out["certificate_s"] = cert_s
    out["certificate_peak_rss_MB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(json.dumps(out), flush=True)


def run_child(args, env, limit, max_rss):
    """Runs args under nice, polling its RSS; returns (returncode or 'timeout'/'memory-limit', stdout, stderr, peak)."""
    p = subprocess.Popen(["nice"] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    t0, peak = time.time(), 0.0
    while p.poll() is None:
        peak = max(peak, rss_mb(p.pid))
        if peak > max_rss or time.time() - t0 > limit:
            p.kill()
            out, err = p.communicate()  # a line printed before the kill (eigsh done, certificate not) is kept
            return ("memory-limit" if peak > max_rss else "timeout"), out, err, peak
        time.sleep(0.5)
    out, err = p.communicate()
    return p.returncode, out, err, peak


def compare(bindir, n, limit, max_rss):
    bench, cli = os.path.join(bindir, "lattice_lobpcg_benchmark"), os.path.join(bindir, "sphstab")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    row = {"n": n, "blas": blas_name(), "load_before": open("/proc/loadavg").read().split()[0],
           "cpu": next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?"),
           "commit": subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True,
                                    text=True).stdout.strip()}
    # (a) LOBPCG, as lattice_lobpcg_report.py's main rows at 1 thread.
    header = subprocess.run([bench, "--header"], capture_output=True, text=True, check=True).stdout
    p = subprocess.run(["nice", "timeout", "900", bench, str(n), "--threads", "1", "--measure"], capture_output=True,
                       text=True)
    b = next(csv.DictReader(io.StringIO(header + p.stdout))) if p.returncode == 0 and p.stdout.strip() else None
    if not b or b["status"] != "successful":
        row.update(status="lobpcg-failed", reason=(p.stderr.strip().splitlines() or [""])[-1])
        return row
    row.update(dofs=b["dofs"], e_crit_lobpcg=b["e_crit"], lobpcg_total_s=b["total_s"], lobpcg_solve_s=b["solve_s"],
               lobpcg_cpu_s=b["cpu_s"], lobpcg_peak_rss_MB=b["peak_rss_MB"], lobpcg_iterations=b["iterations"])
    with tempfile.TemporaryDirectory(prefix=f"scipy_eigsh_{n}_") as work:
        # (b) the exported matrices of the same case.
        t = time.perf_counter()
        e = subprocess.run(["nice", cli, "jacobian", "elastic", "--out", work, "--dim", "2", "--lattice", "square",
                            "--n", str(n), "--kernel", "cubic", "--h", "1.3", "--form", "conservative",
                            "--prestrain", "isotropic", "--lambda", LAMBDA, "--mu", MU],
                           capture_output=True, text=True)
        row["export_s"] = f"{time.perf_counter() - t:.3f}"
        if e.returncode != 0:
            row.update(status="export-failed", reason=(e.stderr.strip().splitlines() or [""])[-1])
            return row
        # (c) eigsh in its own process (its own peak RSS), single-threaded BLAS.
        env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
        row["threads_env"] = "OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1"
        rc, out, err, peak = run_child([sys.executable, os.path.abspath(__file__), "--case", work,
                                        repr(1.0 / float(b["e_crit"]))], env, limit, max_rss)
    lines = [l for l in out.splitlines() if l.startswith("{")]
    if rc != 0 and not lines:
        row.update(status=rc if isinstance(rc, str) else "failed", eigsh_peak_rss_MB=f"{peak:.0f}",
                   reason=f"killed above {limit:g} s" if rc == "timeout" else f"killed above {max_rss:g} MB RSS"
                   if rc == "memory-limit" else (err.strip().splitlines() or [""])[-1])
        return row
    c = json.loads(lines[-1])
    if rc != 0:
        c["reason"] = f"certificate killed above {limit:g} s" if rc == "timeout" else \
            f"certificate killed above {max_rss:g} MB RSS" if rc == "memory-limit" else f"certificate failed ({rc})"
    for k in FIELDS:
        if k in c and k not in row:
            row[k] = c[k]
    if c["status"] in ("successful", "uncertified"):
        el, es = float(b["e_crit"]), c["e_crit_eigsh"]
        row["rel_diff"] = abs(el - es) / es
        row["ratio_lobpcg_eigsh"] = float(b["total_s"]) / c["eigsh_s"]
        if row["rel_diff"] > 1e-8:
            row.update(status="disagree", reason=f"relative difference {row['rel_diff']:.3g} > 1e-8")
    return row


def fmt(key, v):
    if isinstance(v, float):
        return f"{v:.15g}" if key.startswith("e_crit") else f"{v:.4g}"
    return v


def main(argv):
    if len(argv) >= 3 and argv[0] == "--case":
        return case(argv[1], float(argv[2]))
    try:
        import scipy  # noqa: F401
    except ImportError:
        sys.exit("scipy_eigsh_compare: SciPy is missing (Debian: apt-get install python3-scipy)")
    opts = {"--sizes": ",".join(map(str, SIZES)), "--limit": "1800", "--max-rss": "8192"}
    pos = []
    i = 0
    while i < len(argv):
        if argv[i] in opts and i + 1 < len(argv):
            opts[argv[i]] = argv[i + 1]
            i += 2
        else:
            pos.append(argv[i])
            i += 1
    if len(pos) != 2:
        sys.exit(__doc__)
    bindir, outdir = pos
    os.makedirs(outdir, exist_ok=True)
    rows = []
    for n in (int(s) for s in opts["--sizes"].split(",")):
        r = compare(bindir, n, float(opts["--limit"]), float(opts["--max-rss"]))
        rows.append(r)
        print(f"n={n}: {r['status']} e_crit LOBPCG {r.get('e_crit_lobpcg', '-')} eigsh {r.get('e_crit_eigsh', '-')} "
              f"rel diff {r.get('rel_diff', '-')} LOBPCG {r.get('lobpcg_total_s', '-')} s eigsh {r.get('eigsh_s', '-')} s "
              f"peak {r.get('eigsh_peak_rss_MB', '-')} MB {r.get('reason', '')}", flush=True)
        if r["status"] != "successful":
            break
    with open(os.path.join(outdir, "scipy_eigsh.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow({k: fmt(k, r.get(k, "")) for k in FIELDS})
    print(f"wrote {outdir}/scipy_eigsh.csv")
    return 0 if all(r["status"] == "successful" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
