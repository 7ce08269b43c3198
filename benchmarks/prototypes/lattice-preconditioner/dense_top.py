"""Top of the spectrum of the pencil (L, K) by dense eigh (small n): e_crit reference and the cluster structure."""
import sys, time, numpy as np, scipy.linalg as sl
from common import load, HERE, CASE
import os
for n in map(int, sys.argv[1:]):
    A0, A1, xy = load(n)
    K = A0.toarray(); L = -A1.toarray(); N = K.shape[0]
    t = time.time()
    w, V = sl.eigh(L, K, subset_by_index=[N - 40, N - 1], driver='gvx')
    w = w[::-1]; V = V[:, ::-1]
    print(f'n={n}: e_crit = {1 / w[0]:.14e}  ({time.time() - t:.1f}s)')
    print('  top 40 lambda / lambda_max:', np.array2string(w / w[0], precision=6, max_line_width=150))
    np.savez(os.path.join(HERE, f'dense_top_{CASE}{n}.npz'), w=w, V=V[:, :12])
