"""Direct check by sparse shift-invert (SuperLU on L - sigma K, ARPACK): the eigenvalues of (L, K) nearest sigma,
with sigma = 1.5 x the DST grid estimate (above lambda_max, so the nearest are the largest)."""
import sys, time, numpy as np, scipy.sparse.linalg as sla
from lattice import operators, DSTPrec
for n in map(int, sys.argv[1:]):
    K, L = operators(n)
    sigma = 1.5 * DSTPrec(n, 0).grid_max
    t = time.time()
    w = sla.eigsh(L.tocsc(), k=6, M=K.tocsc(), sigma=sigma, which='LM', return_eigenvectors=False, tol=1e-14)
    w = np.sort(w)[::-1]
    print(f'n={n}: shift-invert sigma={sigma:.6g}: top lambda {w} -> e_crit = {1 / w[0]:.14e} ({time.time() - t:.1f}s)')
