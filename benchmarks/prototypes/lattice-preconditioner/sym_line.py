import numpy as np
from symbol import stencils, symbol, top_pencil
K, L = stencils()
N = 33
k = 2 * np.pi * np.arange(N) / N
kx = k[16]  # nearest pi
print('kx/pi', kx / np.pi)
KY = k
w = top_pencil(symbol(L, np.full_like(KY, kx), KY).real, symbol(K, np.full_like(KY, kx), KY).real)
for j in range(0, N, 2):
    Kh = symbol(K, np.array(kx), np.array(KY[j])).real; Lh = symbol(L, np.array(kx), np.array(KY[j])).real
    print(f'ky/pi={KY[j]/np.pi:.3f} lam_top={w[j,1]:.8g} lam2={w[j,0]:.6g} Kh={Kh.ravel()} Lh={Lh.ravel()}')
