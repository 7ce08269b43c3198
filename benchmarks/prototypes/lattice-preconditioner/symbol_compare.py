"""Compare the stencil symbol with the toolkit's ElasticSymbol2D (cpp/symbol_check output)."""
import numpy as np
from lattice import symbols
d = np.loadtxt('cpp/symbol_cpp.txt')
for row in d:
    Kh, Lh = symbols(np.array(row[0]), np.array(row[1]))
    print(f'k=({row[0]:.3f},{row[1]:.3f}): max|K_stencil - a0| = {abs(Kh.ravel() - row[2:6]).max():.2e}, '
          f'max|L_stencil - (-a1)| = {abs(Lh.ravel() - row[6:10]).max():.2e} (|a0| {abs(row[2:6]).max():.3f}, |a1| {abs(row[6:10]).max():.3f})')
