"""Shared helpers: load exported sphstab matrices (Matrix Market -> cached .npz)."""
import os, numpy as np, scipy.sparse as sp

HERE = os.path.dirname(os.path.abspath(__file__))
# SPHSTAB_CASE selects the exported case: 'n' (default: isotropic, mats/n<N>) or e.g. 'uni' (uniaxial, mats/uni<N>).
CASE = os.environ.get('SPHSTAB_CASE', 'n')
# Direct-solver e_crit of the isotropic case (128, 256: given; 16-64: dense eigh, dense_top.py).
REF = {16: 1.53095124159266e-03, 32: 5.75187135005991e-04, 64: 1.50721497909830e-04,
       128: 3.8532198124872e-05, 256: 9.73848094883822e-06} if CASE == 'n' else \
      {32: 8.22940583548557e-04, 64: 2.15865585985583e-04, 128: 5.51860826814964e-05} if CASE == 'uni' else {}
# (uniaxial: 32 dense eigh, 64 and 128 sparse shift-invert, direct_si.py)

def _read_mtx(path):
    with open(path) as f:
        while True:
            line = f.readline()
            if not line.startswith('%'):
                break
        m, n, nnz = map(int, line.split())
        data = np.loadtxt(f, dtype=np.float64)
    return sp.csr_matrix((data[:, 2], (data[:, 0].astype(np.int64) - 1, data[:, 1].astype(np.int64) - 1)), shape=(m, n))

def load(n):
    d = os.path.join(HERE, 'mats', f'{CASE}{n}')
    cache = os.path.join(d, 'mats.npz')
    if os.path.exists(cache):
        z = np.load(cache)
        A0 = sp.csr_matrix((z['a0d'], z['a0i'], z['a0p']), shape=tuple(z['shape']))
        A1 = sp.csr_matrix((z['a1d'], z['a1i'], z['a1p']), shape=tuple(z['shape']))
        return A0, A1, z['xy']
    A0 = _read_mtx(os.path.join(d, 'A0.mtx')); A1 = _read_mtx(os.path.join(d, 'A1.mtx'))
    dofs = np.loadtxt(os.path.join(d, 'dofs.csv'), delimiter=',', skiprows=1, usecols=(3, 4))
    xy = dofs[::2]
    np.savez(cache, a0d=A0.data, a0i=A0.indices, a0p=A0.indptr, a1d=A1.data, a1i=A1.indices, a1p=A1.indptr,
             shape=np.array(A0.shape), xy=xy)
    return A0, A1, xy
