"""Which DST-I modes carry the critical eigenvector (envelope index along / across the sawtooth direction)."""
import sys, numpy as np, scipy.fft as sfft
from lattice import operators, DSTPrec
from solvers import Counted, lobpcg, zone_boundary_start
for n in map(int, sys.argv[1:]):
    Km, Lm = operators(n)
    X0 = np.random.default_rng(2).standard_normal((2 * n * n, 6))
    r = lobpcg(Counted(Km, 'K'), Counted(Lm, 'L'), Counted(DSTPrec(n, 0), 'T'), X0, tol=1e-8, nconv=4)
    print(f'n={n}: top Ritz lambda/lambda1 = {r["theta"][:6] / r["lam"]}')
    for q in range(4):
        U = r['X'][:, q].reshape(n, n, 2)
        F = sfft.dstn(U, type=1, axes=(0, 1), norm='ortho')   # F[b, a, c]: b = y index-1, a = x index-1
        E = (F ** 2); E /= E.sum()
        top = np.argsort(E.ravel())[::-1][:4]
        desc = []
        for t in top:
            bj, ai, c = np.unravel_index(t, E.shape)
            desc.append(f"{'xy'[c]}-pol (a={ai + 1}, b={bj + 1}) {E.ravel()[t]:.3f}")
        print(f'   mode {q}: lambda/lambda1={r["theta"][q] / r["lam"]:.6f}; largest DST-I energy shares: ' + '; '.join(desc))
