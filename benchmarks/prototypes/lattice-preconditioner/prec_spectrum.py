"""Spectral equivalence of the FFT/DST preconditioners: eigenvalues of T (sigma K - L) (dense, small n).
A good preconditioner for the shifted operator has bounded kappa = w_max / w_min independent of n (at fixed d)."""
import sys, time, numpy as np, scipy.linalg as sl
from lattice import operators, FFTPrec, DSTPrec
lam1 = {16: 1 / 1.53095124159266e-03, 32: 1 / 5.75187135005991e-04, 64: 1 / 1.50721497909830e-04}
for n in map(int, sys.argv[1:]):
    K, L = operators(n); K = K.toarray(); L = L.toarray(); N = K.shape[0]
    l1 = lam1[n]
    precs = [('fft pad0 m0.3', FFTPrec(n, 0, margin=0.3)), ('fft pad0 m1', FFTPrec(n, 0, margin=1.0)),
             ('fft pad4 m0.3', FFTPrec(n, 4, margin=0.3)),
             ('dst pad0 m.02', DSTPrec(n, 0)), ('dst pad0 m0.1', DSTPrec(n, 0, margin=0.1)), ('dst pad0 m0.3', DSTPrec(n, 0, margin=0.3)),
             ('dst pad1 m.02', DSTPrec(n, 1)), ('dst pad0 K^-1', DSTPrec(n, 0, sigma_p=None))]
    for name, T in precs:
        t = time.time()
        Td = T(np.eye(N)); Td = 0.5 * (Td + Td.T)
        s = f'n={n} {name:14s} sigma_p/l1={T.sigma_p / l1:.3f}:'
        Tinv = np.linalg.inv(Td); Tinv = 0.5 * (Tinv + Tinv.T)
        for d in [1e-3, 1e-2, 1e-1, 1.0]:
            A = (1 + d) * l1 * K - L
            w = sl.eigh(A, Tinv, eigvals_only=True, driver='gvd')
            s += f' | d={d:g}: [{w[0]:.3g}, {w[-1]:.3g}] k={w[-1] / w[0]:.3g}'
        print(s + f' ({time.time() - t:.0f}s)', flush=True)
