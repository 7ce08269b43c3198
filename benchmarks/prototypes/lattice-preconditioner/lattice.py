"""The n x n lattice operators K = A0, L = -A1 rebuilt from the translation-invariant stencil (exact: stencil.py),
and FFT / DST preconditioners from the 2x2 Fourier symbol.

Vector layout: dof = 2 (i + n j) + c (i along x, j along y, c component), as sphstab's dofs.csv; as an array
u.reshape(n, n, 2) indexed [j, i, c]."""
import numpy as np, scipy.sparse as sp, scipy.fft as sfft, os
from symbol import stencils, symbol

KST, LST = stencils(64)

def build(st, n):
    idx = np.arange(n * n).reshape(n, n)  # [j, i]
    rows, cols, vals = [], [], []
    for (di, dj), B in st.items():
        jj, ii = np.meshgrid(np.arange(n), np.arange(n), indexing='ij')
        i2, j2 = ii + di, jj + dj
        ok = (i2 >= 0) & (i2 < n) & (j2 >= 0) & (j2 < n)
        p = idx[jj[ok], ii[ok]]; q = idx[j2[ok], i2[ok]]
        for c in range(2):
            for d in range(2):
                if B[c, d] != 0.0:
                    rows.append(2 * p + c); cols.append(2 * q + d); vals.append(np.full(p.size, B[c, d]))
    M = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(2 * n * n,) * 2)
    M.sort_indices()
    return M

def operators(n):
    return build(KST, n), build(LST, n)

def symbols(kx, ky):
    return symbol(KST, kx, ky).real, symbol(LST, kx, ky).real

def pencil_top(Kh, Lh):
    """Largest generalised eigenvalue of the 2x2 pencils (Lh, Kh) (Kh > 0)."""
    a, b, c = Kh[..., 0, 0], Kh[..., 0, 1], Kh[..., 1, 1]
    p, q, r = Lh[..., 0, 0], Lh[..., 0, 1], Lh[..., 1, 1]
    # det(L - t K) = 0: (a c - b^2) t^2 - (a r + c p - 2 b q) t + (p r - q^2) = 0
    A = a * c - b * b; B = -(a * r + c * p - 2 * b * q); C = p * r - q * q
    disc = np.sqrt(np.maximum(B * B - 4 * A * C, 0))
    return (-B + disc) / (2 * A)

class FFTPrec:
    """T = R (sigma_p K_per - L_per)^{-1} R^T on an M x M torus, M = n + 2 pad, by complex FFT.
    twist=True: anti-periodic grid k = pi (2m + 1)/M (avoids k = 0 and pi); False: periodic k = 2 pi m / M.
    sigma_p=None: plain K_per^{-1} (needs a grid free of K_hat zeros).  sigma_p='auto': (1 + margin) x grid max."""
    def __init__(self, n, pad=0, sigma_p='auto', margin=0.02, twist=True, M=None):
        self.n = n; self.M = M = (n + 2 * pad) if M is None else M; self.pad = (M - n) // 2
        m = np.arange(M)
        k = np.pi * (2 * m + 1) / M if twist else 2 * np.pi * m / M
        KX, KY = np.meshgrid(k, k, indexing='xy')   # [j, i]: KY varies with j, KX with i
        Kh, Lh = symbols(KX, KY)
        self.grid_max = pencil_top(Kh, Lh).max()
        if sigma_p is None:
            P = Kh; self.sigma_p = 0.0
        else:
            self.sigma_p = (1 + margin) * self.grid_max if sigma_p == 'auto' else sigma_p
            P = self.sigma_p * Kh - Lh
        ev = np.linalg.eigvalsh(P)
        self.min_eig = ev.min()
        self.Pinv = np.linalg.inv(P)          # [j, i, 2, 2]
        self.twist = twist
        jj, ii = np.meshgrid(m, m, indexing='ij')
        self.ph = np.exp(-1j * np.pi * (ii + jj) / M) if twist else None

    def __call__(self, X):
        X = np.asarray(X); one = X.ndim == 1
        if one: X = X[:, None]
        n, M, p = self.n, self.M, self.pad
        b = X.shape[1]
        U = np.zeros((b, M, M, 2))
        U[:, p:p + n, p:p + n, :] = X.T.reshape(b, n, n, 2)
        if self.twist:
            U = U * self.ph[None, :, :, None]
        F = sfft.fft2(U, axes=(1, 2), workers=1)
        F = np.einsum('jkcd,bjkd->bjkc', self.Pinv, F)
        V = sfft.ifft2(F, axes=(1, 2), workers=1)
        if self.twist:
            V = V * np.conj(self.ph)[None, :, :, None]
        Y = V.real[:, p:p + n, p:p + n, :].reshape(b, -1).T
        return Y[:, 0] if one else Y

class DSTPrec:
    """T = R tau(sigma_p K - L)^{-1} R^T with DST-I on an M x M grid (k = pi m/(M+1)), components decoupled:
    the xy block of the symbol is odd-odd and has no DST-I representation, so it is dropped (block-diagonal)."""
    def __init__(self, n, pad=0, sigma_p='auto', margin=0.02, keep_xy=False):
        self.n = n; self.M = M = n + 2 * pad; self.pad = pad
        k = np.pi * np.arange(1, M + 1) / (M + 1)
        KX, KY = np.meshgrid(k, k, indexing='xy')
        Kh, Lh = symbols(KX, KY)
        Kd = Kh.copy(); Ld = Lh.copy()
        Kd[..., 0, 1] = Kd[..., 1, 0] = 0; Ld[..., 0, 1] = Ld[..., 1, 0] = 0
        self.grid_max = pencil_top(Kd, Ld).max()
        if sigma_p is None:
            P = Kd; self.sigma_p = 0.0
        else:
            self.sigma_p = (1 + margin) * self.grid_max if sigma_p == 'auto' else sigma_p
            P = self.sigma_p * Kd - Ld
        self.min_eig = np.linalg.eigvalsh(P).min()
        self.d = 1.0 / np.stack([P[..., 0, 0], P[..., 1, 1]], axis=-1)   # [j, i, c]

    def __call__(self, X):
        X = np.asarray(X); one = X.ndim == 1
        if one: X = X[:, None]
        n, M, p = self.n, self.M, self.pad
        b = X.shape[1]
        U = np.zeros((b, M, M, 2))
        U[:, p:p + n, p:p + n, :] = X.T.reshape(b, n, n, 2)
        F = sfft.dstn(U, type=1, axes=(1, 2), norm='ortho', workers=1) * self.d[None]
        V = sfft.idstn(F, type=1, axes=(1, 2), norm='ortho', workers=1)
        Y = V[:, p:p + n, p:p + n, :].reshape(b, -1).T
        return Y[:, 0] if one else Y
