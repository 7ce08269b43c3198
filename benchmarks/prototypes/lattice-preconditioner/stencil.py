"""Idea 1: is the free-free block of A0 / A1 the restriction of a translation-invariant lattice operator?
Extract the 2x2-block stencil from the central particle and compare every free row against it."""
import sys, numpy as np
from common import load, HERE, CASE
import os

def grid_index(xy):
    ij = np.rint(xy - xy.min(0)).astype(int)
    assert np.allclose(ij + xy.min(0), xy)
    return ij

def extract(M, ij, n, p):
    """Stencil {(di,dj): 2x2 block} from particle p's rows."""
    st = {}
    for c in range(2):
        r = 2 * p + c
        row = M.getrow(r)
        for col, v in zip(row.indices, row.data):
            q, d = divmod(col, 2)
            off = tuple(ij[q] - ij[p])
            st.setdefault(off, np.zeros((2, 2)))[c, d] = v
    return st

def check(M, ij, n, st):
    n_p = ij.shape[0]
    idx = -np.ones((n, n), dtype=int); idx[ij[:, 0], ij[:, 1]] = np.arange(n_p)
    # build the translation-invariant restriction as a sparse matrix and subtract
    import scipy.sparse as sp
    rows, cols, vals = [], [], []
    for (di, dj), B in st.items():
        i2 = ij[:, 0] + di; j2 = ij[:, 1] + dj
        ok = (i2 >= 0) & (i2 < n) & (j2 >= 0) & (j2 < n)
        p = np.nonzero(ok)[0]; q = idx[i2[ok], j2[ok]]
        for c in range(2):
            for d in range(2):
                rows.append(2 * p + c); cols.append(2 * q + d); vals.append(np.full(p.size, B[c, d]))
    T = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=M.shape)
    D = (M - T).tocsr(); D.eliminate_zeros()
    absd = abs(D)
    rowmax = np.asarray(absd.max(axis=1).todense()).ravel()
    pm = np.maximum(rowmax[0::2], rowmax[1::2])
    dist = np.minimum.reduce([ij[:, 0], ij[:, 1], n - 1 - ij[:, 0], n - 1 - ij[:, 1]])  # to nearest free edge
    return absd.max() if absd.nnz else 0.0, pm, dist

if __name__ == '__main__':
    for n in map(int, sys.argv[1:]):
        A0, A1, xy = load(n)
        ij = grid_index(xy)
        pc = int(np.nonzero((ij[:, 0] == n // 2) & (ij[:, 1] == n // 2))[0][0])
        out = {}
        for name, M in (('A0', A0), ('A1', A1)):
            st = extract(M, ij, n, pc)
            scale = max(abs(B).max() for B in st.values())
            mx, pm, dist = check(M, ij, n, st)
            offs = np.array(list(st.keys()))
            print(f'n={n} {name}: stencil offsets {len(st)} (|d|max={np.abs(offs).max()}, radius {np.sqrt((offs**2).sum(1)).max():.3f}), '
                  f'max|entry| {scale:.4g}, max |M - R S R^T| = {mx:.3e} (rel {mx/scale:.3e})')
            for d in range(0, 7):
                sel = dist == d
                if sel.any(): print(f'    rows at distance {d} from the free edge: max dev {pm[sel].max():.3e}')
            sel = dist >= 7
            if sel.any(): print(f'    rows at distance >=7: max dev {pm[sel].max():.3e}')
            # symmetry of stencil: S(-d) = S(d)^T, and S(d) reflections
            asym = max(abs(st[o] - st[tuple(-np.array(o))].T).max() for o in st)
            print(f'    stencil S(-d) - S(d)^T max {asym:.3e}')
            out[name] = st
        np.save(os.path.join(HERE, f'stencil_{CASE}{n}.npy'), {k: {o: B for o, B in v.items()} for k, v in out.items()}, allow_pickle=True)
