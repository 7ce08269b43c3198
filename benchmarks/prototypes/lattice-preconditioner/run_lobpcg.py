"""LOBPCG for lambda_max of (L, K) with several preconditioners; iterations / products / time / error vs n."""
import sys, time, argparse, numpy as np
from lattice import operators, FFTPrec, DSTPrec
from solvers import Counted, lobpcg, zone_boundary_start
from common import REF
ap = argparse.ArgumentParser()
ap.add_argument('--n', type=int, nargs='+', default=[32, 64])
ap.add_argument('--prec', default='dst')       # dst | fft | dstK | fftK | exactK | none
ap.add_argument('--pad', type=int, default=0)
ap.add_argument('--margin', type=float, default=0.1)
ap.add_argument('--b', type=int, default=4)
ap.add_argument('--tol', type=float, default=1e-7)
ap.add_argument('--maxit', type=int, default=3000)
ap.add_argument('--random', action='store_true')
ap.add_argument('--log', type=int, default=0)
a = ap.parse_args()
for n in a.n:
    t = time.perf_counter()
    Km, Lm = operators(n)
    tb = time.perf_counter() - t
    t = time.perf_counter()
    if a.prec == 'dst': P = DSTPrec(n, a.pad, margin=a.margin)
    elif a.prec == 'fft': P = FFTPrec(n, a.pad, margin=a.margin)
    elif a.prec == 'dstK': P = DSTPrec(n, a.pad, sigma_p=None)
    elif a.prec == 'fftK': P = FFTPrec(n, a.pad, sigma_p=None)
    elif a.prec == 'exactK':
        import scipy.sparse.linalg as sla
        lu = sla.splu(Km.tocsc())
        P = lambda X: lu.solve(X)
    else: P = lambda X: X
    tp = time.perf_counter() - t
    K, L, T = Counted(Km, 'K'), Counted(Lm, 'L'), Counted(P, 'T')
    X0 = np.random.default_rng(1).standard_normal((2 * n * n, a.b)) if a.random else zone_boundary_start(n, a.b)
    r = lobpcg(K, L, T, X0, maxit=a.maxit, tol=a.tol, ref=REF.get(n), verbose=a.log > 0, log_every=a.log)
    err = abs(r['e'] - REF[n]) / REF[n] if n in REF else float('nan')
    if n in REF:
        h = [(it, abs(1 / th - REF[n]) / REF[n], res) for it, th, res in r['hist']]
        for tgt in (1e-6, 1e-8, 1e-10):
            f = next((x for x in h if x[1] < tgt and all(y[1] < tgt for y in h if y[0] >= x[0])), None)
            if f: print(f'    rel.err < {tgt:g} from it {f[0]} (residual then {f[2]:.1e})')
    sp = getattr(P, 'sigma_p', 0) * REF.get(n, np.nan)
    print(f"n={n} prec={a.prec} pad={a.pad} margin={a.margin} b={a.b}: it={r['it']} e_crit={r['e']:.14e} rel.err={err:.2e} "
          f"res={r['res']:.1e} K/L products={K.count}/{L.count} T applies={T.count} time={r['time']:.2f}s "
          f"(K {K.time:.2f}s, L {L.time:.2f}s, T {T.time:.2f}s; build {tb:.1f}s, prec setup {tp:.2f}s) sigma_p/lam1={sp:.3f}", flush=True)
