"""Inexact shift-invert variants with the DST preconditioner T ~ (sigma_p K - L)^{-1}:
  rqi:      x <- MINRES_m(theta K - L, K x; M = T) (Rayleigh-quotient shift, inexact), Rayleigh-Ritz on [x_prev, x, y]
  davidson: subspace V, expansion t = MINRES_m(theta K - L, K x; M = T) (or PCG_m with shift sigma_p), RR on V
Counts: combined A(sigma) = sigma K - L applies (one matrix-free pass each), K and L products, T applies."""
import argparse, time, numpy as np, scipy.sparse.linalg as sla
from lattice import operators, DSTPrec
from solvers import Counted, zone_boundary_start, _korth
from common import REF

ap = argparse.ArgumentParser()
ap.add_argument('--n', type=int, nargs='+', default=[32, 64])
ap.add_argument('--method', default='davidson')
ap.add_argument('--inner', default='minres')    # minres (shift theta) | pcg (shift sigma_p, SPD)
ap.add_argument('--m', type=int, default=10)     # inner steps
ap.add_argument('--margin', type=float, default=0.1)
ap.add_argument('--tol', type=float, default=1e-7)
ap.add_argument('--maxit', type=int, default=300)
ap.add_argument('--restart', type=int, default=20)
a = ap.parse_args()

def pcg(Aop, b, M, m):
    x = np.zeros_like(b); r = b.copy(); z = M(r); p = z.copy(); rz = r @ z
    for _ in range(m):
        Ap = Aop(p); pAp = p @ Ap
        if pAp <= 0: break
        al = rz / pAp; x += al * p; r -= al * Ap
        z = M(r); rzn = r @ z; p = z + (rzn / rz) * p; rz = rzn
    return x

for n in a.n:
    Km, Lm = operators(n)
    P = DSTPrec(n, 0, margin=a.margin)
    K, L, T = Counted(Km, 'K'), Counted(Lm, 'L'), Counted(P, 'T')
    nA = [0]
    t0 = time.perf_counter()
    V = zone_boundary_start(n, 1)
    KV, LV = K(V), L(V)
    V, KV, LV = _korth(V, KV, LV)
    inner_total = 0
    for it in range(1, a.maxit + 1):
        H = V.T @ LV; w, C = np.linalg.eigh(0.5 * (H + H.T))
        th = w[-1]; c = C[:, -1]
        x, Kx, Lx = V @ c, KV @ c, LV @ c
        r = Lx - th * Kx
        res = np.linalg.norm(r) / (abs(th) * np.linalg.norm(Kx))
        if res < a.tol: break
        sig = th if a.inner == 'minres' else P.sigma_p
        Am = (sig * Km - Lm).tocsr()
        def Aop(v):
            nA[0] += 1; return Am @ v
        Aop_l = sla.LinearOperator(Am.shape, matvec=Aop, dtype=float)
        Mop = sla.LinearOperator(Am.shape, matvec=lambda v: T(v), dtype=float)
        if a.inner == 'minres':
            y, _ = sla.minres(Aop_l, Kx, M=Mop, maxiter=a.m, tol=1e-14)
        else:
            y = pcg(Aop, Kx, T, a.m)
        inner_total += a.m
        if a.method == 'rqi':
            Vn = np.column_stack([x, y]) if V.shape[1] >= 1 else y[:, None]
        else:
            Vn = np.column_stack([V, y]) if V.shape[1] < a.restart else np.column_stack([V @ C[:, -4:], y])
        KVn, LVn = K(Vn[:, -1:]), L(Vn[:, -1:])
        if a.method == 'rqi':
            KVn, LVn = np.column_stack([Kx, KVn]), np.column_stack([Lx, LVn])
        elif V.shape[1] < a.restart:
            KVn, LVn = np.column_stack([KV, KVn]), np.column_stack([LV, LVn])
        else:
            KVn, LVn = np.column_stack([KV @ C[:, -4:], KVn]), np.column_stack([LV @ C[:, -4:], LVn])
        V, KV, LV = _korth(Vn, KVn, LVn)
    e = 1 / th
    err = abs(e - REF[n]) / REF[n] if n in REF else float('nan')
    print(f'n={n} {a.method}/{a.inner} m={a.m}: outer={it} inner(total)={inner_total} e_crit={e:.14e} rel.err={err:.2e} res={res:.1e} '
          f'A(sigma) applies={nA[0]} K/L products={K.count}/{L.count} T applies={T.count} time={time.perf_counter() - t0:.2f}s', flush=True)
