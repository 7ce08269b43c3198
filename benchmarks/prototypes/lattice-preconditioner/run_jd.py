"""Jacobi-Davidson for lambda_max of (L, K) with the DST preconditioner in the correction equation:
   (I - K x x^T)(theta K - L)(I - x x^T K) t = r,  t _|_K x,   r = L x - theta K x,
solved by m steps of MINRES with the projected preconditioner M~ = M - M y y^T M / (y^T M y), y = K x, M = T.
Subspace V (K-orthonormal), Rayleigh-Ritz each outer step, thick restart to the best `keep` Ritz vectors."""
import argparse, time, numpy as np, scipy.linalg as sl, scipy.sparse.linalg as sla
from lattice import operators, DSTPrec
from solvers import Counted, zone_boundary_start, _korth, _kproject
from common import REF

ap = argparse.ArgumentParser()
ap.add_argument('--n', type=int, nargs='+', default=[32, 64])
ap.add_argument('--m', type=int, default=10)
ap.add_argument('--margin', type=float, default=0.1)
ap.add_argument('--tol', type=float, default=1e-7)
ap.add_argument('--maxit', type=int, default=300)
ap.add_argument('--vmax', type=int, default=24)
ap.add_argument('--keep', type=int, default=6)
ap.add_argument('--start', type=int, default=4)
ap.add_argument('--nexp', type=int, default=1)   # corrections per outer step (block JD)
a = ap.parse_args()

for n in a.n:
    Km, Lm = operators(n)
    P = DSTPrec(n, 0, margin=a.margin)
    K, L, T = Counted(Km, 'K'), Counted(Lm, 'L'), Counted(P, 'T')
    nA = [0]; inner_total = 0
    t0 = time.perf_counter()
    V = zone_boundary_start(n, a.start)
    KV, LV = K(V), L(V)
    V, KV, LV = _korth(V, KV, LV)
    for it in range(1, a.maxit + 1):
        H = V.T @ LV; w, C = np.linalg.eigh(0.5 * (H + H.T)); w = w[::-1]; C = C[:, ::-1]
        th = w[0]; c = C[:, 0]
        x, Kx, Lx = V @ c, KV @ c, LV @ c
        r = Lx - th * Kx
        res = np.linalg.norm(r) / (abs(th) * np.linalg.norm(Kx))
        if res < a.tol: break
        N = Km.shape[0]
        ts = []
        for q in range(min(a.nexp, V.shape[1])):
            thq = w[q]; cq = C[:, q]
            xq, Kxq, Lxq = V @ cq, KV @ cq, LV @ cq
            rq = Lxq - thq * Kxq
            Am = (thq * Km - Lm).tocsr()
            My = T(Kxq); yMy = Kxq @ My
            def op(v, xq=xq, Kxq=Kxq, Am=Am):
                nA[0] += 1
                v = v - xq * (Kxq @ v)
                u = Am @ v
                return u - Kxq * (xq @ u)
            def prec(v, My=My, yMy=yMy, Kxq=Kxq):
                Mv = T(v)
                return Mv - My * ((Kxq @ Mv) / yMy)
            t, _ = sla.minres(sla.LinearOperator((N, N), matvec=op, dtype=float), rq,
                              M=sla.LinearOperator((N, N), matvec=prec, dtype=float), maxiter=a.m, tol=1e-14)
            inner_total += a.m
            ts.append(t)
        if V.shape[1] >= a.vmax:   # thick restart
            Ck = C[:, :a.keep]
            V, KV, LV = V @ Ck, KV @ Ck, LV @ Ck
        t = np.column_stack(ts)
        Kt, Lt = K(t), L(t)
        t, Kt, Lt = _kproject(t, Kt, Lt, V, KV, LV)
        t, Kt, Lt = _korth(t, Kt, Lt)
        V, KV, LV = np.hstack([V, t]), np.hstack([KV, Kt]), np.hstack([LV, Lt])
    e = 1 / th
    err = abs(e - REF[n]) / REF[n] if n in REF else float('nan')
    print(f'n={n} JD m={a.m} nexp={a.nexp}: outer={it} inner(total)={inner_total} e_crit={e:.14e} rel.err={err:.2e} res={res:.1e} '
          f'A(theta) applies={nA[0]} K/L products={K.count}/{L.count} T applies={T.count} time={time.perf_counter() - t0:.2f}s', flush=True)
