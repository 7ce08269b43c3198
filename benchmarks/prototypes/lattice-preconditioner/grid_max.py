import numpy as np
from lattice import FFTPrec, DSTPrec
lam1 = {16: 1 / 1.53095124159266e-03, 32: 1 / 5.75187135005991e-04, 64: 1 / 1.50721497909830e-04,
        128: 1 / 3.8532198124872e-05, 256: 1 / 9.73848094883822e-06}
for n in [16, 32, 64, 128, 256]:
    s = f'n={n} lam1={lam1[n]:.6g}: grid max / lam1:'
    for pad in [0, 1, 2, 4, 8]:
        s += f' pad{pad}: fft {FFTPrec(n, pad).grid_max / lam1[n]:.3f} dst {DSTPrec(n, pad).grid_max / lam1[n]:.3f};'
    print(s)
