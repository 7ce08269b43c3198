#!/usr/bin/python3
"""Runs lattice_lobpcg_benchmark --dim 3 one case per process (nice, timeout 1800 s each) and writes
results/critical-strain-3d/{results.csv, summary.md, time_vs_n.png}: the critical strain of n x n x n cubic lattices
by the matrix-free block LOBPCG with the 3D lattice sine-transform preconditioner (issue 13: 100^3 particles; issue
35: 100^3 in < 60 s and < 2 GB). The cases take the default storage (auto: G, H by lattice offset); STORAGE reruns
cases with the values per pair (--storage per-pair), in the same run, for the ratio of the two storages.

/usr/bin/python3 benchmarks/lattice_lobpcg_3d_report.py build/bin/lattice_lobpcg_benchmark results/critical-strain-3d
(--summary-only: rewrite summary.md and the plot from an existing results.csv; --append-repeats: run the REPEATS
cases, append them to results.csv with variant "repeat", then rewrite summary.md and the plot)
"""
import csv
import os
import platform
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from lattice_lobpcg_report import run, slope, storage_section  # noqa: E402  (one case per process, the same CSV row)

# (n, threads, extra): the direct route in the same process up to n = 11 (3993 DOFs); timing rows on 2 threads
# for every n and on 1 thread up to n = 64.
DENSE = [8, 11]
SIZES = [16, 24, 32, 48, 64, 80, 100]
CASES = ([(n, 2, ["--dim", "3", "--direct-reference"]) for n in DENSE] + [(n, 2, ["--dim", "3"]) for n in SIZES] +
         [(n, 1, ["--dim", "3"]) for n in SIZES if n <= 64])
# Per pair at n = 32 and 64 only: at 100^3 the per-pair case alone took 337 s and 7.2 GB (the run before the by-offset
# storage, commit 8d5879e), too long to repeat beside the other agents' jobs on this machine.
STORAGE = [(n, 2, ["--dim", "3", "--storage", "per-pair"]) for n in (32, 64)]
TARGET_S, TARGET_MB = 60.0, 2048.0  # issue 35 at n = 100 (2 threads: the machine's cores)
# Repeatability of the timings on this shared machine: the n = 32 case three more times per thread count.
REPEATS = [(32, th, ["--dim", "3"]) for th in (1, 2) for _ in range(3)]


def main(binary, outdir, summary_only=False, append_repeats=False):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    os.makedirs(outdir, exist_ok=True)
    path = os.path.join(outdir, "results.csv")
    if summary_only or append_repeats:
        rows = list(csv.DictReader(open(path)))
        if append_repeats:
            for n, th, extra in REPEATS:
                r = run(binary, n, th, extra, timeout=1800)
                r["variant"] = "repeat"
                rows.append(r)
    if not summary_only:
        if not append_repeats:
            rows = [run(binary, n, th, extra, timeout=1800) for n, th, extra in CASES + STORAGE]
        fields = ["variant"] + [k for k in rows[0] if k != "variant"]
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            for r in rows:
                w.writerow({k: r.get(k, "") for k in fields})
    ok = [r for r in rows if r["status"] == "successful"]
    timing = {(int(r["n"]), int(r["threads"])): r for r in ok
              if "--direct-reference" not in r["variant"] and r["variant"] != "repeat" and "--storage" not in r["variant"]}
    fits = {}
    for th in (1, 2):
        pts = [timing[(n, th)] for n in SIZES if n >= 24 and (n, th) in timing]
        if len(pts) >= 2:
            x = [int(p["dofs"]) for p in pts]
            fits[th] = {c: slope(x, [float(p[c]) for p in pts]) for c in ("solve_s", "total_s", "peak_rss_MB")}
            fits[th]["range"] = f"n = {pts[0]['n']}-{pts[-1]['n']}"
    commit = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    machine = None  # --summary-only: the measurements' machine line, not the machine that re-renders the text
    old = os.path.join(outdir, "summary.md")
    if summary_only and os.path.exists(old):
        machine = next((l.rstrip("\n") for l in open(old, encoding="utf-8") if l.startswith("**Machine**")), None)

    def f(x, fmt="{:.3g}"):
        return fmt.format(float(x)) if x not in ("", None, "nan") else "-"

    L = ["# Critical strain of cubic lattices (3D): matrix-free block LOBPCG with a 3D sine-transform preconditioner",
         "",
         "Issue 13 asks for a 3D cubic-lattice linear-elastic critical strain at 100^3 particles, with its time and "
         "memory. This is it, on this 2-core machine, on **2 threads of one process** (not 2 MPI ranks: see Reading).",
         "",
         "**Case** (`lattice_lobpcg_benchmark --dim 3`): n x n x n free particles of a cubic lattice (spacing 1) "
         "plus 3 fixed layers on every side (the kernel support, 2h = 2.6 dx), cubic spline, h = 1.3 dx, "
         "conservative form, isotropic 3D pre-strain e (pre-stress (3 lambda + 2 mu) e I), lambda = 1.2115, mu = "
         "0.8077, rho = 7.8 (the 2D study's constants, now as 3D Lame constants). Quantity: e_crit = 1/lambda_max "
         "of L x = lambda K x, K = A0, L = -A1 (`MatrixFreeLinearisation<3>`, jacobian/matrix_free_linearisation.hpp; "
         "G and H kept once per lattice offset and applied as lattice loops, storage by-offset, the default on these "
         "perfect lattices; the section Storage reruns cases with the values per neighbour pair).",
         "",
         "**Method** (`matrix_free_critical_load`, `BlockLobpcg`, as results/critical-strain-large): block size 4, "
         "zone-boundary start (x-, y- and z-polarised modes with sine envelopes, 10 % noise), stop at "
         "||L x - theta K x|| <= 1e-8 |theta| ||K x||; preconditioner `LatticeSinePreconditioner<3>`: per "
         "displacement component a 3D DST-I (fields two at a time as one complex field, lines as FFTW complex DFTs of "
         "their odd extension, FFTW_MEASURE) with the diagonal of the 3 x 3 symbol of the "
         "interior stencil (stencil radius 4: 9^3 offsets, probed from the operator, 6 products), sigma_p = 1.02 x "
         "the symbol maximum. Below n = 11 the stencil is probed on an 11^3 lattice. **Reference**: the engine's direct "
         "route in the same process for n = 8 and 11 (the linearisation assembled by products with unit vectors, "
         "`assemble_by_products`, then `critical_load`'s eigen route: CHOLMOD and shifted Spectra on 1536 / 3993 "
         "DOFs).",
         "",
         machine or (f"**Machine**: {cpu}, {os.cpu_count()} cores shared, {platform.system()} {platform.release()}; "
                     f"load average (1 min) before each case {min(float(r['load_before']) for r in rows):.2f}-"
                     f"{max(float(r['load_before']) for r in rows):.2f}; OMP_WAIT_POLICY "
                     f"{os.environ.get('OMP_WAIT_POLICY', 'unset')} (passive: waiting threads sleep instead of spinning, "
                     f"which on a loaded machine keeps a descheduled thread from stalling its partner). Build: Release, "
                     f"g++ -O3 (no -march). "
                     f"Commit {commit}."),
         "",
         "## Results",
         "",
         "| n | DOFs | threads | e_crit | direct reference | rel. diff. | steps | residual | sigma_p e_crit | "
         "linearisation s | solve s (products / T / dense) | total s | peak RSS MB | linearisation MB | probe dev. |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["variant"] == "repeat" or "--storage" in r["variant"]:
            continue
        if r["status"] != "successful":
            L.append(f"| {r['n']} | - | {r['threads']} | {r['status']}: {r.get('reason', '')} |" + " |" * 11)
            continue
        L.append(f"| {r['n']} | {r['dofs']} | {r['threads']} | {float(r['e_crit']):.14e} | "
                 f"{f(r['direct_reference_e_crit'], '{:.14e}')} | {f(r['rel_diff_reference'])} | {r['iterations']} | "
                 f"{f(r['residual'])} | {f(r['sigma_p_over_lambda'])} | {f(r['linearisation_s'])} | {f(r['solve_s'])} "
                 f"({f(r['solve_products_s'])} / {f(r['solve_preconditioner_s'])} / {f(r['solve_dense_s'])}) | "
                 f"{f(r['total_s'])} | {f(r['peak_rss_MB'], '{:.0f}')} | {f(r['linearisation_MB'], '{:.0f}')} | "
                 f"{f(r['probe_deviation'])} |")
    main_rows = {(int(r["n"]), int(r["threads"])): r for r in ok if r["variant"] == "--dim 3"}
    L += [""] + storage_section([dict(r, variant=r["variant"].replace("--dim 3 ", "")) for r in rows], main_rows)
    L += ["", "## Reading", ""]
    dense = [r for r in ok if "--direct-reference" in r["variant"]]
    if dense:
        worst = max(float(r["rel_diff_reference"]) for r in dense)
        L.append(f"- **Agreement with the direct route**: <= {worst:.1e} relative at n = "
                 f"{', '.join(r['n'] for r in dense)} (issue 13 asks 1e-8).")
    big = timing.get((100, 2))
    if big:
        met = float(big["total_s"]) < TARGET_S and float(big["peak_rss_MB"]) < TARGET_MB
        parts = (("products", float(big["solve_products_s"])), ("the DST preconditioner",
                 float(big["solve_preconditioner_s"])), ("the dense block algebra", float(big["solve_dense_s"])))
        L.append(f"- **100^3 free particles** ({int(big['dofs']):,} DOFs, {100 + 6}^3 particles with the fixed layers), "
                 f"2 threads, issue 35's target (60 s, 2 GB) **{'met' if met else 'NOT met'}**: total "
                 f"{float(big['total_s']):.0f} s (solve {float(big['solve_s']):.0f} s: products "
                 f"{float(big['solve_products_s']):.0f} s, DST preconditioner {float(big['solve_preconditioner_s']):.0f} "
                 f"s, dense block algebra {float(big['solve_dense_s']):.0f} s; neighbour search "
                 f"{float(big['lattice_s']):.0f} s, linearisation {float(big['linearisation_s']):.0f} s), peak RSS "
                 f"{float(big['peak_rss_MB']) / 1024:.2f} GB (the linearisation {float(big['linearisation_MB']):.0f} MB), "
                 f"{big['iterations']} block steps, e_crit = {float(big['e_crit']):.6e}; load average "
                 f"{big['load_before']} before the case. The largest share of the solve: "
                 f"{max(parts, key=lambda p: p[1])[0]}.")
    # the default cases (by offset, not the per-pair or repeat rows): the steps of the table above
    its = [int(r["iterations"]) for r in ok if int(r["n"]) >= 16 and r["variant"] == "--dim 3"]
    if its:
        L.append(f"- **Steps independent of n**: {min(its)}-{max(its)} block steps for n = 16-100 (2D: 36-40).")
    for th, fit in fits.items():
        L.append(f"- **Cost exponents** ({th} thread(s), least squares of log value on log DOFs, {fit['range']}): "
                 f"solve N^{fit['solve_s']:.2f}, total N^{fit['total_s']:.2f}, peak memory "
                 f"N^{fit['peak_rss_MB']:.2f}.")
    for th in (1, 2):
        rep = [float(r["total_s"]) for r in ok if int(r["n"]) == 32 and int(r["threads"]) == th
               and "--storage" not in r["variant"]]
        if len(rep) >= 2:
            L.append(f"- **Repeatability** (n = 32, {th} thread(s), {len(rep)} runs of the same case in this run): total "
                     f"{min(rep):.1f}-{max(rep):.1f} s (max/min {max(rep) / min(rep):.2f}); the machine is a shared "
                     f"virtual machine, so single timings (and the thread speed-ups below) carry this spread.")
    for n in SIZES:
        a, b = timing.get((n, 1)), timing.get((n, 2))
        if a and b and n == max(m for m in SIZES if (m, 1) in timing and (m, 2) in timing):
            L.append(f"- **Threads**: 1 -> 2 threads at n = {n}: total {float(a['total_s']):.1f} s -> "
                     f"{float(b['total_s']):.1f} s (speed-up {float(a['total_s']) / float(b['total_s']):.2f}); the same "
                     f"e_crit bits: {'yes' if a['e_crit'] == b['e_crit'] else 'no'}.")
    # Memory from the measurements: the linearisation's own storage per free particle at the largest n, by offset
    # (the default rows) and per pair (the Storage rows), and the largest n whose peak stayed within issue 35's 2 GB.
    big_n = max(n for (n, th) in timing)
    big_row = max((r for (n, th), r in timing.items() if n == big_n), key=lambda r: float(r["peak_rss_MB"]))
    per_pair = [r for r in ok if r["variant"] == "--dim 3 --storage per-pair" and int(r["n"]) == big_n]
    lin_b = float(big_row["linearisation_MB"]) * 1e6 / big_n ** 3
    within = [n for (n, th), r in timing.items() if float(r["peak_rss_MB"]) <= TARGET_MB]
    text = (f"- **Memory per free particle** at n = {big_n}: the linearisation by offset holds {lin_b:.0f} bytes (the "
            f"grids of x and sigma, 9 values per site of the free box padded by 2 r = 4, and the free positions)")
    if per_pair:
        pp = per_pair[0]
        text += (f", per pair {float(pp['linearisation_MB']) * 1e3 / big_n ** 3:.2f} kB (G on every pair and H on the "
                 f"free rows, 81 pairs per particle at h = 1.3 dx): "
                 f"{float(pp['linearisation_MB']) / float(big_row['linearisation_MB']):.0f}x less")
    text += (f". The peak RSS by offset, {float(big_row['peak_rss_MB']):.0f} MB, is mostly outside the linearisation "
             f"(the particle set and neighbour list it is built from, and the block LOBPCG's vectors). The largest n "
             f"within 2 GB: {max(within) if within else '-'}^3 free particles.")
    L.append(text)
    L.append("- **Why not on 2 MPI ranks**: the distributed route (distributed/petsc_critical_load.hpp) factorises "
             "L - sigma K with MUMPS. In 3D, nested dissection gives factor fill ~N^(4/3) and work ~N^2: at 3e6 DOFs "
             "the top separator alone is a dense 3e4 x 3e4 front (7 GB), far beyond this machine (docs/scaling.md). "
             "The matrix-free route is shared-memory only (threads); a distributed version needs a distributed "
             "sine transform (FFTW's MPI interface) and halo exchange of the operator rows: not done.")
    L.append("- **sigma_p e_crit** (the preconditioner's shift over the true lambda_max) falls from about 2.3 at n = 8 "
             "to about 1.1 at n = 64: the symbol maximum on the DST grid over-estimates lambda_max of small blocks, "
             "whose critical modes are bent by the fixed layers; the step count does not depend on it.")
    L.append("")
    L.append("![time and memory against DOFs](time_vs_n.png)")
    L.append("")
    with open(os.path.join(outdir, "summary.md"), "w") as fh:
        fh.write("\n".join(L))

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no plot", file=sys.stderr)
        return
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for th, mk in ((1, "s-"), (2, "o-")):
        pts = sorted((int(r["dofs"]), r) for (n, t), r in timing.items() if t == th)
        if not pts:
            continue
        x = [p[0] for p in pts]
        ax[0].loglog(x, [float(p[1]["total_s"]) for p in pts], mk, label=f"total, {th} thread(s)")
        ax[1].loglog(x, [float(p[1]["peak_rss_MB"]) / 1024 for p in pts], mk, label=f"peak RSS, {th} thread(s)")
    for a, lab in ((ax[0], "wall time (s)"), (ax[1], "memory (GB)")):
        a.set_xlabel("DOFs (3 per free particle)")
        a.set_ylabel(lab)
        a.grid(True, which="both", alpha=0.3)
        a.legend()
    fig.suptitle("3D cubic lattice critical strain, matrix-free block LOBPCG + 3D DST preconditioner")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "time_vs_n.png"), dpi=120)


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a not in ("--summary-only", "--append-repeats")]
    if len(args) != 2:
        sys.exit(__doc__)
    main(args[0], args[1], "--summary-only" in sys.argv, "--append-repeats" in sys.argv)
