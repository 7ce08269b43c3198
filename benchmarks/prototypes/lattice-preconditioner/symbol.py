"""The 2x2 Fourier symbols K_hat(k), L_hat(k) of the extracted stencils and the periodic pencil's top eigenvalue."""
import numpy as np, os
from common import HERE, CASE

def stencils(n=64):
    st = np.load(os.path.join(HERE, f'stencil_{CASE}{n}.npy'), allow_pickle=True).item()
    return st['A0'], {o: -B for o, B in st['A1'].items()}   # K = A0, L = -A1

def symbol(st, kx, ky):
    """sum_d S(d) exp(i k.d), kx/ky arrays (same shape) -> (..., 2, 2) complex."""
    out = np.zeros(np.broadcast(kx, ky).shape + (2, 2), complex)
    for (di, dj), B in st.items():
        out += np.exp(1j * (kx * di + ky * dj))[..., None, None] * B
    return out

def top_pencil(Lh, Kh):
    # generalised eigenvalues of 2x2 Hermitian pencils (Lh, Kh), Kh > 0
    Ki = np.linalg.inv(Kh)
    w = np.linalg.eigvals(Ki @ Lh).real
    return np.sort(w, axis=-1)

if __name__ == '__main__':
    K, L = stencils()
    for name, st in (('K', K), ('L', L)):
        s = symbol(st, np.array(0.3), np.array(0.7))
        print(name, 'imag part of symbol max', abs(s.imag).max())
    for k in [(0, 0), (np.pi, 0), (0, np.pi), (np.pi, np.pi), (np.pi / 2, 0), (np.pi, np.pi / 2)]:
        Kh = symbol(K, np.array(k[0]), np.array(k[1])).real; Lh = symbol(L, np.array(k[0]), np.array(k[1])).real
        print('k/pi =', np.array(k) / np.pi, 'eig K_hat', np.linalg.eigvalsh(Kh), 'eig L_hat', np.linalg.eigvalsh(Lh))
    # behaviour of K_hat near (pi, 0)
    for q in [1e-1, 1e-2, 1e-3]:
        for d in [(1, 0), (0, 1), (1, 1)]:
            Kh = symbol(K, np.array(np.pi + q * d[0]), np.array(q * d[1])).real
            Lh = symbol(L, np.array(np.pi + q * d[0]), np.array(q * d[1])).real
            print(f'q={q:g} dir={d}: eig K_hat {np.linalg.eigvalsh(Kh)}, eig K^-1 L {top_pencil(Lh, Kh)}')
    # the periodic torus: N x N with odd N, grid k = 2 pi m / N
    for N in [33, 65, 129, 257]:
        k = 2 * np.pi * np.arange(N) / N
        KX, KY = np.meshgrid(k, k, indexing='ij')
        w = top_pencil(symbol(L, KX, KY).real, symbol(K, KX, KY).real)
        top = np.sort(w[..., 1].ravel())[::-1]
        print(f'torus N={N}: lambda_per max {top[0]:.6g}, next {top[1:6]}, min eig of pencil {w.min():.4g}')
